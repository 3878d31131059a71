// F8–F10 of the volume front, and the local back-off that re-opens a cavity.
#include <algorithm>

#include "core/quality/measures.h"
#include "core/volume/front_steps.h"

namespace afmesh::volume {
namespace {

double tet_volume(const MesherState& s, const Tet& k) {
  return tet_signed_volume(s.points[k[0]], s.points[k[1]], s.points[k[2]], s.points[k[3]]);
}

// Deletes live tet t and updates the front around the hole it leaves: each of its faces that
// was on the front leaves it (both sides are now unmeshed); each other face (shared with a live
// tet or on the input boundary) joins it, looking into the hole.
void delete_tet(MesherState& s, Index t) {
  const Tet k = s.tets[t];
  // Faces of the positive tet (a, b, c, d), oriented out of it.
  const Triangle faces[4] = {{k[0], k[2], k[1]}, {k[0], k[1], k[3]}, {k[1], k[2], k[3]},
                             {k[0], k[3], k[2]}};
  for (const Triangle& f : faces) {
    if (auto g = s.front.find(f)) {  // a front face looking out of t
      s.front.remove(*g);
    } else {
      const Triangle inward{f[0], f[2], f[1]};
      const Index env = face_environment(s, inward);
      s.front.add(inward, queue_size_for_face(s, inward, env), env);
    }
  }
  s.incidence.remove(s.tets, t);
  s.meshed_volume -= tet_volume(s, k);
  s.tets[t][0] = kInvalidIndex;
  --s.live_tets;
}

}  // namespace

void add_element(MesherState& s, Index face, Index p) {
  const Triangle v = s.front.item(face).v;
  const Index t = static_cast<Index>(s.tets.size());
  s.tets.push_back({v[0], v[1], v[2], p});  // F8
  s.incidence.add(s.tets, t);
  s.meshed_volume += tet_volume(s, s.tets[t]);
  ++s.live_tets;
  s.front.remove(face);  // F10
  const Triangle sides[3] = {{v[0], v[1], p}, {v[1], v[2], p}, {v[2], v[0], p}};
  for (const Triangle& side : sides) {
    // F10: the element closes the front face facing it (the side reversed). A face with the
    // side's own orientation would look into the same space as the element: that is another
    // layer's face where two sides of a thin region cross (paper §2), not one to close.
    if (auto g = s.front.find({side[0], side[2], side[1]})) {
      s.front.remove(*g);
    } else {
      const Index env = face_environment(s, side);
      s.front.add(side, queue_size_for_face(s, side, env), env);  // F8, F9
    }
  }
}

std::int64_t open_cavity(MesherState& s, Index face, int rings) {
  std::vector<Index>& cavity = s.cavity;
  cavity.clear();
  for (Index p : s.front.item(face).v) s.incidence.elements_of(s.tets, p, cavity);
  for (int ring = 1; ring < rings; ++ring) {
    std::sort(cavity.begin(), cavity.end());
    cavity.erase(std::unique(cavity.begin(), cavity.end()), cavity.end());
    const std::size_t n = cavity.size();
    for (std::size_t i = 0; i < n; ++i)
      for (Index p : s.tets[cavity[i]]) s.incidence.elements_of(s.tets, p, cavity);
  }
  std::sort(cavity.begin(), cavity.end());
  cavity.erase(std::unique(cavity.begin(), cavity.end()), cavity.end());
  for (Index t : cavity) delete_tet(s, t);
  return static_cast<std::int64_t>(cavity.size());
}

}  // namespace afmesh::volume
