#include "core/volume/mesher_state.h"

namespace afmesh::volume {

MesherState::MesherState(const Mesh& input, double growth_in, const SizeField& size_field_in,
                         const Box& domain, double cell_size)
    : growth(growth_in),
      size_field(size_field_in),
      size_field_varies(dynamic_cast<const UniformSize*>(&size_field_in) == nullptr),
      input_points(static_cast<Index>(input.points.size())),
      points(input.points),
      front(points, domain, cell_size) {}

}  // namespace afmesh::volume
