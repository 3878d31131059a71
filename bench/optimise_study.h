// The optimiser's effect measured on its own: the front meshed without optimisation, the quality
// before, optimise_tets with chosen steps (timed apart), the quality after, and the tets still
// under 10° and 20° grouped by how many of their points and faces lie on the boundary.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/quality/optimise.h"

namespace afmesh::bench {

// One way to run the optimiser, with its label (the steps and target it was made from).
struct StudyVariant {
  std::string label;
  OptimiseParams params;
};

struct StudyOptions {
  double size = 0.0;
  double growth = 1.0;
  std::vector<StudyVariant> variants;  // each run on its own copy of the same raw mesh
  bool json = false;
};

// Parses a comma-separated list of steps (edge, face, smooth, split, sweep, or none) into
// params, or leaves params alone for "default". Returns an error text naming the unknown step,
// or an empty string.
std::string set_optimise_steps(const std::string& list, OptimiseParams& params);

// Runs the study on `surface`, prints it (readable or one JSON line per variant) and returns the
// exit code.
int run_optimise_study(const std::string& shape, const Mesh& surface, const StudyOptions& o);

}  // namespace afmesh::bench
