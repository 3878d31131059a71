// F1 for fronts as real files bring them: repeated-point triangles dropped, components oriented
// consistently and outward by nesting (not in the paper; see repair_front.h).
#include "core/volume/repair_front.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_format.h"
#include "core/geometry/vec.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate_common.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

// A winding number further than this from an integer is not trusted (the point lies on or very
// near the other component, or the components cross).
constexpr double kWindingTolerance = 0.2;
// A component whose enclosed volume is below this share of the rounding scale of its volume sum
// (the sum of the terms' magnitudes) has no trustworthy sign: a sheet folded flat, say.
constexpr double kVolumeSignTolerance = 1e-9;

void flip(Triangle& t) { std::swap(t[1], t[2]); }

// The edge neighbours of the triangles after the ones marked in `turn` were flipped (flip):
// (a, c, b) has (a, b, c)'s edges in slots 2, 1, 0, each reversed, so a turned triangle's slots
// 0 and 2 swap, and an edge between a turned triangle and one that is not changes its same_way
// flag (seen from both sides). The same as triangle_edge_neighbours of the flipped triangles.
EdgeNeighbours turned_neighbours(EdgeNeighbours n, const std::vector<char>& turn) {
  for (std::size_t t = 0; t < turn.size(); ++t) {
    if (!turn[t]) continue;
    std::swap(n.across[t][0], n.across[t][2]);
    std::swap(n.same_way[t][0], n.same_way[t][2]);
  }
  for (std::size_t t = 0; t < turn.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index g = n.across[t][k];
      if (g != kInvalidIndex && turn[t] != turn[g]) n.same_way[t][k] = !n.same_way[t][k];
    }
  return n;
}

// Step 1: the triangles that do not repeat a point, with their tags, into `triangles` and `tags`
// (filled only when some triangle repeats a point). Returns how many repeat one.
std::int64_t without_repeated_points(const Mesh& front, std::vector<Triangle>& triangles,
                                     std::vector<Index>& tags) {
  const std::int64_t repeated = std::count_if(
      front.triangles.begin(), front.triangles.end(),
      [](const Triangle& t) { return !has_distinct_indices(t); });
  if (repeated == 0) return 0;
  for (std::size_t t = 0; t < front.triangles.size(); ++t) {
    if (!has_distinct_indices(front.triangles[t])) continue;
    triangles.push_back(front.triangles[t]);
    tags.push_back(front.triangle_tags[t]);
  }
  return repeated;
}

// The triangle sides without exactly one neighbour across them (the sides of open and of
// non-manifold edges); 0 when every edge has exactly two triangles (closed, manifold along edges).
std::int64_t unpaired_sides(const EdgeNeighbours& adjacency) {
  std::int64_t count = 0;
  for (const std::array<Index, 3>& across : adjacency.across)
    for (const Index u : across) count += u == kInvalidIndex;
  return count;
}

// Step 2: labels the edge-connected components and, per triangle, whether it must turn to agree
// with its component's first triangle. False when some component cannot be oriented (a walk
// around it comes back turned: a non-orientable surface).
bool orient_components(const EdgeNeighbours& adjacency, std::vector<Index>& component,
                       std::vector<char>& turn, Index& component_count) {
  const std::size_t m = adjacency.across.size();
  component.assign(m, kInvalidIndex);
  turn.assign(m, 0);
  component_count = 0;
  std::vector<Index> queue;
  for (std::size_t seed = 0; seed < m; ++seed) {
    if (component[seed] != kInvalidIndex) continue;
    const Index c = component_count++;
    component[seed] = c;
    queue.assign(1, static_cast<Index>(seed));
    for (std::size_t i = 0; i < queue.size(); ++i) {
      const Index t = queue[i];
      for (int k = 0; k < 3; ++k) {
        const Index u = adjacency.across[t][k];
        if (u == kInvalidIndex) continue;
        // Two triangles agree when they traverse their edge in opposite directions.
        const char u_turn = static_cast<char>(turn[t] ^ (adjacency.same_way[t][k] ? 1 : 0));
        if (component[u] == kInvalidIndex) {
          component[u] = c;
          turn[u] = u_turn;
          queue.push_back(u);
        } else if (turn[u] != u_turn) {
          return false;
        }
      }
    }
  }
  return true;
}

// The solid angle that triangle (a, b, c) subtends at x, signed by its orientation
// (Van Oosterom and Strackee, 1983).
double solid_angle(const Point& x, const Point& a, const Point& b, const Point& c) {
  const Point p = sub(a, x), q = sub(b, x), r = sub(c, x);
  const double lp = norm(p), lq = norm(q), lr = norm(r);
  const double numerator = dot(p, cross(q, r));
  const double denominator = lp * lq * lr + dot(p, q) * lr + dot(p, r) * lq + dot(q, r) * lp;
  return 2.0 * std::atan2(numerator, denominator);
}

struct Component {
  std::vector<Triangle> triangles;  // oriented consistently (after step 2)
  std::vector<Index> ids;           // positions in the front
  Box box;
  double volume = 0;                // enclosed, signed by the orientation
  bool sign_known = false;
  Point sample{};                   // the centroid of its largest triangle
};

std::vector<Component> split_components(const Mesh& front, const std::vector<Index>& component,
                                        const std::vector<char>& turn, Index count) {
  std::vector<Component> parts(static_cast<std::size_t>(count));
  for (Component& part : parts) part.box = empty_box();
  for (std::size_t t = 0; t < front.triangles.size(); ++t) {
    Component& part = parts[component[t]];
    Triangle v = front.triangles[t];
    if (turn[t]) flip(v);
    part.triangles.push_back(v);
    part.ids.push_back(static_cast<Index>(t));
    for (Index p : v) enclose(part.box, front.points[p]);
  }
  for (Component& part : parts) {
    double magnitude = 0;
    part.volume = enclosed_volume(front.points, part.triangles, &magnitude);
    part.sign_known = std::abs(part.volume) > kVolumeSignTolerance * magnitude;
    double largest = -1;
    for (const Triangle& v : part.triangles) {
      const Point& a = front.points[v[0]];
      const Point& b = front.points[v[1]];
      const Point& c = front.points[v[2]];
      const double area = norm(cross(sub(b, a), sub(c, a)));
      if (area > largest) {
        largest = area;
        part.sample = scale(add(a, add(b, c)), 1.0 / 3.0);
      }
    }
  }
  return parts;
}

bool inside_box(const Box& box, const Point& x) {
  for (int a = 0; a < 3; ++a)
    if (x[a] < box.lo[a] || x[a] > box.hi[a]) return false;
  return true;
}

// Step 3: how many other components enclose part `c`'s sample point; -1 when some winding
// number is not clearly an integer.
int nesting_depth(const Mesh& front, const std::vector<Component>& parts, std::size_t c) {
  int depth = 0;
  for (std::size_t d = 0; d < parts.size(); ++d) {
    if (d == c || !inside_box(parts[d].box, parts[c].sample)) continue;
    double angle = 0;
    for (const Triangle& v : parts[d].triangles)
      angle += solid_angle(parts[c].sample, front.points[v[0]], front.points[v[1]],
                           front.points[v[2]]);
    // About a consistently oriented closed surface: +-1 inside (by its orientation), 0 outside.
    const double winding = std::abs(angle / (4.0 * std::numbers::pi));
    const double nearest = std::round(winding);
    if (std::abs(winding - nearest) > kWindingTolerance || nearest > 1) return -1;
    depth += static_cast<int>(nearest);
  }
  return depth;
}

}  // namespace

std::vector<std::string> FrontRepairReport::notes() const {
  std::vector<std::string> out;
  if (triangles_dropped > 0)
    out.push_back(absl::StrFormat(
        "dropped %d triangle(s) that repeat a point (no area); the rest of the surface is closed",
        triangles_dropped));
  if (triangles_reoriented > 0)
    out.push_back(absl::StrFormat(
        "re-oriented %d triangle(s) so that each of the %d closed component(s) is consistently "
        "oriented, outer walls facing out and the %d cavity(ies) facing in (%d component(s) "
        "turned whole)",
        triangles_reoriented, components, cavities, components_turned));
  return out;
}

std::string FrontRepairReport::why_repeated_points_kept() const {
  if (repeated_points_kept == 0) return "";
  if (triangle_sides_unpaired == 0)
    return absl::StrFormat("the %d triangle(s) that repeat a point are all there is",
                           repeated_points_kept);
  return absl::StrFormat(
      "the %d triangle(s) that repeat a point were not dropped: without them %d triangle side(s) "
      "still have no single neighbour across them (the surface is open or non-manifold there, "
      "which a volume cannot be meshed from)",
      repeated_points_kept, triangle_sides_unpaired);
}

FrontRepairReport repair_front(Mesh& front, EdgeNeighbours* neighbours) {
  FrontRepairReport report;
  if (neighbours != nullptr) *neighbours = {};
  front.triangle_tags.resize(front.triangles.size(), 0);
  // Step 1, kept only when the rest is closed and manifold: then one edge adjacency serves the
  // check and steps 2-3.
  std::vector<Triangle> kept;
  std::vector<Index> kept_tags;
  const std::int64_t repeated = without_repeated_points(front, kept, kept_tags);
  const std::vector<Triangle>& triangles = repeated > 0 ? kept : front.triangles;
  EdgeNeighbours adjacency = triangle_edge_neighbours(triangles);
  const std::int64_t unpaired = unpaired_sides(adjacency);
  if ((repeated > 0 && kept.empty()) || unpaired > 0) {
    report.skipped_because = repeated > 0 ? "a triangle repeats a point"
                                          : "the surface has open or non-manifold edges";
    report.repeated_points_kept = repeated;
    report.triangle_sides_unpaired = repeated > 0 ? unpaired : 0;
    return report;
  }
  if (repeated > 0) {
    front.triangles = std::move(kept);
    front.triangle_tags = std::move(kept_tags);
    report.triangles_dropped = repeated;
  }
  std::vector<Index> component;
  std::vector<char> turn;
  Index count = 0;
  if (!orient_components(adjacency, component, turn, count)) {
    report.skipped_because = "a component cannot be oriented (non-orientable)";
    return report;
  }
  report.components = count;
  // Of a component's two orientations, start from the one that turns fewer triangles.
  std::vector<std::int64_t> turned(static_cast<std::size_t>(count), 0), size(turned);
  for (std::size_t t = 0; t < turn.size(); ++t) {
    turned[component[t]] += turn[t];
    ++size[component[t]];
  }
  for (std::size_t t = 0; t < turn.size(); ++t)
    if (2 * turned[component[t]] > size[component[t]]) turn[t] ^= 1;

  std::vector<Component> parts = split_components(front, component, turn, count);
  for (std::size_t c = 0; c < parts.size(); ++c) {
    if (!parts[c].sign_known) continue;
    const int depth = parts.size() == 1 ? 0 : nesting_depth(front, parts, c);
    if (depth < 0) continue;
    const bool cavity = depth % 2 == 1;
    report.cavities += cavity ? 1 : 0;
    if ((parts[c].volume < 0) != cavity) {
      ++report.components_turned;
      for (Index t : parts[c].ids) turn[t] ^= 1;
    }
  }
  for (std::size_t t = 0; t < turn.size(); ++t) {
    if (!turn[t]) continue;
    flip(front.triangles[t]);
    ++report.triangles_reoriented;
  }
  if (neighbours != nullptr) *neighbours = turned_neighbours(std::move(adjacency), turn);
  return report;
}

}  // namespace afmesh
