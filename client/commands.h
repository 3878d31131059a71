// The afmesh command-line client: one subcommand per file, registered in main.cc.
#pragma once

#include <functional>

#include "CLI/CLI.hpp"

namespace afmesh::cli {

// Exit codes: scripts tell bad input from an invalid result from an unreachable server.
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,          // bad command line
  kExitBadInput = 3,       // an input file cannot be read or is malformed / invalid
  kExitInvalidMesh = 4,    // `stats`: the mesh was read but fails validation
  kExitUnavailable = 5,    // the server cannot be reached or started
  kExitMeshingFailed = 6,  // the server could not produce the mesh
  kExitInternal = 7,       // anything else (an output file cannot be written, ...)
  // The server refused the call's credentials (a missing or wrong bearer token). A refused TLS
  // handshake cannot be told from an unreachable server and exits with kExitUnavailable.
  kExitUnauthenticated = 8,
};

// A subcommand's action, run after a successful parse; returns the process exit code.
using Action = std::function<int()>;

// Each adds its subcommand to `app` and, when it is selected, stores its action in `action`.
void add_stats_command(CLI::App& app, Action& action);
void add_convert_command(CLI::App& app, Action& action);
void add_volume_command(CLI::App& app, Action& action);
void add_surface_command(CLI::App& app, Action& action);
void add_sizes_command(CLI::App& app, Action& action);

}  // namespace afmesh::cli
