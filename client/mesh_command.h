// What `afmesh volume` and `afmesh surface` share: their flags (IN, -o, --size, --growth, --spec,
// --server, TLS and token, --json, --quiet, --timeout, --retries) and their run (IN read, the
// size specification, a private afmesh-server when no --server is given, the call with its
// retries, the exit codes of commands.h, OUT written, the summary printed). Each command supplies
// its output check, its input check, its call and how its summary prints.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "client/channel_credentials.h"
#include "client/volume_call.h"
#include "core/mesh/mesh.h"

namespace afmesh::cli {

struct MeshCommandOptions {
  std::string input;
  std::string output;
  double size = 0.0;  // 0: the mean edge length of IN
  double growth = 1.0;
  bool size_given = false;    // --size was on the command line
  bool growth_given = false;  // --growth was on the command line
  std::string spec_path;      // empty: a uniform size, no sources
  std::string server;         // empty: start a private server
  int retries = 4;            // calls sent again after a refusal that may pass later
  ClientSecurityFiles security;  // TLS and token files for --server
  bool json = false;
  bool quiet = false;
  double timeout_seconds = 0.0;
  double ridge_angle_deg = 0.0;   // --ridge-angle; 0: the server's default
  double corner_angle_deg = 0.0;  // --corner-angle; 0: the server's default
  std::optional<double> curvature_angle_deg;  // --curvature-angle; unset: the server's default
  double curvature_angle_flag = 0.0;          // its parsed value (note_given_flags)
  std::optional<double> curvature_deviation;  // --curvature-deviation; unset: the server's default
  double curvature_deviation_flag = 0.0;      // its parsed value (note_given_flags)
  std::optional<double> wall_sizes;           // --wall-sizes; unset: the server's default
  double wall_sizes_flag = 0.0;               // its parsed value (note_given_flags)
};

// Adds the shared flags to `command`, with the help texts of IN and -o.
void add_mesh_command_flags(CLI::App& command, MeshCommandOptions& options,
                            const std::string& input_help, const std::string& output_help);
// Adds --ridge-angle, --corner-angle and --curvature-angle (SurfaceOptions).
void add_surface_angle_flags(CLI::App& command, MeshCommandOptions& options);
// After parsing: which of --size and --growth were given, and --curvature-angle's value if it
// was.
void note_given_flags(const CLI::App& command, MeshCommandOptions& options);

// What a command's call brought back.
struct MeshAnswer {
  Mesh mesh;
  std::string summary_json;                                // printed with --json
  std::function<void(const std::string& output)> print;   // the summary for a person
};

// The MeshAnswer of a call_mesh_volume or call_mesh_surface result, its summary printed by
// `print(output, summary)`.
template <class Result, class Print>
absl::StatusOr<MeshAnswer> mesh_answer(absl::StatusOr<Result> result, Print print) {
  if (!result.ok()) return result.status();
  return MeshAnswer{.mesh = std::move(result->mesh),
                    .summary_json = result->summary.json,
                    .print = [summary = result->summary, print](const std::string& output) {
                      print(output, summary);
                    }};
}

using MeshCall = std::function<absl::StatusOr<MeshAnswer>(
    const std::string& address, const Mesh& input, const VolumeCallOptions& options,
    const ProgressCallback& on_progress, const WarningCallback& on_warning)>;

struct MeshCommand {
  std::string name;  // "volume": messages start "afmesh volume: "
  // OUT's format must suit the result (checked before anything is read): exit 2 otherwise.
  std::function<absl::Status(const std::string& output)> check_output;
  // IN must suit the call (optional): exit 3 otherwise.
  std::function<absl::Status(const Mesh& input)> check_input;
  // The command's own call options (environments, remesh_surface); run_mesh_command sets the
  // size, the specification, the angles, the timeout, the canceller and the security.
  VolumeCallOptions call_options;
  MeshCall call;
};

// Prints a summary's timings on one line: "  time  receive 0.001 s  queue 0.000 s ...".
void print_timings(const std::vector<std::pair<std::string, double>>& timings);

// Runs `command` with `options`; returns the exit code (commands.h).
int run_mesh_command(const MeshCommandOptions& options, MeshCommand command);

}  // namespace afmesh::cli
