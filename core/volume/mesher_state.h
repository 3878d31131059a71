// The state of one run of the volume front (paper §1): the growing point and element lists,
// the sizes attached to points (eq. 15) and the front. One MesherState per request; nothing is
// shared between runs.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/front/advancing_front.h"
#include "core/mesh/mesh.h"
#include "core/mesh/simplex_incidence.h"
#include "core/sizing/size_field.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::volume {

// A point the front may connect a face to (F7.2): an existing front point, or the new point at
// `position` when `point == kInvalidIndex`.
struct Candidate {
  Index point = kInvalidIndex;
  Point position{};
  double rank = 0;  // lower is tried first
  // A new point: the element sizes its distances from front faces and from front points are
  // checked with (new_point_is_clear).
  double clearance_size = 0;
  double spacing_size = 0;
};

struct MesherState {
  MesherState(const Mesh& input, double growth, const SizeField& size_field, const Box& domain,
              double cell_size);

  double growth;                // c_i of eq. 15
  const SizeField& size_field;  // delta_bg / delta_s
  bool size_field_varies;       // false for a UniformSize: one value everywhere
  Index input_points = 0;
  std::vector<Point> points;
  std::vector<double> point_size;  // delta of each point (eq. 15)
  // Crossing environments (paper §2): LPOCR per point (0 none, -1 on several, new points 0);
  // empty when the input has none. The environment of a front face is FrontItem::env (LFACR).
  std::vector<std::int32_t> point_env;
  // Points of the input faces of no environment whose points are all ridge points (-1): the
  // strips closing plates' rims between their two sides (environments.h). Empty when there are
  // none.
  std::vector<bool> rim_strip_point;
  // Per input point, on a front with a sliver face (is_sliver_face, so no crossing
  // environments), whether it is a corner of a poor input face, one whose best element is under
  // kRetryMarkQuality (mark_poor_input_faces): the faces touching one retry at once under later
  // rules (touches_input_sliver). Empty when the input has no sliver face.
  std::vector<bool> input_sliver_point;
  // The input front has sliver faces: new points closer to a face keep the best point's spacing
  // from front points, and a face takes first the far corner of a neighbour that looks back at
  // it across a thin wedge (gather_candidates, wedge_apex_candidates; on fronts with crossing
  // environments only the faces that have failed once, wedge_apex_angle).
  bool sliver_front() const { return !input_sliver_point.empty(); }
  bool is_input_sliver_point(Index p) const {
    return p < static_cast<Index>(input_sliver_point.size()) && input_sliver_point[p];
  }
  std::vector<Tet> tets;           // a deleted tet has tet[0] == kInvalidIndex
  std::int64_t live_tets = 0;
  // Sum of the live tets' volumes (a measure, for the guard against overlapping elements).
  double meshed_volume = 0;
  SimplexIncidence<4> incidence;  // the tets around each point (cavity repair, F7.3)
  AdvancingFront<3> front;  // the faces of the volume front

  // Scratch buffers reused for every face: no allocation per element in the loop.
  std::vector<Index> near_faces;
  std::vector<Candidate> candidates;
  std::vector<Index> cavity;
  std::vector<Index> tets_around;  // element_crosses_front's look at the tets on a point
  // Per point, where it lies against the faces of the element being checked (F7.3): the code in
  // the low 8 bits, valid when the high 24 bits equal side_epoch.
  std::vector<std::uint32_t> side_codes;
  std::uint32_t side_epoch = 0;
  // The front face the last element found crossing by its bins' walk met (element_crosses_front
  // tests it first); a slot index, possibly of a face deleted since, or kInvalidIndex.
  Index last_crossed_face = kInvalidIndex;
  // Front faces and points element_crosses_front (F7.3) has tested: the job's work, most of its
  // time, counted against its budget (VolumeBudget).
  std::int64_t face_tests = 0;
  std::int64_t searches = 0;  // face deletions tried (F7), also counted against the budget
  // Face deletions and, of face_tests, the front points element_crosses_front has looked at, in
  // the current window of adapt_bins_when_crowded.
  BinsWatch bins_watch;
};

}  // namespace afmesh::volume
