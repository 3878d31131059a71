// make-thin-examples EXAMPLES_DIR: writes the fronts of core/shapes/thin_shapes.h with their
// default parameters as EXAMPLES_DIR/dome/dome.mesh, EXAMPLES_DIR/sails/sails.mesh and
// EXAMPLES_DIR/crossing/crossing.mesh (Medit,
// triangle references = crossing-environment ids). The shipped files are its output;
// thin_examples_test checks that they still are.
//
// make-thin-examples --variants DIR: the same three families with other thicknesses,
// triangulations, boxes, heels and cambers, whole hemispherical shells, and plates crossing at
// ±30° with strips closing their rims (issue 10, part 6), as DIR/NAME.mesh, and one JSON
// line per front in DIR/thin.jsonl (name, family, file, parameters), for bench/sweep.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/shapes/thin_shapes.h"

namespace {

struct Variant {
  std::string name;
  std::string family;  // dome, sails or crossing: the shipped spec file of that family applies
  std::string parameters;  // JSON object
  afmesh::Mesh mesh;
};

std::vector<Variant> thin_variants() {
  std::vector<Variant> out;
  char text[256];
  for (const double thickness : {0.001, 0.01}) {
    for (const int inner : {8, 14, 20}) {
      for (const int extra : {2, 4}) {
        for (const double box : {3.0, 4.0}) {
          afmesh::QuarterDomeParams p;
          p.thickness = thickness;
          p.inner_divisions = inner;
          p.outer_divisions = inner + extra;
          p.box_side = box;
          std::snprintf(text, sizeof text, "dome_t%g_n%d_m%d_L%g", thickness, inner, inner + extra,
                        box);
          const std::string name = text;
          std::snprintf(text, sizeof text,
                        "{\"thickness\": %g, \"inner_divisions\": %d, \"outer_divisions\": %d, "
                        "\"box_side\": %g}",
                        thickness, inner, inner + extra, box);
          out.push_back({name, "dome", text, afmesh::quarter_dome_surface(p)});
        }
      }
    }
  }
  // The whole hemispherical shell (4 r box, box size r / 2), its sides in rings of
  // different counts and phases.
  for (const double thickness : {0.001, 0.01}) {
    for (const auto& [inner, outer] : {std::pair{20, 22}, std::pair{12, 15}}) {
      afmesh::HemisphericalShellParams p;
      p.thickness = thickness;
      p.inner_rings = inner;
      p.outer_rings = outer;
      std::snprintf(text, sizeof text, "shell_t%g_n%d_m%d", thickness, inner, outer);
      const std::string name = text;
      std::snprintf(text, sizeof text,
                    "{\"thickness\": %g, \"inner_rings\": %d, \"outer_rings\": %d}", thickness,
                    inner, outer);
      out.push_back({name, "dome", text, afmesh::hemispherical_shell_surface(p)});
    }
  }
  for (const double thickness : {0.001, 0.01}) {
    for (const double heel : {0.0, 10.0, 20.0}) {
      afmesh::SailsParams p;
      p.thickness = thickness;
      p.heel_deg = heel;
      std::snprintf(text, sizeof text, "sails_t%g_heel%g", thickness, heel);
      const std::string name = text;
      std::snprintf(text, sizeof text, "{\"thickness\": %g, \"heel_deg\": %g}", thickness, heel);
      out.push_back({name, "sails", text, afmesh::sails_surface(p)});
    }
  }
  // The large sails: about 15k sail triangles in a box some 20 chords wide.
  for (const double thickness : {0.001, 0.01}) {
    afmesh::SailsParams p;
    p.thickness = thickness;
    p.grid_scale = 4;
    p.box_scale = 3.0;
    p.box_size = 30.0;
    std::snprintf(text, sizeof text, "sails_t%g_grid4_box3", thickness);
    const std::string name = text;
    std::snprintf(text, sizeof text,
                  "{\"thickness\": %g, \"grid_scale\": 4, \"box_scale\": 3, \"box_size\": 30}",
                  thickness);
    out.push_back({name, "sails", text, afmesh::sails_surface(p)});
  }
  for (const double camber : {0.0, 0.02, 0.04}) {
    for (const int divisions : {3, 4, 6}) {
      for (const double thickness : {0.001, 0.01}) {
        afmesh::CrossingPlatesParams p;
        p.camber = camber;
        p.divisions = divisions;
        p.thickness = thickness;
        std::snprintf(text, sizeof text, "crossing_c%g_n%d_t%g", camber, divisions, thickness);
        const std::string name = text;
        std::snprintf(text, sizeof text,
                      "{\"camber\": %g, \"divisions\": %d, \"thickness\": %g}", camber,
                      divisions, thickness);
        out.push_back({name, "crossing", text, afmesh::crossing_plates_surface(p)});
      }
    }
  }
  // The plates crossing at ±30° whose rims are closed by strips of no environment.
  for (const double camber : {0.0, 0.02}) {
    for (const int divisions : {4, 8}) {
      for (const double thickness : {0.001, 0.01}) {
        afmesh::CrossingPlatesParams p;
        p.angle_deg = 60.0;
        p.rim_strips = true;
        p.camber = camber;
        p.divisions = divisions;
        p.thickness = thickness;
        std::snprintf(text, sizeof text, "strips60_c%g_n%d_t%g", camber, divisions, thickness);
        const std::string name = text;
        std::snprintf(text, sizeof text,
                      "{\"angle_deg\": 60, \"rim_strips\": true, \"camber\": %g, "
                      "\"divisions\": %d, \"thickness\": %g}",
                      camber, divisions, thickness);
        out.push_back({name, "crossing", text, afmesh::crossing_plates_surface(p)});
      }
    }
  }
  return out;
}

int write_variants(const std::string& dir) {
  std::FILE* list = std::fopen((dir + "/thin.jsonl").c_str(), "w");
  if (list == nullptr) {
    std::fprintf(stderr, "make-thin-examples: cannot write %s/thin.jsonl\n", dir.c_str());
    return 1;
  }
  for (const Variant& v : thin_variants()) {
    const std::string path = dir + "/" + v.name + ".mesh";
    if (const absl::Status status = afmesh::write_mesh(v.mesh, path); !status.ok()) {
      std::fprintf(stderr, "make-thin-examples: %s\n", std::string(status.message()).c_str());
      std::fclose(list);
      return 1;
    }
    std::fprintf(list,
                 "{\"name\": \"%s\", \"family\": \"%s\", \"file\": \"%s\", \"triangles\": %zu, "
                 "\"parameters\": %s}\n",
                 v.name.c_str(), v.family.c_str(), path.c_str(), v.mesh.triangles.size(),
                 v.parameters.c_str());
  }
  return std::fclose(list) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--variants") return write_variants(argv[2]);
  // One sails front with the given SailsParams (thin_shapes.h), for trying sizes by hand.
  if (argc == 7 && std::string(argv[1]) == "--sails") {
    afmesh::SailsParams p;
    p.thickness = std::atof(argv[2]);
    p.grid_scale = std::atoi(argv[3]);
    p.box_scale = std::atof(argv[4]);
    p.box_size = std::atof(argv[5]);
    return afmesh::write_mesh(afmesh::sails_surface(p), argv[6]).ok() ? 0 : 1;
  }
  // One hemispherical shell with the given HemisphericalShellParams.
  if (argc == 6 && std::string(argv[1]) == "--shell") {
    afmesh::HemisphericalShellParams p;
    p.thickness = std::atof(argv[2]);
    p.inner_rings = std::atoi(argv[3]);
    p.outer_rings = std::atoi(argv[4]);
    return afmesh::write_mesh(afmesh::hemispherical_shell_surface(p), argv[5]).ok() ? 0 : 1;
  }
  // One X of crossing plates with the given CrossingPlatesParams (rim strips: 1, tapered: 0).
  if (argc == 8 && std::string(argv[1]) == "--plates") {
    afmesh::CrossingPlatesParams p;
    p.angle_deg = std::atof(argv[2]);
    p.thickness = std::atof(argv[3]);
    p.camber = std::atof(argv[4]);
    p.divisions = std::atoi(argv[5]);
    p.rim_strips = std::atoi(argv[6]) != 0;
    return afmesh::write_mesh(afmesh::crossing_plates_surface(p), argv[7]).ok() ? 0 : 1;
  }
  if (argc != 2) {
    std::fprintf(stderr,
                 "usage: make-thin-examples EXAMPLES_DIR | --variants DIR\n"
                 "       make-thin-examples --sails THICKNESS GRID_SCALE BOX_SCALE BOX_SIZE OUT\n"
                 "       make-thin-examples --shell THICKNESS INNER_RINGS OUTER_RINGS OUT\n"
                 "       make-thin-examples --plates ANGLE THICKNESS CAMBER DIVISIONS STRIPS "
                 "OUT\n");
    return 2;
  }
  const std::string dir = argv[1];
  const struct {
    std::string path;
    afmesh::Mesh mesh;
  } outputs[] = {{dir + "/dome/dome.mesh", afmesh::quarter_dome_surface()},
                 {dir + "/sails/sails.mesh", afmesh::sails_surface()},
                 {dir + "/crossing/crossing.mesh", afmesh::crossing_plates_surface()}};
  for (const auto& [path, mesh] : outputs) {
    if (const absl::Status status = afmesh::write_mesh(mesh, path); !status.ok()) {
      std::fprintf(stderr, "make-thin-examples: %s\n", std::string(status.message()).c_str());
      return 1;
    }
    std::printf("%s: %zu points, %zu triangles\n", path.c_str(), mesh.points.size(),
                mesh.triangles.size());
  }
  return 0;
}
