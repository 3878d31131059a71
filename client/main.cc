// afmesh: command-line client. See ../shared/design.md for the command-line contract.
#include <iostream>

#include "client/commands.h"

int main(int argc, char** argv) {
  using namespace afmesh::cli;
  CLI::App app{"afmesh: advancing-front meshing service client"};
  app.require_subcommand(1);
  Action action;
  add_stats_command(app, action);
  add_convert_command(app, action);
  add_volume_command(app, action);
  add_surface_command(app, action);
  add_sizes_command(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  return action ? action() : kExitUsage;
}
