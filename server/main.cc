// afmesh-server: serves afmesh.v1.Mesher (with gRPC health and reflection) until SIGTERM or
// SIGINT, then stops accepting calls, lets those in flight finish within --grace-period (then
// stops them: they end UNAVAILABLE) and exits 0. A second signal during that drain exits at
// once (status 1).
#include <pthread.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "CLI/CLI.hpp"
#include "grpc/grpc.h"
#include "core/surface/generate_surface_mesh.h"
#include "server/default_volume_job.h"
#include "server/listen_note.h"
#include "server/server.h"

namespace {

// SIGTERM and SIGINT, blocked in every thread so that only sigwait() sees them.
sigset_t stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  return signals;
}

int wait_for_signal(const sigset_t& signals) {
  int signal = 0;
  while (sigwait(&signals, &signal) != 0) {
  }
  return signal;
}

// A flag in MiB for a limit kept in bytes.
void add_mebibytes_option(CLI::App& app, const std::string& name, std::int64_t& bytes,
                          const std::string& description) {
  app.add_option_function<std::int64_t>(
         name, [&bytes](std::int64_t mib) { bytes = mib << 20; }, description)
      ->default_str(std::to_string(bytes >> 20))
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
}

void add_flags(CLI::App& app, afmesh::server::ServerOptions& options) {
  app.add_option("--listen", options.listen, "host:port (port 0: any free port) or unix:PATH")
      ->capture_default_str();
  app.add_option("--workers", options.workers,
                 "meshing jobs run at once (0: one per hardware thread)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-queue", options.max_queue,
                 "calls admitted beyond the running ones; more get RESOURCE_EXHAUSTED")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-points", options.service.limits.max_points, "most input points per request")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--max-triangles", options.service.limits.max_triangles,
                 "most input triangles per request")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--max-grid-points", options.service.limits.max_grid_points,
                 "most background grid points per request")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--max-grid-tets", options.service.limits.max_grid_tets,
                 "most background grid tetrahedra per request")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option_function<double>(
         "--grace-period",
         [&options](double seconds) {
           options.grace_period = std::chrono::milliseconds(static_cast<long long>(seconds * 1000));
         },
         "seconds a drain (SIGTERM) waits for the calls in flight before stopping them "
         "(they end UNAVAILABLE)")
      ->default_str(std::to_string(options.grace_period.count() / 1000))
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option_function<double>(
         "--stall-timeout",
         [&options](double seconds) {
           options.service.stall_timeout =
               std::chrono::milliseconds(static_cast<long long>(seconds * 1000));
         },
         "seconds a read or write of a call may stay pending before the call is cancelled (a "
         "client that stops reading its result frees the mesh's memory then)")
      ->default_str(std::to_string(options.service.stall_timeout.count() / 1000))
      ->check(CLI::Range(0.05, 86400.0));
  app.add_option("--max-elements", options.service.limits.max_elements,
                 "most tetrahedra a request may ask for, by the estimate made before meshing")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  add_mebibytes_option(app, "--max-request-mb", options.service.limits.max_request_bytes,
                       "most bytes of one request's messages, in MiB");
  add_mebibytes_option(app, "--memory-budget-mb", options.service.memory_budget_bytes,
                       "memory the jobs running at once may be expected to need together, in "
                       "MiB (default: 3/4 of physical memory)");
  app.add_option("--tls-cert", options.security.tls_cert,
                 "PEM certificate chain to serve TLS with (needs --tls-key)");
  app.add_option("--tls-key", options.security.tls_key,
                 "PEM private key of --tls-cert (unencrypted)");
  app.add_option("--tls-client-ca", options.security.tls_client_ca,
                 "PEM CA bundle: require client certificates signed by it (mutual TLS)");
  app.add_option("--token-file", options.security.token_file,
                 "file holding a bearer token every Mesher call must send "
                 "(authorization: Bearer TOKEN)");
  app.add_option("--metrics", options.metrics,
                 "serve Prometheus metrics at http://ADDR/metrics, ADDR = IPV4:PORT (port 0: any "
                 "free port; 0.0.0.0:9464 for other hosts); off when not given")
      ->type_name("ADDR");
  app.add_flag_callback(
      "--quiet", [&options] { options.service.log_calls = false; }, "do not log each call");
}

}  // namespace

int main(int argc, char** argv) {
  const sigset_t signals = stop_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts
  // Held until exit: gRPC otherwise shuts its library down when the server object goes away,
  // which in 1.51 can wait seconds for an idle poller.
  grpc_init();

  afmesh::server::ServerOptions options;
  CLI::App app{"afmesh-server: advancing-front meshing service (gRPC afmesh.v1.Mesher)"};
  add_flags(app, options);
  CLI11_PARSE(app, argc, argv);

  auto server = afmesh::server::MesherServer::start(
      options, afmesh::server::default_volume_job(),
      [](const afmesh::Mesh& input, const afmesh::SurfaceParams& params,
         afmesh::Progress& progress) {
        return afmesh::generate_surface_mesh(input, params, progress);
      });
  if (!server.ok()) {
    std::fprintf(stderr, "afmesh-server: %s\n", std::string(server.status().message()).c_str());
    return 1;
  }
  for (const std::string& line :
       afmesh::server::listen_note((*server)->address(), (*server)->security())) {
    std::fprintf(stderr, "afmesh-server: %s\n", line.c_str());
  }
  if (!(*server)->metrics_address().empty()) {
    std::fprintf(stderr, "afmesh-server: %s\n",
                 afmesh::server::metrics_note((*server)->metrics_address()).c_str());
  }

  const int signal = wait_for_signal(signals);
  std::fprintf(stderr, "afmesh-server: %s, draining calls in flight\n", strsignal(signal));
  std::thread([&signals] {
    wait_for_signal(signals);
    std::fprintf(stderr, "afmesh-server: second signal, exiting without draining\n");
    std::_Exit(1);
  }).detach();
  (*server)->shutdown();
  std::fprintf(stderr, "afmesh-server: stopped\n");
  return 0;
}
