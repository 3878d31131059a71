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

int TetIncidence::corner_of(const Tet& tet, Index p) {
  for (int k = 0; k < 4; ++k)
    if (tet[k] == p) return k;
  return -1;
}

void TetIncidence::add(const std::vector<Tet>& tets, Index t) {
  if (next_.size() <= static_cast<std::size_t>(t)) next_.resize(t + 1);
  for (int k = 0; k < 4; ++k) {
    const Index p = tets[t][k];
    if (first_.size() <= static_cast<std::size_t>(p)) first_.resize(p + 1, kInvalidIndex);
    next_[t][k] = first_[p];
    first_[p] = t;
  }
}

void TetIncidence::remove(const std::vector<Tet>& tets, Index t) {
  for (int k = 0; k < 4; ++k) {
    const Index p = tets[t][k];
    Index* link = &first_[p];
    while (*link != t) {
      const Index u = *link;
      link = &next_[u][corner_of(tets[u], p)];
    }
    *link = next_[t][k];
  }
}

void TetIncidence::tets_of(const std::vector<Tet>& tets, Index p, std::vector<Index>& out) const {
  if (static_cast<std::size_t>(p) >= first_.size()) return;
  for (Index t = first_[p]; t != kInvalidIndex; t = next_[t][corner_of(tets[t], p)])
    out.push_back(t);
}

}  // namespace afmesh::volume
