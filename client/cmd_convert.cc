// afmesh convert IN OUT: any supported mesh format to any other, by file extension.
#include <iostream>
#include <memory>
#include <string>

#include "client/commands.h"
#include "core/io/mesh_io.h"

namespace afmesh::cli {
namespace {

struct ConvertOptions {
  std::string in;
  std::string out;
  bool ascii_stl = false;
};

int run_convert(const ConvertOptions& o) {
  ReadReport notes;
  absl::StatusOr<Mesh> mesh = read_mesh(o.in, &notes);
  if (!mesh.ok()) {
    std::cerr << "afmesh convert: " << mesh.status().message() << "\n";
    return kExitBadInput;
  }
  for (const std::string& n : notes.notes) std::cerr << "afmesh convert: note: " << n << "\n";
  WriteOptions options;
  options.binary_stl = !o.ascii_stl;
  if (absl::Status st = write_mesh(*mesh, o.out, options); !st.ok()) {
    std::cerr << "afmesh convert: " << st.message() << "\n";
    return st.code() == absl::StatusCode::kInvalidArgument ? kExitBadInput : kExitInternal;
  }
  return kExitOk;
}

}  // namespace

void add_convert_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand("convert", "Convert a mesh file to another format");
  cmd->add_option("in", opts->in, "Input mesh (.stl .obj .msh .mesh)")->required();
  cmd->add_option("out", opts->out, "Output mesh (.stl .obj .msh .mesh .vtu)")->required();
  cmd->add_flag("--ascii-stl", opts->ascii_stl, "Write STL as text instead of binary");
  cmd->callback([opts, &action] { action = [opts] { return run_convert(*opts); }; });
}

}  // namespace afmesh::cli
