// afmesh volume IN -o OUT [--size H] [--growth C] [--spec SPEC.json] [--envs auto|tags|none]
//                         [--max-reruns N]
//                         [--remesh-surface [--ridge-angle DEG] [--corner-angle DEG]
//                                           [--curvature-angle DEG] [--curvature-deviation E]
//                                           [--wall-sizes F]]
//                         [--server ADDR] [--retries N]
//                         [--tls-ca FILE [--tls-cert FILE --tls-key FILE]]
//                         [--token-file FILE] [--json] [--quiet] [--timeout SEC]
// Fills the closed front in IN with tetrahedra through the MeshVolume call and writes OUT.
// --spec sends a whole size specification (sources, background grid; design.md, "Size
// specification"); --size and --growth, when given, override its maxSize and growth.
// --envs marks crossing environments (paper §2) so that the two sides of thin structures may
// nearly touch or cross: `tags` reads them from the triangle tags (Medit references, Gmsh
// physical tags; 0 = none), `auto` lets the server find them; default none.
// Without --server a private afmesh-server runs for the command on a local socket: the same
// code path as a remote server. Formats follow the file extensions (core/io/mesh_io.h).
// --max-reruns bounds how many times a front that stops is meshed again with the size halved
// where it stopped (VolumeOptions.max_reruns).
// --remesh-surface re-triangulates IN on the server first (as `afmesh surface` does), then fills
// the new surface, in one call and one server job; OUT's boundary is then the new surface.
// The flags and the run it shares with `afmesh surface` are client/mesh_command.h's.
// --tls-ca, --tls-cert, --tls-key and --token-file match a shared server's --tls-cert, --tls-key,
// --tls-client-ca and --token-file (client/channel_credentials.h); they need --server.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/string_view.h"
#include "client/commands.h"
#include "client/mesh_command.h"
#include "client/volume_call.h"
#include "core/environments/environments.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::cli {
namespace {

struct VolumeCommandOptions {
  MeshCommandOptions mesh;
  std::string envs = "none";  // auto, tags or none
  bool remesh_surface = false;
  std::optional<int> max_reruns;  // --max-reruns; unset: the server's default
  int max_reruns_flag = 0;        // its parsed value
};

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

// With --envs tags, IN must carry environment ids.
absl::Status check_tags(const Mesh& front, const std::string& input) {
  if (has_positive_tags(front)) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrFormat(
      "--envs tags: none of the %d triangles of %s carries a positive tag (Medit triangle "
      "reference or Gmsh physical tag), so there are no crossing environments to read; tag "
      "each side of a thin region with an id > 0, or use --envs auto",
      front.triangles.size(), input));
}

void print_summary(const std::string& output, const VolumeSummary& summary) {
  std::printf("%s: %llu points, %llu boundary triangles, %llu tetrahedra\n", output.c_str(),
              static_cast<unsigned long long>(summary.point_count),
              static_cast<unsigned long long>(summary.triangle_count),
              static_cast<unsigned long long>(summary.tet_count));
  if (summary.surface_remeshed) {
    std::printf("  boundary         the input re-triangulated first (--remesh-surface)\n");
  }
  std::printf("  dihedral angles  min %.2f°  max %.2f°  (%.3f%% of tets < 10°, %.3f%% < 20°)\n",
              summary.min_dihedral_deg, summary.max_dihedral_deg, 100 * summary.share_below_10_deg,
              100 * summary.share_below_20_deg);
  // Boundary slivers make the tets round them as flat (QualityFigures): the figures away from
  // them say what the mesher made where the input leaves it free.
  if (summary.boundary_sliver_count > 0) {
    std::printf(
        "  input slivers    %llu boundary triangles with an angle under %g° (down to %.2f°); "
        "the tets round them are about as flat\n",
        static_cast<unsigned long long>(summary.boundary_sliver_count), kSliverTriangleDeg,
        summary.boundary_min_angle_deg);
    if (summary.tets_away_from_slivers > 0)
      std::printf("  away from them   min dihedral %.2f°  (%.3f%% of %llu tets < 20°)\n",
                  summary.min_dihedral_away_from_slivers_deg,
                  100 * summary.share_away_from_slivers_below_20_deg,
                  static_cast<unsigned long long>(summary.tets_away_from_slivers));
  }
  std::printf("  radius ratio     min %.4f  mean %.4f\n", summary.min_radius_ratio,
              summary.mean_radius_ratio);
  std::printf("  validation       %s\n", summary.validation_passed ? "passed" : "FAILED");
  for (const std::string& message : summary.validation_messages) {
    std::printf("    %s\n", message.c_str());
  }
  print_timings(summary.timings);
}

// A front that stopped where a re-triangulated surface would not (the server's message says so,
// kRetriangulatedSurfaceAdvice) is told which flag does that, unless it was given; and one that
// stopped again after every rerun the job allowed (the message says "after meshing again N
// times ...") that --max-reruns allows more, unless N is the most. Said of a failure, and of the
// warning when the volume was then filled from the front's points instead (the flags may still
// give a mesh of the size asked).
std::string with_hints(absl::string_view message, bool remesh_surface, int max_reruns) {
  std::string out(message);
  if (!remesh_surface && absl::StrContains(message, kRetriangulatedSurfaceAdvice))
    absl::StrAppend(&out,
                    "; --remesh-surface re-triangulates IN at the size first, in the same call "
                    "(OUT's boundary is then the new surface)");
  if (max_reruns < kMaxLocalRefinements &&
      absl::StrContains(message, meshed_again_times(max_reruns)))
    absl::StrAppend(&out,
                    absl::StrFormat("; --max-reruns N (up to %d) meshes it again more times, "
                                    "each run up to as long as one",
                                    kMaxLocalRefinements));
  return out;
}

absl::StatusOr<MeshAnswer> with_hints(absl::StatusOr<MeshAnswer> answer, bool remesh_surface,
                                      int max_reruns) {
  if (answer.ok() || answer.status().code() != absl::StatusCode::kFailedPrecondition)
    return answer;
  return absl::FailedPreconditionError(
      with_hints(answer.status().message(), remesh_surface, max_reruns));
}

int run_volume(const VolumeCommandOptions& options) {
  MeshCommand command;
  command.name = "volume";
  command.check_output = check_output_path;
  if (options.envs == "tags") {
    command.check_input = [input = options.mesh.input](const Mesh& front) {
      return check_tags(front, input);
    };
  }
  command.call_options.environments = options.envs == "tags"   ? EnvironmentSource::kTags
                                      : options.envs == "auto" ? EnvironmentSource::kAuto
                                                               : EnvironmentSource::kNone;
  command.call_options.remesh_surface = options.remesh_surface;
  command.call_options.max_reruns = options.max_reruns;
  command.call = [](const std::string& address, const Mesh& front,
                    const VolumeCallOptions& call_options, const ProgressCallback& on_progress,
                    const WarningCallback& on_warning) -> absl::StatusOr<MeshAnswer> {
    const int max_reruns = call_options.max_reruns.value_or(VolumeParams{}.local_refinements);
    const WarningCallback hinted = [&](std::string_view warning) {
      const absl::string_view message(warning.data(), warning.size());
      on_warning(absl::StrContains(message, kDelaunayFillWords)
                     ? with_hints(message, call_options.remesh_surface, max_reruns)
                     : std::string(warning));
    };
    return with_hints(
        mesh_answer(call_mesh_volume(address, front, call_options, on_progress, hinted),
                    print_summary),
        call_options.remesh_surface, max_reruns);
  };
  return run_mesh_command(options.mesh, std::move(command));
}

}  // namespace

void add_volume_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<VolumeCommandOptions>();
  CLI::App* command =
      app.add_subcommand("volume", "fill a closed triangulated front with tetrahedra");
  add_mesh_command_flags(*command, options->mesh,
                         "closed, outward-oriented front (.stl .obj .msh .mesh)",
                         "volume mesh to write (.msh .mesh .vtu)");
  command
      ->add_option("--envs", options->envs,
                   "crossing environments for thin or crossing surfaces (paper §2): tags "
                   "(environment id = triangle tag), auto (found by the server) or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "tags", "none"}));
  CLI::Option* remesh = command->add_flag(
      "--remesh-surface", options->remesh_surface,
      "re-triangulate IN at the size first (as `afmesh surface`), then fill the new surface, in "
      "one server job; OUT's boundary is the new surface");
  command
      ->add_option("--max-reruns", options->max_reruns_flag,
                   absl::StrFormat("how many times a front that stops is meshed again with the "
                                   "size halved where it stopped, each run taking up to as long "
                                   "as a whole run (default %d; 0: fail where it first stops)",
                                   VolumeParams{}.local_refinements))
      ->check(CLI::Range(0, kMaxLocalRefinements));
  add_surface_angle_flags(*command, options->mesh);
  command->get_option("--ridge-angle")->needs(remesh);
  command->get_option("--corner-angle")->needs(remesh);
  command->get_option("--curvature-angle")->needs(remesh);
  command->get_option("--curvature-deviation")->needs(remesh);
  command->get_option("--wall-sizes")->needs(remesh);
  command->callback([options, command, &action] {
    note_given_flags(*command, options->mesh);
    if (command->count("--max-reruns") > 0) options->max_reruns = options->max_reruns_flag;
    action = [options] { return run_volume(*options); };
  });
}

}  // namespace afmesh::cli
