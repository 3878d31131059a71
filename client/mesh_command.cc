#include "client/mesh_command.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <utility>

#include "absl/strings/str_format.h"
#include "client/commands.h"
#include "client/interrupt_watcher.h"
#include "client/progress_display.h"
#include "client/server_launcher.h"
#include "client/spec_file.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "grpc/grpc.h"
#include "proto/size_spec_convert.h"
#include "security/address_reach.h"

namespace afmesh::cli {
namespace {

void print_error(const std::string& name, const absl::Status& status) {
  std::fprintf(stderr, "afmesh %s: %s\n", name.c_str(), std::string(status.message()).c_str());
}

// The exit code for a failed call (commands.h): what the user should do next differs.
int exit_code_for(const absl::Status& status) {
  switch (status.code()) {
    case absl::StatusCode::kInvalidArgument:
      return kExitBadInput;  // fix the input (the message names the element)
    case absl::StatusCode::kUnavailable:
    case absl::StatusCode::kResourceExhausted:
    case absl::StatusCode::kUnimplemented:
      return kExitUnavailable;  // the server cannot take the work: elsewhere or later
    case absl::StatusCode::kUnauthenticated:
    case absl::StatusCode::kPermissionDenied:
      return kExitUnauthenticated;  // the token is missing or wrong
    case absl::StatusCode::kFailedPrecondition:
    case absl::StatusCode::kInternal:
    case absl::StatusCode::kDeadlineExceeded:
    case absl::StatusCode::kCancelled:
      return kExitMeshingFailed;  // the mesh could not be produced (in time)
    default:
      return kExitInternal;
  }
}



// The wait before retry `attempt` (1, 2, ...): the server's hint or 0.25 s doubling per attempt,
// whichever is longer, at most 30 s, times a random factor in [0.5, 1.5) so that clients
// refused together do not come back together.
std::chrono::milliseconds retry_delay(int attempt, std::optional<std::chrono::milliseconds> hint,
                                      std::mt19937_64& random) {
  const double backoff_ms = 250.0 * std::pow(2.0, std::min(attempt - 1, 16));
  const double base_ms =
      std::min(30'000.0, std::max(backoff_ms, hint ? static_cast<double>(hint->count()) : 0.0));
  const double jitter = std::uniform_real_distribution<double>(0.5, 1.5)(random);
  return std::chrono::milliseconds(static_cast<std::int64_t>(base_ms * jitter));
}

// Sleeps for `delay`, or less when a signal arrives (then returns false).
bool wait_unless_interrupted(std::chrono::milliseconds delay, const InterruptWatcher& interrupts) {
  const auto until = std::chrono::steady_clock::now() + delay;
  while (std::chrono::steady_clock::now() < until) {
    if (interrupts.signal() != 0) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return interrupts.signal() == 0;
}

// IN's points and triangles with their tags (tets in IN are ignored).
absl::StatusOr<Mesh> read_front(const std::string& name, const MeshCommandOptions& options) {
  ReadReport report;
  absl::StatusOr<Mesh> mesh = read_mesh(options.input, &report);
  if (!mesh.ok()) return mesh.status();
  if (!options.quiet) {
    for (const std::string& note : report.notes) {
      std::fprintf(stderr, "afmesh %s: note: %s\n", name.c_str(), note.c_str());
    }
  }
  if (mesh->triangles.empty()) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s has no triangles: a triangulated surface is needed", options.input));
  }
  if (!mesh->tets.empty() && !options.quiet) {
    std::fprintf(stderr, "afmesh %s: note: ignoring the %zu tetrahedra of %s\n", name.c_str(),
                 mesh->tets.size(), options.input.c_str());
  }
  mesh->tets.clear();
  mesh->tet_tags.clear();
  return mesh;
}


// The specification travels in the call's first message, except its background grid, which
// follows in slices of any number (volume_call.cc). gRPC refuses messages over 4 MiB (its
// default, which the server keeps), so only an absurd number of sources can overflow the header;
// the other header fields take a few bytes.
absl::Status check_fits_in_header(const SizeSpec& spec) {
  constexpr std::size_t kMaxSpecBytes = 4 * 1024 * 1024 - 1024;
  v1::SizeSpec message = size_spec_to_proto(spec);
  message.clear_background();
  const std::size_t bytes = message.ByteSizeLong();
  if (bytes <= kMaxSpecBytes) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrFormat(
      "the size specification's %zu sources take %.2f MiB on the wire, more than the 4 MiB the "
      "call's first message can carry: use fewer sources, or a background grid",
      spec.sources.size(), static_cast<double>(bytes) / (1024.0 * 1024.0)));
}

// The size specification of --spec with the command line's overrides: --size, else the file's
// maxSize, else the front's mean edge length; --growth, else the file's growth. Validated
// (validate_size_spec); errors name the file and the field.
absl::StatusOr<SizeSpec> spec_for(const std::string& name, const MeshCommandOptions& options,
                                  const Mesh& front) {
  ReadReport report;
  absl::StatusOr<SizeSpec> spec = read_size_spec_file(options.spec_path, &report);
  if (!options.quiet) {
    for (const std::string& note : report.notes) {
      std::fprintf(stderr, "afmesh %s: note: %s\n", name.c_str(), note.c_str());
    }
  }
  if (!spec.ok()) return spec.status();
  if (options.size_given) {
    spec->max_size = options.size;
  } else if (spec->max_size == 0.0) {
    spec->max_size = mean_edge_length(front);
  }
  if (options.growth_given) spec->growth = options.growth;
  if (absl::Status status = validate_size_spec(*spec); !status.ok()) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %s", options.spec_path, status.message()));
  }
  if (absl::Status status = check_fits_in_header(*spec); !status.ok()) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %s", options.spec_path, status.message()));
  }
  return spec;
}

// TLS and token for the call (--tls-*, --token-file). They are for a shared server: the private
// one listens on a unix socket only this user can reach, without TLS or token.
absl::StatusOr<ClientSecurity> security_for(const std::string& name,
                                            const MeshCommandOptions& options) {
  if (options.server.empty() && options.security.any()) {
    return absl::InvalidArgumentError(
        "--tls-ca, --tls-cert, --tls-key and --token-file are for a shared server: give --server "
        "ADDR (the private server needs none of them)");
  }
  absl::StatusOr<ClientSecurity> loaded = load_client_security(options.security);
  if (loaded.ok() && loaded->has_token() && !loaded->tls() && !options.quiet &&
      security::reach_of(options.server) == security::Reach::kOtherHosts) {
    std::fprintf(stderr,
                 "afmesh %s: warning: the bearer token goes to %s in plaintext; use --tls-ca "
                 "when the server serves TLS\n",
                 name.c_str(), options.server.c_str());
  }
  return loaded;
}

// Exit status after SIGINT / SIGTERM, as a shell reports a process ended by the signal.
int interrupted(const std::string& name, int signal) {
  std::fprintf(stderr, "afmesh %s: interrupted\n", name.c_str());
  return 128 + signal;
}

}  // namespace

int run_mesh_command(const MeshCommandOptions& options, MeshCommand command) {
  const std::string& name = command.name;
  // Ctrl-C cancels the call; everything below is then undone by the destructors (the private
  // server stopped, its folder removed). Set up before any thread exists.
  const auto canceller = std::make_shared<CallCanceller>();
  const InterruptWatcher interrupts([canceller] { canceller->cancel(); });
  // Held until exit: gRPC otherwise shuts its library down when the last channel goes away,
  // which in 1.51 can wait seconds for an idle poller.
  grpc_init();
  if (absl::Status status = command.check_output(options.output); !status.ok()) {
    print_error(name, status);
    return kExitUsage;
  }
  absl::StatusOr<ClientSecurity> security = security_for(name, options);
  if (!security.ok()) {
    print_error(name, security.status());
    return kExitUsage;
  }
  ProgressDisplay progress(stderr, ProgressDisplay::mode_for(stderr, options.quiet));
  progress.update("read", -1.0);
  absl::StatusOr<Mesh> front = read_front(name, options);
  if (!front.ok()) {
    progress.finish();
    print_error(name, front.status());
    return kExitBadInput;
  }

  if (command.check_input) {
    if (absl::Status status = command.check_input(*front); !status.ok()) {
      progress.finish();
      print_error(name, status);
      return kExitBadInput;
    }
  }

  std::optional<SizeSpec> spec;
  if (!options.spec_path.empty()) {
    absl::StatusOr<SizeSpec> read = spec_for(name, options, *front);
    if (!read.ok()) {
      progress.finish();
      print_error(name, read.status());
      return kExitBadInput;
    }
    spec = *std::move(read);
  }

  std::unique_ptr<PrivateServer> private_server;  // stopped on every way out of this function
  std::string address = options.server;
  if (address.empty()) {
    progress.update("start", -1.0);
    absl::StatusOr<std::unique_ptr<PrivateServer>> started = PrivateServer::start();
    if (!started.ok()) {
      progress.finish();
      print_error(name, started.status());
      return kExitUnavailable;
    }
    private_server = *std::move(started);
    address = private_server->address();
  }
  if (interrupts.signal() != 0) return interrupted(name, interrupts.signal());

  VolumeCallOptions call_options = std::move(command.call_options);
  call_options.size = options.size > 0 ? options.size : mean_edge_length(*front);
  call_options.growth = options.growth;
  call_options.spec = std::move(spec);
  call_options.ridge_angle_deg = options.ridge_angle_deg;
  call_options.corner_angle_deg = options.corner_angle_deg;
  call_options.curvature_angle_deg = options.curvature_angle_deg;
  call_options.curvature_deviation = options.curvature_deviation;
  call_options.wall_sizes = options.wall_sizes;
  call_options.timeout_seconds = options.timeout_seconds;
  call_options.canceller = canceller.get();
  call_options.security = *std::move(security);
  const auto call = [&] {
    return command.call(
        address, *front, call_options,
        [&progress](std::string_view stage, double fraction) { progress.update(stage, fraction); },
        [&progress, &options, &name](std::string_view message) {
          if (options.quiet) return;
          progress.finish();
          std::fprintf(stderr, "afmesh %s: warning: %.*s\n", name.c_str(),
                       static_cast<int>(message.size()), message.data());
        });
  };
  absl::StatusOr<MeshAnswer> result = call();
  std::mt19937_64 random(std::random_device{}());
  for (int attempt = 1; attempt <= options.retries && !result.ok() &&
                        interrupts.signal() == 0 &&
                        worth_retrying(result.status(), private_server == nullptr);
       ++attempt) {
    const std::chrono::milliseconds delay =
        retry_delay(attempt, retry_after(result.status()), random);
    progress.finish();
    if (!options.quiet) {
      std::fprintf(stderr, "afmesh %s: %s; retry %d of %d in %.1f s\n", name.c_str(),
                   std::string(result.status().message()).c_str(), attempt, options.retries,
                   static_cast<double>(delay.count()) / 1000.0);
    }
    if (!wait_unless_interrupted(delay, interrupts)) break;
    result = call();
  }
  if (!result.ok()) {
    progress.finish();
    if (interrupts.signal() != 0) return interrupted(name, interrupts.signal());
    if (result.status().code() == absl::StatusCode::kDeadlineExceeded) {
      print_error(name, absl::DeadlineExceededError(absl::StrFormat(
          "meshing did not finish within --timeout %g s; the server stopped the job",
          options.timeout_seconds)));
      return kExitMeshingFailed;
    }
    if (result.status().code() == absl::StatusCode::kUnavailable) {
      print_error(name, absl::UnavailableError(absl::StrFormat("cannot reach the server at %s: %s",
                                                         address, result.status().message())));
      return kExitUnavailable;
    }
    print_error(name, result.status());
    return result.status().code() == absl::StatusCode::kDataLoss ? kExitInternal
                                                                 : exit_code_for(result.status());
  }

  progress.update("write", -1.0);
  if (absl::Status status = write_mesh(result->mesh, options.output); !status.ok()) {
    progress.finish();
    print_error(name, status);
    return kExitInternal;
  }
  progress.finish();
  if (options.json) {
    std::cout << result->summary_json << std::flush;
  } else if (!options.quiet) {
    result->print(options.output);
  }
  return kExitOk;
}

void print_timings(const std::vector<std::pair<std::string, double>>& timings) {
  std::printf("  time");
  for (const auto& [stage, seconds] : timings) std::printf("  %s %.3f s", stage.c_str(), seconds);
  std::printf("\n");
}

void add_mesh_command_flags(CLI::App& command, MeshCommandOptions& options,
                            const std::string& input_help, const std::string& output_help) {
  command.add_option("IN", options.input, input_help)->required();
  command.add_option("-o,--output", options.output, output_help)->required();
  command
      .add_option("--size", options.size,
                  "target edge length h (default: the mean edge length of IN)")
      ->check(CLI::PositiveNumber);
  command.add_option("--growth", options.growth, "growth factor c >= 1 (eq. 15)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e6));
  command.add_option("--spec", options.spec_path,
                     "size specification (JSON, design.md); --size and --growth override its "
                     "maxSize and growth");
  command.add_option("--server", options.server,
                     "server address: host:port, unix:PATH, dns:///NAME:PORT (every address the "
                     "name resolves to) or a comma list of IPv4 host:port, calls spread over "
                     "them round-robin; default: a private server");
  add_client_security_flags(command, options.security);
  command.add_flag("--json", options.json, "print the summary as JSON on stdout");
  command.add_flag("--quiet", options.quiet, "print nothing but errors");
  command.add_option("--timeout", options.timeout_seconds, "give up after SEC seconds")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--retries", options.retries,
                  "times a call is sent again when the server is busy (its retry hint), or a "
                  "shared server is unreachable or draining; jittered back-off from 0.25 s, "
                  "doubling, at most 30 s per wait")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
}

void add_surface_angle_flags(CLI::App& command, MeshCommandOptions& options) {
  command
      .add_option("--ridge-angle", options.ridge_angle_deg,
                  "adjacent faces whose normals differ by more than DEG degrees make a ridge, "
                  "kept in the result (default 30)")
      ->check(CLI::Range(0.0, 180.0) & !CLI::IsMember({0.0, 180.0}));
  command
      .add_option("--corner-angle", options.corner_angle_deg,
                  "a ridge turning by more than DEG degrees at a vertex makes a corner, kept in "
                  "the result (default 60)")
      ->check(CLI::Range(0.0, 180.0) & !CLI::IsMember({0.0}));
  command
      .add_option("--curvature-angle", options.curvature_angle_flag,
                  "where IN curves, elements turn by at most DEG degrees: the size is reduced "
                  "there, so small holes and fillets are not meshed over (default 30, about 12 "
                  "elements round a circle; 0: the size alone)")
      ->check(CLI::Range(0.0, 180.0) & !CLI::IsMember({180.0}));
  command
      .add_option("--curvature-deviation", options.curvature_deviation_flag,
                  "the result stays within E times IN's bounding-box diagonal from IN where IN "
                  "curves or creases: the size is reduced there (0.001: within 0.1%; default 0: "
                  "the angle alone)")
      ->check(CLI::Range(0.0, 1.0) & !CLI::IsMember({1.0}));
  command
      .add_option("--wall-sizes", options.wall_sizes_flag,
                  "elements at most F times the thickness of the solid IN bounds where its walls "
                  "are thinner than the size, down to 0.15 of the size, so that a volume's tets "
                  "do not span them flat (default: 1 for volume --remesh-surface, 0: none for "
                  "surface)")
      ->check(CLI::Range(0.0, 100.0) & !CLI::IsMember({100.0}));
}

void note_given_flags(const CLI::App& command, MeshCommandOptions& options) {
  options.size_given = command.count("--size") > 0;
  options.growth_given = command.count("--growth") > 0;
  if (command.count("--curvature-angle") > 0) {
    options.curvature_angle_deg = options.curvature_angle_flag;
  }
  if (command.count("--curvature-deviation") > 0) {
    options.curvature_deviation = options.curvature_deviation_flag;
  }
  if (command.count("--wall-sizes") > 0) options.wall_sizes = options.wall_sizes_flag;
}

}  // namespace afmesh::cli
