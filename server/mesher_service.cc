#include "server/mesher_service.h"

#include <utility>

#include "afmesh/v1/mesher.grpc.pb.h"
#include "grpcpp/grpcpp.h"
#include "server/mesh_surface_rpc.h"
#include "server/mesh_volume_rpc.h"
#include "server/stall_watch.h"
#include "server/streaming_call.h"

namespace afmesh::server {
namespace {

// Each RPC is a StreamingCall of its own part (streaming_call.h): MeshVolume's is
// mesh_volume_rpc.h, MeshSurface's mesh_surface_rpc.h.
class MesherService final : public v1::Mesher::CallbackService {
 public:
  MesherService(WorkerPool& pool, CallGate& gate, MemoryBudget& budget, ServerMetrics& metrics,
                VolumeJob job, const ServiceOptions& options, SurfaceJob surface_job)
      : stall_watch_(options.stall_timeout),
        resources_{.pool = pool,
                   .gate = gate,
                   .budget = budget,
                   .metrics = metrics,
                   .stall_watch = stall_watch_,
                   .log_calls = options.log_calls,
                   .bearer_token = options.bearer_token},
        volume_(std::move(job), options.limits, surface_job),
        surface_(std::move(surface_job), options.limits) {}

  grpc::ServerBidiReactor<v1::MeshVolumeRequest, v1::MeshVolumeResponse>* MeshVolume(
      grpc::CallbackServerContext* context) override {
    return start_streaming_call(context, volume_, resources_);
  }

  grpc::ServerBidiReactor<v1::MeshSurfaceRequest, v1::MeshSurfaceResponse>* MeshSurface(
      grpc::CallbackServerContext* context) override {
    return start_streaming_call(context, surface_, resources_);
  }

 private:
  StallWatch stall_watch_;  // outlives the calls: the server ends them before the service goes
  const CallResources resources_;
  const MeshVolumeRpc volume_;
  const MeshSurfaceRpc surface_;
};

}  // namespace

std::unique_ptr<grpc::Service> make_mesher_service(WorkerPool& pool, CallGate& gate,
                                                   MemoryBudget& budget, ServerMetrics& metrics,
                                                   VolumeJob job, const ServiceOptions& options,
                                                   SurfaceJob surface_job) {
  return std::make_unique<MesherService>(pool, gate, budget, metrics, std::move(job), options,
                                         std::move(surface_job));
}

}  // namespace afmesh::server
