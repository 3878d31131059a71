// afmesh-server as a library: the Mesher service with its worker pool, the standard health
// service and server reflection, listening on one address, and optionally Prometheus metrics
// on another. Used by the afmesh-server executable and, in-process, by the tests.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "server/call_gate.h"
#include "server/credentials.h"
#include "server/mesher_service.h"
#include "server/surface_job.h"
#include "server/volume_job.h"
#include "server/worker_pool.h"

namespace grpc {
class Server;
}

namespace afmesh::server {

class MetricsEndpoint;
class ServerMetrics;

struct ServerOptions {
  // host:port (port 0 picks a free one), or unix:PATH for a local socket.
  std::string listen = "127.0.0.1:50051";
  // Meshing jobs run at once; 0 means one per hardware thread.
  int workers = 0;
  // Calls admitted beyond the running ones (they wait in arrival order); a call arriving when
  // workers + max_queue calls are in progress gets RESOURCE_EXHAUSTED.
  int max_queue = 16;
  // How long a drain (SIGTERM) waits for the calls in flight before stopping them
  // (--grace-period); below Kubernetes' default terminationGracePeriodSeconds of 30.
  std::chrono::milliseconds grace_period{25'000};
  ServiceOptions service;  // its bearer_token comes from security.token_file
  // TLS, mutual TLS and the bearer token (credentials.h); default: plaintext, no token.
  SecurityFiles security;
  // IPV4:PORT to serve Prometheus metrics on, as plain HTTP GET /metrics (port 0 picks a free
  // one); empty: no metrics endpoint (the server counts all the same). metrics.h lists them.
  std::string metrics;
};

class MesherServer {
 public:
  // Starts listening. INVALID_ARGUMENT naming the file when a security file is unreadable or
  // invalid (load_server_security), or naming --metrics when options.metrics is not IPV4:PORT;
  // UNAVAILABLE when the address (or the metrics address) cannot be bound. `surface_job` serves
  // MeshSurface and remesh_surface (empty: those calls end UNIMPLEMENTED).
  static absl::StatusOr<std::unique_ptr<MesherServer>> start(const ServerOptions& options,
                                                             VolumeJob job,
                                                             SurfaceJob surface_job = {});
  // Shuts down (see shutdown()).
  ~MesherServer();
  MesherServer(const MesherServer&) = delete;
  MesherServer& operator=(const MesherServer&) = delete;

  // The address clients dial: the listen address, with the chosen port when it asked for 0.
  const std::string& address() const { return address_; }
  // What the server asks of its clients (TLS, client certificates, token).
  const ServerSecurity& security() const { return security_; }
  // Where GET /metrics is served (IPV4:PORT, the chosen port when options.metrics asked for 0);
  // empty when options.metrics was.
  const std::string& metrics_address() const;

  // Drains, then stops: health turns NOT_SERVING and new calls get UNAVAILABLE; every call in
  // flight finishes (its job and its whole result included) within options.grace_period; calls
  // still in flight then are stopped (jobs cancelled, the calls end UNAVAILABLE so that clients
  // retry elsewhere); after a short grace for clients to read their last messages (200 ms, at
  // most options.grace_period) the gRPC server, then the metrics endpoint (scraped through the
  // drain), then the workers stop.
  // Blocks until done; idempotent.
  void shutdown();

 private:
  MesherServer();

  CallGate gate_;
  std::unique_ptr<WorkerPool> pool_;
  std::unique_ptr<MemoryBudget> budget_;
  // Counted whether or not they are served; read by metrics_endpoint_'s threads.
  std::shared_ptr<ServerMetrics> metrics_;
  std::unique_ptr<MetricsEndpoint> metrics_endpoint_;
  std::unique_ptr<grpc::Service> service_;
  std::unique_ptr<grpc::Server> server_;
  std::string address_;
  std::chrono::milliseconds grace_period_{0};
  ServerSecurity security_;
};

}  // namespace afmesh::server
