// afmesh surface IN -o OUT [--size H] [--growth C] [--spec SPEC.json] [--ridge-angle DEG]
//                          [--corner-angle DEG] [--curvature-angle DEG]
//                          [--curvature-deviation E] [--wall-sizes F] [--server ADDR] [--retries N]
//                          [--tls-ca FILE [--tls-cert FILE --tls-key FILE]] [--token-file FILE]
//                          [--json] [--quiet] [--timeout SEC]
// Re-triangulates the surface in IN at the size asked through the MeshSurface call (paper §3),
// keeping its ridges and corners, and writes OUT with the input's tags on its patches. The
// flags, the private server and the exit codes are `afmesh volume`'s (client/mesh_command.h).
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "absl/strings/str_format.h"
#include "client/commands.h"
#include "client/mesh_command.h"
#include "client/volume_call.h"
#include "core/io/mesh_io.h"

namespace afmesh::cli {
namespace {

// Any format that holds triangles will do.
absl::Status check_output_path(const std::string& path) {
  return format_from_path(path).status();
}

void print_summary(const std::string& output, const SurfaceSummary& summary) {
  std::printf("%s: %llu points, %llu triangles\n", output.c_str(),
              static_cast<unsigned long long>(summary.point_count),
              static_cast<unsigned long long>(summary.triangle_count));
  std::printf("  angles     min %.2f°  max %.2f°  (%.3f%% of triangles < 30°, %llu < 15°",
              summary.min_angle_deg, summary.max_angle_deg, 100 * summary.share_below_30_deg,
              static_cast<unsigned long long>(summary.count_below_15_deg));
  if (summary.count_below_15_deg > 0)
    std::printf(", %llu of them at input triangles or corners as thin",
                static_cast<unsigned long long>(summary.count_below_15_deg_at_thinner_input));
  std::printf(")\n");
  std::printf("  features   %llu patches, %llu lines, %llu corners\n",
              static_cast<unsigned long long>(summary.patches),
              static_cast<unsigned long long>(summary.lines),
              static_cast<unsigned long long>(summary.corners));
  if (summary.patches_from_input > 0)
    std::printf("  fallback   %llu patches re-triangulated from their input (their fronts "
                "stopped: see the warnings)\n",
                static_cast<unsigned long long>(summary.patches_from_input));
  std::printf("  distance   Hausdorff %.4g, vertices at most %.4g (model size %.4g)\n",
              summary.hausdorff, summary.max_vertex_distance, summary.model_size);
  print_timings(summary.timings);
}

absl::StatusOr<MeshAnswer> call_surface(const std::string& address, const Mesh& input,
                                        const VolumeCallOptions& options,
                                        const ProgressCallback& on_progress,
                                        const WarningCallback& on_warning) {
  return mesh_answer(call_mesh_surface(address, input, options, on_progress, on_warning),
                     print_summary);
}

}  // namespace

void add_surface_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<MeshCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "surface", "re-triangulate a triangulated surface at a size, keeping ridges and corners");
  add_mesh_command_flags(*command, *options, "triangulated surface (.stl .obj .msh .mesh)",
                         "surface to write (.stl .obj .msh .mesh .vtu)");
  add_surface_angle_flags(*command, *options);
  command->callback([options, command, &action] {
    note_given_flags(*command, *options);
    action = [options] {
      return run_mesh_command(*options, MeshCommand{.name = "surface",
                                                    .check_output = check_output_path,
                                                    .check_input = {},
                                                    .call_options = {},
                                                    .call = call_surface});
    };
  });
}

}  // namespace afmesh::cli
