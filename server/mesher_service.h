// The afmesh.v1.Mesher gRPC service (callback API, one reactor per call): each RPC runs as a
// StreamingCall (streaming_call.h) of its own part, MeshVolume's being MeshVolumeRpc
// (mesh_volume_rpc.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "server/call_gate.h"
#include "server/memory_budget.h"
#include "server/surface_job.h"
#include "server/volume_input.h"
#include "server/volume_job.h"
#include "server/worker_pool.h"

namespace grpc {
class Service;
}

namespace afmesh::server {

class ServerMetrics;

struct ServiceOptions {
  InputLimits limits;
  // Bytes the jobs running at once may be expected to need together (--memory-budget-mb).
  std::int64_t memory_budget_bytes = default_memory_budget();
  // One structured line on stderr per finished call (id, peer, input sizes, duration, outcome,
  // code: call_log.h).
  bool log_calls = true;
  // When set, calls must carry "authorization: Bearer <bearer_token>" (call_auth.h).
  std::string bearer_token;
  // A read or write pending this long cancels its call (--stall-timeout; stall_watch.h): a
  // client that stops reading holds its mesh and its memory budget no longer than this.
  std::chrono::milliseconds stall_timeout{60000};
};

// The Mesher service: MeshVolume calls pass `gate` (UNAVAILABLE once it is closed), reserve a
// slot of `pool` (RESOURCE_EXHAUSTED when none is free), assemble and check their input, reserve
// their estimated bytes of `budget`, run `job` on a worker and stream its result; each call is
// counted into `metrics` when it ends. `pool`, `gate`, `budget` and `metrics` must outlive
// every call. (options.memory_budget_bytes is for whoever makes `budget`.) MeshSurface calls,
// and MeshVolume calls with remesh_surface, run `surface_job` likewise (empty: they end
// UNIMPLEMENTED).
std::unique_ptr<grpc::Service> make_mesher_service(WorkerPool& pool, CallGate& gate,
                                                   MemoryBudget& budget, ServerMetrics& metrics,
                                                   VolumeJob job, const ServiceOptions& options,
                                                   SurfaceJob surface_job = {});

}  // namespace afmesh::server
