// Point-to-element incidence of a growing and shrinking list of simplices (triangles M×3 or
// tets K×4, indices into the caller's array): per point, the live elements that use it, as a
// linked list through the elements' corners (no allocation per element beyond two arrays).
// Elements enter with add() and leave with remove() (before the caller overwrites or drops
// them); the caller keeps the element array, which may grow between calls.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

template <std::size_t Arity>
class SimplexIncidence {
 public:
  using Simplex = std::array<Index, Arity>;

  // The incidence of every element of `elements` (all live).
  static SimplexIncidence of(const std::vector<Simplex>& elements) {
    SimplexIncidence incidence;
    for (Index t = 0; t < static_cast<Index>(elements.size()); ++t) incidence.add(elements, t);
    return incidence;
  }

  // Element t (elements[t], live, not yet added) joins the lists of its corners.
  void add(const std::vector<Simplex>& elements, Index t) {
    if (next_.size() <= static_cast<std::size_t>(t)) next_.resize(t + 1);
    for (std::size_t k = 0; k < Arity; ++k) {
      const Index p = elements[t][k];
      if (first_.size() <= static_cast<std::size_t>(p)) first_.resize(p + 1, kInvalidIndex);
      next_[t][k] = first_[p];
      first_[p] = t;
    }
  }
  // Element t (added, with its corners unchanged since) leaves the lists of its corners.
  void remove(const std::vector<Simplex>& elements, Index t) {
    for (std::size_t k = 0; k < Arity; ++k) {
      const Index p = elements[t][k];
      Index* link = &first_[p];
      while (*link != t) {
        const Index u = *link;
        link = &next_[u][corner_of(elements[u], p)];
      }
      *link = next_[t][k];
    }
  }
  // Appends the live elements using point p to `out`, the last added first.
  void elements_of(const std::vector<Simplex>& elements, Index p, std::vector<Index>& out) const {
    if (p < 0 || static_cast<std::size_t>(p) >= first_.size()) return;
    for (Index t = first_[p]; t != kInvalidIndex; t = next_[t][corner_of(elements[t], p)])
      out.push_back(t);
  }

 private:
  static std::size_t corner_of(const Simplex& s, Index p) {
    std::size_t k = 0;
    while (k + 1 < Arity && s[k] != p) ++k;
    return k;
  }
  std::vector<Index> first_;                  // per point: its last added live element
  std::vector<std::array<Index, Arity>> next_;  // per element and corner: the next in the list
};

// The points other than p of the elements `fan` (indices into `elements`), each once,
// ascending: p's neighbours when `fan` is the elements round p (SimplexIncidence::elements_of),
// for the link condition of an edge collapse.
template <std::size_t Arity>
void corners_of_fan(const std::vector<std::array<Index, Arity>>& elements,
                    const std::vector<Index>& fan, Index p, std::vector<Index>& out) {
  out.clear();
  for (const Index t : fan)
    for (const Index r : elements[t])
      if (r != p) out.push_back(r);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace afmesh
