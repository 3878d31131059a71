#include "server/server.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "grpcpp/ext/proto_server_reflection_plugin.h"
#include "grpcpp/grpcpp.h"
#include "grpcpp/health_check_service_interface.h"
#include "grpcpp/impl/service_type.h"
#include "server/metrics.h"
#include "server/metrics_endpoint.h"

namespace afmesh::server {
namespace {

// Time left to clients to read the end of their calls before the connections close; never more
// than the grace period itself: a server asked for none (the CLI's private server, stopped only
// once its one client has read its whole result) stops at once.
constexpr auto kFinishGrace = std::chrono::milliseconds(200);
// After the grace period, how long stopped calls get to end by themselves before gRPC cancels
// whatever is left (a client that stopped reading, say).
constexpr auto kAbortGrace = std::chrono::seconds(2);

// `listen` with its port replaced by `port` (for "host:0"); unix: addresses are kept.
std::string dial_address(const std::string& listen, int port) {
  if (absl::StartsWith(listen, "unix:")) return listen;
  const std::string::size_type colon = listen.rfind(':');
  if (colon == std::string::npos) return listen;
  return absl::StrCat(listen.substr(0, colon + 1), port);
}

int worker_count(int requested) {
  if (requested > 0) return requested;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

}  // namespace

absl::StatusOr<std::unique_ptr<MesherServer>> MesherServer::start(const ServerOptions& options,
                                                                  VolumeJob job,
                                                                  SurfaceJob surface_job) {
  // Process-wide switches of gRPC; both must be set before a server is built.
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();

  absl::StatusOr<ServerSecurity> security = load_server_security(options.security);
  if (!security.ok()) return security.status();
  ServiceOptions service_options = options.service;
  service_options.bearer_token = security->bearer_token;

  std::unique_ptr<MesherServer> server(new MesherServer());
  server->security_ = *std::move(security);
  server->pool_ = std::make_unique<WorkerPool>(worker_count(options.workers), options.max_queue);
  server->budget_ = std::make_unique<MemoryBudget>(service_options.memory_budget_bytes);
  server->metrics_ =
      std::make_shared<ServerMetrics>(server->gate_, *server->pool_, *server->budget_);
  if (!options.metrics.empty()) {
    absl::StatusOr<std::unique_ptr<MetricsEndpoint>> endpoint =
        MetricsEndpoint::start(options.metrics, server->metrics_);
    if (!endpoint.ok()) return endpoint.status();
    server->metrics_endpoint_ = *std::move(endpoint);
  }
  server->service_ = make_mesher_service(*server->pool_, server->gate_, *server->budget_,
                                         *server->metrics_, std::move(job), service_options,
                                         std::move(surface_job));

  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(options.listen, server->security_.credentials, &port);
  builder.RegisterService(server->service_.get());
  server->server_ = builder.BuildAndStart();
  if (server->server_ == nullptr || port == 0) {
    return absl::UnavailableError(absl::StrCat("cannot listen on ", options.listen,
                                               " (address in use, bad address, or no permission)"));
  }
  server->address_ = dial_address(options.listen, port);
  server->grace_period_ = options.grace_period;
  return server;
}

MesherServer::MesherServer() = default;

const std::string& MesherServer::metrics_address() const {
  static const std::string kNone;
  return metrics_endpoint_ != nullptr ? metrics_endpoint_->address() : kNone;
}

MesherServer::~MesherServer() { shutdown(); }

void MesherServer::shutdown() {
  if (server_ != nullptr) {
    gate_.close();
    server_->GetHealthCheckService()->SetServingStatus(false);
    if (!gate_.wait_until_empty_for(grace_period_)) {
      gate_.abort();
      gate_.wait_until_empty_for(kAbortGrace);
    }
    // A call's last bytes are written when it ends, but the client may not have read them:
    // closing the connections at once can fail the call on its side ("Broken pipe").
    std::this_thread::sleep_until(gate_.last_leave() + std::min<std::chrono::milliseconds>(
                                                          kFinishGrace, grace_period_));
    // Calls still open now (only after an abort) are cancelled by gRPC at once.
    server_->Shutdown(std::chrono::system_clock::now());
    server_->Wait();
    server_.reset();
  }
  metrics_endpoint_.reset();  // its scrapes read the pool and the budget
  service_.reset();
  pool_.reset();  // joins the workers (their queue is empty once every call is done)
}

}  // namespace afmesh::server
