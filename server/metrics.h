// What afmesh-server tells Prometheus (issue 12, part 6; deploy/README.md lists every series).
//
// Two kinds of numbers, each from one place:
//  - counters and the job-seconds histogram are counted once per call, when it ends, from the
//    same CallRecord its log line is written from (report_call_end in call_log.h);
//  - gauges (calls in flight, jobs queued and running, the memory budget held, ...) are read
//    from the call gate, the worker pool and the memory budget when Prometheus scrapes, so
//    nothing else in the server has to keep them up to date.
// Owned by the server (MesherServer) and passed down to the service: no global registry, so
// several servers in one process (the tests) count apart.
#pragma once

#include <string>
#include <vector>

#include "prometheus/collectable.h"
#include "prometheus/counter.h"
#include "prometheus/family.h"
#include "prometheus/histogram.h"
#include "prometheus/metric_family.h"
#include "prometheus/registry.h"
#include "server/call_gate.h"
#include "server/call_log.h"
#include "server/memory_budget.h"
#include "server/worker_pool.h"

namespace afmesh::server {

class ServerMetrics final : public prometheus::Collectable {
 public:
  // Upper bounds of the job-seconds buckets: 10 ms (a job refused by its estimate) to 10 min
  // (about 20M tets at the ~30 s per million measured in deploy/README.md), about 3x apart.
  static const std::vector<double>& job_seconds_buckets();

  // Reads its gauges from `gate`, `pool` and `budget`, which must outlive every Collect() call
  // (stop the MetricsEndpoint serving this first). Every Mesher RPC has its calls_total series
  // for the codes the service documents, at 0, from the start, so that rate() sees the first
  // call of each.
  ServerMetrics(const CallGate& gate, const WorkerPool& pool, const MemoryBudget& budget);

  // Counts a finished call: its code, bytes in and out, job seconds (when a job ran) and, when
  // it succeeded, the tets and triangles it handed out.
  void observe_call(const CallRecord& record);

  // The counters and histogram, then the gauges read now.
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  void add_rpc(const std::string& rpc);

  const CallGate& gate_;
  const WorkerPool& pool_;
  const MemoryBudget& budget_;
  prometheus::Registry registry_;
  prometheus::Family<prometheus::Counter>& calls_;
  prometheus::Family<prometheus::Counter>& received_bytes_;
  prometheus::Family<prometheus::Counter>& sent_bytes_;
  prometheus::Family<prometheus::Counter>& elements_;
  prometheus::Family<prometheus::Histogram>& job_seconds_;
};

}  // namespace afmesh::server
