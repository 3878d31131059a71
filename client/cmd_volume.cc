// afmesh volume IN -o OUT [--size H] [--growth C] [--spec SPEC.json] [--envs auto|tags|none]
//                         [--server ADDR] [--tls-ca FILE [--tls-cert FILE --tls-key FILE]]
//                         [--token-file FILE] [--json] [--quiet] [--timeout SEC]
// Fills the closed front in IN with tetrahedra through the MeshVolume call and writes OUT.
// --spec sends a whole size specification (sources, background grid; design.md, "Size
// specification"); --size and --growth, when given, override its maxSize and growth.
// --envs marks crossing environments (paper §2) so that the two sides of thin structures may
// nearly touch or cross: `tags` reads them from the triangle tags (Medit references, Gmsh
// physical tags; 0 = none), `auto` lets the server find them; default none.
// Without --server a private afmesh-server runs for the command on a local socket: the same
// code path as a remote server. Formats follow the file extensions (core/io/mesh_io.h).
// --tls-ca, --tls-cert, --tls-key and --token-file match a shared server's --tls-cert, --tls-key,
// --tls-client-ca and --token-file (client/channel_credentials.h); they need --server.
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
#include "client/channel_credentials.h"
#include "client/commands.h"
#include "core/environments/environments.h"
#include "client/interrupt_watcher.h"
#include "client/progress_display.h"
#include "client/server_launcher.h"
#include "client/spec_file.h"
#include "proto/size_spec_convert.h"
#include "security/address_reach.h"
#include "client/volume_call.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "grpc/grpc.h"

namespace afmesh::cli {
namespace {

struct VolumeCommandOptions {
  std::string input;
  std::string output;
  double size = 0.0;  // 0: the mean edge length of the front
  double growth = 1.0;
  bool size_given = false;    // --size was on the command line
  bool growth_given = false;  // --growth was on the command line
  std::string spec_path;      // empty: a uniform size, no sources
  std::string envs = "none";  // auto, tags or none
  std::string server;  // empty: start a private server
  int retries = 4;     // calls sent again after a refusal that may pass later
  ClientSecurityFiles security;  // TLS and token files for --server
  bool json = false;
  bool quiet = false;
  double timeout_seconds = 0.0;
};

void print_error(const absl::Status& status) {
  std::fprintf(stderr, "afmesh volume: %s\n", std::string(status.message()).c_str());
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

// The output must hold tetrahedra: checked before any meshing work.
absl::Status check_output_path(const std::string& path) {
  absl::StatusOr<MeshFormat> format = format_from_path(path);
  if (!format.ok()) return format.status();
  if (*format == MeshFormat::kStl || *format == MeshFormat::kObj) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s: STL and OBJ files cannot hold tetrahedra; use .msh, .mesh or .vtu", path));
  }
  return absl::OkStatus();
}

// The front to mesh: IN's points and triangles with their tags (tets in IN are ignored).
absl::StatusOr<Mesh> read_front(const VolumeCommandOptions& options) {
  ReadReport report;
  absl::StatusOr<Mesh> mesh = read_mesh(options.input, &report);
  if (!mesh.ok()) return mesh.status();
  if (!options.quiet) {
    for (const std::string& note : report.notes) {
      std::fprintf(stderr, "afmesh volume: note: %s\n", note.c_str());
    }
  }
  if (mesh->triangles.empty()) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s has no triangles: a closed triangulated front is needed", options.input));
  }
  if (!mesh->tets.empty() && !options.quiet) {
    std::fprintf(stderr, "afmesh volume: note: ignoring the %zu tetrahedra of %s\n",
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
absl::StatusOr<SizeSpec> spec_for(const VolumeCommandOptions& options, const Mesh& front) {
  ReadReport report;
  absl::StatusOr<SizeSpec> spec = read_size_spec_file(options.spec_path, &report);
  if (!options.quiet) {
    for (const std::string& note : report.notes) {
      std::fprintf(stderr, "afmesh volume: note: %s\n", note.c_str());
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

void print_summary(const VolumeCommandOptions& options, const VolumeSummary& summary) {
  std::printf("%s: %llu points, %llu boundary triangles, %llu tetrahedra\n", options.output.c_str(),
              static_cast<unsigned long long>(summary.point_count),
              static_cast<unsigned long long>(summary.triangle_count),
              static_cast<unsigned long long>(summary.tet_count));
  std::printf("  dihedral angles  min %.2f°  max %.2f°  (%.3f%% of tets < 10°, %.3f%% < 20°)\n",
              summary.min_dihedral_deg, summary.max_dihedral_deg, 100 * summary.share_below_10_deg,
              100 * summary.share_below_20_deg);
  std::printf("  radius ratio     min %.4f  mean %.4f\n", summary.min_radius_ratio,
              summary.mean_radius_ratio);
  std::printf("  validation       %s\n", summary.validation_passed ? "passed" : "FAILED");
  for (const std::string& message : summary.validation_messages) {
    std::printf("    %s\n", message.c_str());
  }
  std::printf("  time");
  for (const auto& [stage, seconds] : summary.timings) {
    std::printf("  %s %.3f s", stage.c_str(), seconds);
  }
  std::printf("\n");
}

// TLS and token for the call (--tls-*, --token-file). They are for a shared server: the private
// one listens on a unix socket only this user can reach, without TLS or token.
absl::StatusOr<ClientSecurity> security_for(const VolumeCommandOptions& options) {
  if (options.server.empty() && options.security.any()) {
    return absl::InvalidArgumentError(
        "--tls-ca, --tls-cert, --tls-key and --token-file are for a shared server: give --server "
        "ADDR (the private server needs none of them)");
  }
  absl::StatusOr<ClientSecurity> loaded = load_client_security(options.security);
  if (loaded.ok() && loaded->has_token() && !loaded->tls() && !options.quiet &&
      security::reach_of(options.server) == security::Reach::kOtherHosts) {
    std::fprintf(stderr,
                 "afmesh volume: warning: the bearer token goes to %s in plaintext; use --tls-ca "
                 "when the server serves TLS\n",
                 options.server.c_str());
  }
  return loaded;
}

// Exit status after SIGINT / SIGTERM, as a shell reports a process ended by the signal.
int interrupted(int signal) {
  std::fprintf(stderr, "afmesh volume: interrupted\n");
  return 128 + signal;
}

int run_volume(const VolumeCommandOptions& options) {
  // Ctrl-C cancels the call; everything below is then undone by the destructors (the private
  // server stopped, its folder removed). Set up before any thread exists.
  const auto canceller = std::make_shared<CallCanceller>();
  const InterruptWatcher interrupts([canceller] { canceller->cancel(); });
  // Held until exit: gRPC otherwise shuts its library down when the last channel goes away,
  // which in 1.51 can wait seconds for an idle poller.
  grpc_init();
  if (absl::Status status = check_output_path(options.output); !status.ok()) {
    print_error(status);
    return kExitUsage;
  }
  absl::StatusOr<ClientSecurity> security = security_for(options);
  if (!security.ok()) {
    print_error(security.status());
    return kExitUsage;
  }
  ProgressDisplay progress(stderr, ProgressDisplay::mode_for(stderr, options.quiet));
  progress.update("read", -1.0);
  absl::StatusOr<Mesh> front = read_front(options);
  if (!front.ok()) {
    progress.finish();
    print_error(front.status());
    return kExitBadInput;
  }

  if (options.envs == "tags" && !has_positive_tags(*front)) {
    progress.finish();
    print_error(absl::InvalidArgumentError(absl::StrFormat(
        "--envs tags: none of the %d triangles of %s carries a positive tag (Medit triangle "
        "reference or Gmsh physical tag), so there are no crossing environments to read; tag "
        "each side of a thin region with an id > 0, or use --envs auto",
        front->triangles.size(), options.input)));
    return kExitBadInput;
  }

  std::optional<SizeSpec> spec;
  if (!options.spec_path.empty()) {
    absl::StatusOr<SizeSpec> read = spec_for(options, *front);
    if (!read.ok()) {
      progress.finish();
      print_error(read.status());
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
      print_error(started.status());
      return kExitUnavailable;
    }
    private_server = *std::move(started);
    address = private_server->address();
  }
  if (interrupts.signal() != 0) return interrupted(interrupts.signal());

  const VolumeCallOptions call_options{
      .size = options.size > 0 ? options.size : mean_edge_length(*front),
      .growth = options.growth,
      .spec = std::move(spec),
      .environments = options.envs == "tags"   ? EnvironmentSource::kTags
                      : options.envs == "auto" ? EnvironmentSource::kAuto
                                               : EnvironmentSource::kNone,
      .timeout_seconds = options.timeout_seconds,
      .canceller = canceller.get(),
      .security = *std::move(security)};
  const auto call = [&] {
    return call_mesh_volume(
        address, *front, call_options,
        [&progress](std::string_view stage, double fraction) { progress.update(stage, fraction); },
        [&progress, &options](std::string_view message) {
          if (options.quiet) return;
          progress.finish();
          std::fprintf(stderr, "afmesh volume: warning: %.*s\n",
                       static_cast<int>(message.size()), message.data());
        });
  };
  absl::StatusOr<VolumeCallResult> result = call();
  std::mt19937_64 random(std::random_device{}());
  for (int attempt = 1; attempt <= options.retries && !result.ok() &&
                        interrupts.signal() == 0 &&
                        worth_retrying(result.status(), private_server == nullptr);
       ++attempt) {
    const std::chrono::milliseconds delay =
        retry_delay(attempt, retry_after(result.status()), random);
    progress.finish();
    if (!options.quiet) {
      std::fprintf(stderr, "afmesh volume: %s; retry %d of %d in %.1f s\n",
                   std::string(result.status().message()).c_str(), attempt, options.retries,
                   static_cast<double>(delay.count()) / 1000.0);
    }
    if (!wait_unless_interrupted(delay, interrupts)) break;
    result = call();
  }
  if (!result.ok()) {
    progress.finish();
    if (interrupts.signal() != 0) return interrupted(interrupts.signal());
    if (result.status().code() == absl::StatusCode::kDeadlineExceeded) {
      print_error(absl::DeadlineExceededError(absl::StrFormat(
          "meshing did not finish within --timeout %g s; the server stopped the job",
          options.timeout_seconds)));
      return kExitMeshingFailed;
    }
    if (result.status().code() == absl::StatusCode::kUnavailable) {
      print_error(absl::UnavailableError(absl::StrFormat("cannot reach the server at %s: %s",
                                                         address, result.status().message())));
      return kExitUnavailable;
    }
    print_error(result.status());
    return result.status().code() == absl::StatusCode::kDataLoss ? kExitInternal
                                                                 : exit_code_for(result.status());
  }

  progress.update("write", -1.0);
  if (absl::Status status = write_mesh(result->mesh, options.output); !status.ok()) {
    progress.finish();
    print_error(status);
    return kExitInternal;
  }
  progress.finish();
  if (options.json) {
    std::cout << result->summary.json << std::flush;
  } else if (!options.quiet) {
    print_summary(options, result->summary);
  }
  return kExitOk;
}

}  // namespace

void add_volume_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<VolumeCommandOptions>();
  CLI::App* command =
      app.add_subcommand("volume", "fill a closed triangulated front with tetrahedra");
  command->add_option("IN", options->input, "closed, outward-oriented front (.stl .obj .msh .mesh)")
      ->required();
  command->add_option("-o,--output", options->output, "volume mesh to write (.msh .mesh .vtu)")
      ->required();
  command
      ->add_option("--size", options->size,
                   "target edge length h (default: the mean edge length of IN)")
      ->check(CLI::PositiveNumber);
  command->add_option("--growth", options->growth, "growth factor c >= 1 (eq. 15)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e6));
  command->add_option("--spec", options->spec_path,
                      "size specification (JSON, design.md); --size and --growth override its "
                      "maxSize and growth");
  command
      ->add_option("--envs", options->envs,
                   "crossing environments for thin or crossing surfaces (paper §2): tags "
                   "(environment id = triangle tag), auto (found by the server) or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "tags", "none"}));
  command->add_option("--server", options->server,
                      "server address: host:port, unix:PATH, dns:///NAME:PORT (every address the "
                      "name resolves to) or a comma list of IPv4 host:port, calls spread over "
                      "them round-robin; default: a private server");
  add_client_security_flags(*command, options->security);
  command->add_flag("--json", options->json, "print the summary as JSON on stdout");
  command->add_flag("--quiet", options->quiet, "print nothing but errors");
  command->add_option("--timeout", options->timeout_seconds, "give up after SEC seconds")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--retries", options->retries,
                   "times a call is sent again when the server is busy (its retry hint), or a "
                   "shared server is unreachable or draining; jittered back-off from 0.25 s, "
                   "doubling, at most 30 s per wait")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  command->callback([options, command, &action] {
    options->size_given = command->count("--size") > 0;
    options->growth_given = command->count("--growth") > 0;
    action = [options] { return run_volume(*options); };
  });
}

}  // namespace afmesh::cli
