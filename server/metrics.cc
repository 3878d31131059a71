#include "server/metrics.h"

#include <unistd.h>

#include <fstream>
#include <iterator>

#include "afmesh/v1/mesher.pb.h"
#include "prometheus/client_metric.h"
#include "prometheus/metric_type.h"

namespace afmesh::server {
namespace {

// The codes afmesh.v1.Mesher documents (mesher.proto), whose series exist from the start.
constexpr grpc::StatusCode kDocumentedCodes[] = {
    grpc::StatusCode::OK,
    grpc::StatusCode::INVALID_ARGUMENT,
    grpc::StatusCode::RESOURCE_EXHAUSTED,
    grpc::StatusCode::FAILED_PRECONDITION,
    grpc::StatusCode::CANCELLED,
    grpc::StatusCode::DEADLINE_EXCEEDED,
    grpc::StatusCode::UNAVAILABLE,
    grpc::StatusCode::UNAUTHENTICATED,
    grpc::StatusCode::INTERNAL,
};

// The RPCs of afmesh.v1.Mesher, from its descriptor: a new RPC gets its series without an edit
// here.
std::vector<std::string> mesher_rpcs() {
  std::vector<std::string> rpcs;
  const google::protobuf::ServiceDescriptor* service =
      v1::MeshVolumeRequest::descriptor()->file()->FindServiceByName("Mesher");
  if (service == nullptr) return rpcs;
  for (int m = 0; m < service->method_count(); ++m) rpcs.push_back(service->method(m)->name());
  return rpcs;
}

// This process's resident set in bytes (/proc/self/statm), 0 when unknown.
double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0;
  long pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0.0;
  return static_cast<double>(pages_resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

prometheus::MetricFamily gauge(std::string name, std::string help, double value) {
  prometheus::ClientMetric metric;
  metric.gauge.value = value;
  return prometheus::MetricFamily{.name = std::move(name),
                                  .help = std::move(help),
                                  .type = prometheus::MetricType::Gauge,
                                  .metric = {metric}};
}

}  // namespace

const std::vector<double>& ServerMetrics::job_seconds_buckets() {
  static const std::vector<double> buckets = {0.01, 0.03, 0.1, 0.3, 1,   3,
                                              10,   30,   60,  120, 300, 600};
  return buckets;
}

ServerMetrics::ServerMetrics(const CallGate& gate, const WorkerPool& pool,
                             const MemoryBudget& budget)
    : gate_(gate),
      pool_(pool),
      budget_(budget),
      calls_(prometheus::BuildCounter()
                 .Name("afmesh_calls_total")
                 .Help("Mesher calls ended, by RPC and gRPC status code")
                 .Register(registry_)),
      received_bytes_(prometheus::BuildCounter()
                          .Name("afmesh_received_bytes_total")
                          .Help("Serialised bytes of the request messages the server read")
                          .Register(registry_)),
      sent_bytes_(prometheus::BuildCounter()
                      .Name("afmesh_sent_bytes_total")
                      .Help("Serialised bytes of the response messages the server wrote")
                      .Register(registry_)),
      elements_(prometheus::BuildCounter()
                    .Name("afmesh_elements_produced_total")
                    .Help("Elements of the meshes handed out by calls that succeeded, by RPC and "
                          "kind (tets; triangles: the mesh's boundary)")
                    .Register(registry_)),
      job_seconds_(prometheus::BuildHistogram()
                       .Name("afmesh_job_seconds")
                       .Help("Seconds a call's job ran on a worker (repair, estimate, meshing, "
                             "validation), whatever its outcome")
                       .Register(registry_)) {
  for (const std::string& rpc : mesher_rpcs()) add_rpc(rpc);
}

void ServerMetrics::add_rpc(const std::string& rpc) {
  for (const grpc::StatusCode code : kDocumentedCodes) {
    calls_.Add({{"rpc", rpc}, {"code", code_name(code)}});
  }
  received_bytes_.Add({{"rpc", rpc}});
  sent_bytes_.Add({{"rpc", rpc}});
  elements_.Add({{"rpc", rpc}, {"kind", "tets"}});
  elements_.Add({{"rpc", rpc}, {"kind", "triangles"}});
  job_seconds_.Add({{"rpc", rpc}}, job_seconds_buckets());
}

void ServerMetrics::observe_call(const CallRecord& record) {
  calls_.Add({{"rpc", record.rpc}, {"code", code_name(record.status.error_code())}}).Increment();
  received_bytes_.Add({{"rpc", record.rpc}}).Increment(static_cast<double>(record.bytes_in));
  sent_bytes_.Add({{"rpc", record.rpc}}).Increment(static_cast<double>(record.bytes_out));
  if (record.job_seconds) {
    job_seconds_.Add({{"rpc", record.rpc}}, job_seconds_buckets()).Observe(*record.job_seconds);
  }
  if (record.status.ok()) {
    elements_.Add({{"rpc", record.rpc}, {"kind", "tets"}})
        .Increment(static_cast<double>(record.tets_out));
    elements_.Add({{"rpc", record.rpc}, {"kind", "triangles"}})
        .Increment(static_cast<double>(record.triangles_out));
  }
}

std::vector<prometheus::MetricFamily> ServerMetrics::Collect() const {
  // The gauges are read before the counters: a call is counted (observe_call) before it leaves
  // the gate, so a scrape whose afmesh_calls_in_flight no longer holds a call has that call in
  // afmesh_calls_total. Read the other way round, a call ending between the two reads was in
  // neither (MetricsTest.GaugesFollowRunningAndQueuedJobsAndTheBudgetTheyHold failed so once
  // under ASan: no calls in flight and no cancelled call counted).
  std::vector<prometheus::MetricFamily> gauges;
  const WorkerPool::Load load = pool_.load();
  const auto add = [&gauges](std::string name, std::string help, double value) {
    gauges.push_back(gauge(std::move(name), std::move(help), value));
  };
  add("afmesh_calls_in_flight",
      "Mesher calls admitted and not ended (uploading, queued, running or streaming a result)",
      gate_.active());
  add("afmesh_jobs_queued", "Jobs waiting for a worker (the queue depth)", load.queued);
  add("afmesh_jobs_running", "Jobs on a worker", load.running);
  add("afmesh_workers", "Worker threads (--workers): jobs that can run at once", pool_.workers());
  add("afmesh_call_slots_in_use",
      "Worker and queue slots held by calls; at afmesh_call_slots new calls get "
      "RESOURCE_EXHAUSTED",
      load.reserved);
  add("afmesh_call_slots", "Worker and queue slots (--workers + --max-queue)",
      pool_.workers() + pool_.max_queue());
  add("afmesh_memory_budget_reserved_bytes",
      "Bytes of the memory budget reserved by the jobs admitted now (by their estimates)",
      static_cast<double>(budget_.in_use()));
  add("afmesh_memory_budget_bytes", "The memory budget (--memory-budget-mb)",
      static_cast<double>(budget_.capacity()));
  add("afmesh_draining", "1 once the server is draining (SIGTERM): new calls get UNAVAILABLE",
      gate_.closed() ? 1.0 : 0.0);
  add("process_resident_memory_bytes", "Resident memory of the server process", resident_bytes());
  std::vector<prometheus::MetricFamily> families = registry_.Collect();
  families.insert(families.end(), std::make_move_iterator(gauges.begin()),
                  std::make_move_iterator(gauges.end()));
  return families;
}

}  // namespace afmesh::server
