// The wall time of one stage of a meshing job (validate, front, optimise, ...), as the core
// reports it in every result and the server streams it in the Summary.
#pragma once

#include <string>

namespace afmesh {

struct StageTiming {
  std::string stage;   // e.g. "validate", "front", "optimise"
  double seconds = 0;  // wall time
};

}  // namespace afmesh
