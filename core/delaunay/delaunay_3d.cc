// Bowyer–Watson insertion with exact, symbolically perturbed predicates (delaunay_3d.h).
#include "core/delaunay/delaunay_3d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "absl/strings/str_format.h"
#include "core/geometry/predicates.h"
#include "core/spatial/z_order.h"

namespace afmesh {
namespace {

// The far corners' distance from the box's centre, in half-diagonals of the box: a regular
// tetrahedron whose corners lie L from its centre holds the ball of radius L / 3, so the box is
// inside from 3 on; further out, fewer elements near the hull reach a far corner.
constexpr double kFarCornerDistance = 1e6;

// The element e with vertex v[i] replaced by x: positive exactly when x lies strictly on the same
// side of the face opposite v[i] as v[i].
int orient_with(const std::vector<Point>& at, const Tet& v, int i, const Point& x) {
  std::array<const Point*, 4> p{&at[v[0]], &at[v[1]], &at[v[2]], &at[v[3]]};
  p[i] = &x;
  return orient3d(*p[0], *p[1], *p[2], *p[3]);
}

bool is_finite(const Point& x) {
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

}  // namespace

Delaunay3::Delaunay3(const Box& bounds) {
  Point centre{0, 0, 0};
  double half_diagonal = 0;
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (bounds.lo[a] + bounds.hi[a]);
    const double half = 0.5 * (bounds.hi[a] - bounds.lo[a]);
    half_diagonal += half * half;
  }
  half_diagonal = std::sqrt(half_diagonal);
  if (!(half_diagonal > 0)) half_diagonal = 1.0;
  const double l = kFarCornerDistance * half_diagonal / std::sqrt(3.0);
  const double signs[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (const auto& s : signs)
    vertices_.push_back({centre[0] + s[0] * l, centre[1] + s[1] * l, centre[2] + s[2] * l});
  Tet first{0, 1, 2, 3};
  if (orient3d(vertices_[0], vertices_[1], vertices_[2], vertices_[3]) < 0)
    std::swap(first[2], first[3]);
  elements_.push_back({first, {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex}});
}

std::uint32_t Delaunay3::next_random() {  // xorshift32: deterministic, no global state
  random_ ^= random_ << 13;
  random_ ^= random_ >> 17;
  random_ ^= random_ << 5;
  return random_;
}

Index Delaunay3::locate(const Point& x, Index start) {
  Index e = start;
  for (;;) {
    const Element& el = elements_[e];
    const int offset = static_cast<int>(next_random() & 3u);
    Index next = e;
    for (int k = 0; k < 4 && next == e; ++k) {
      const int i = (offset + k) & 3;
      if (orient_with(vertices_, el.v, i, x) < 0) next = el.across[i];
    }
    if (next == e) return e;
    if (next == kInvalidIndex) return kInvalidIndex;
    e = next;
  }
}

int Delaunay3::in_sphere(const Element& e, Index x) const {
  const Tet& v = e.v;
  const Point& q = vertices_[x];
  const int sign = insphere(vertices_[v[0]], vertices_[v[1]], vertices_[v[2]], vertices_[v[3]], q);
  if (sign != 0) return sign;
  // On the sphere: the perturbation of the vertex of highest rank (the latest) whose term does
  // not vanish decides. Raising x's lift puts x outside; raising corner v[i]'s lift tilts the
  // sphere's plane up on v[i]'s side of the face opposite it, so x is inside exactly when it lies
  // strictly on that side (the positive element with v[i] replaced by x).
  std::array<Index, 4> order{0, 1, 2, 3};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return v[a] > v[b]; });
  for (const int i : order) {
    if (v[i] < x) return -1;  // x ranks above every corner left: its own term decides
    const int o = orient_with(vertices_, v, i, q);
    if (o != 0) return o;
  }
  return -1;
}

Index Delaunay3::new_element(const Tet& v) {
  const Element fresh{v, {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex}, true};
  if (!free_.empty()) {
    const Index e = free_.back();
    free_.pop_back();
    elements_[e] = fresh;
    return e;
  }
  elements_.push_back(fresh);
  return static_cast<Index>(elements_.size() - 1);
}

absl::Status Delaunay3::fill_cavity(Index seed, Index x) {
  if (seen_.size() < elements_.size()) {
    seen_.resize(elements_.size(), 0);
    in_cavity_.resize(elements_.size(), false);
  }
  ++visit_;
  cavity_.assign(1, seed);
  boundary_.clear();
  seen_[seed] = visit_;
  in_cavity_[seed] = true;
  for (std::size_t k = 0; k < cavity_.size(); ++k) {
    const Index e = cavity_[k];
    for (int i = 0; i < 4; ++i) {
      const Index nb = elements_[e].across[i];
      if (nb != kInvalidIndex && seen_[nb] != visit_) {
        seen_[nb] = visit_;
        in_cavity_[nb] = in_sphere(elements_[nb], x) > 0;
        if (in_cavity_[nb]) cavity_.push_back(nb);
      }
      if (nb == kInvalidIndex || !in_cavity_[nb]) boundary_.push_back({e, i});
    }
  }
  // Star-shaped about x (the perturbation guarantees it; checked, as a flat element would
  // corrupt every later walk).
  for (const BoundaryFace& b : boundary_)
    if (orient_with(vertices_, elements_[b.element].v, b.face, vertices_[x]) <= 0)
      return absl::InternalError(absl::StrFormat(
          "Delaunay insertion of point %d: its cavity is not star-shaped", x - kFar));
  // The new elements, then their links: across the cavity's face to the element beyond, and to
  // each other across the faces on x, found by the boundary edge they share (open_). Their
  // corners and what lies beyond each cavity face are read (plans_) before the cavity's slots
  // are freed for the new elements to reuse.
  absl::flat_hash_map<std::uint64_t, Open>& open = open_;
  std::vector<Plan>& plans = plans_;
  open.clear();
  plans.clear();
  for (const BoundaryFace& b : boundary_) {
    Plan plan{elements_[b.element].v, b.face, elements_[b.element].across[b.face]};
    plan.v[b.face] = x;
    if (plan.beyond != kInvalidIndex)
      for (int j = 0; j < 4; ++j)
        if (elements_[plan.beyond].across[j] == b.element) plan.back = j;
    plans.push_back(plan);
  }
  for (const Index e : cavity_) {
    in_cavity_[e] = false;
    elements_[e].alive = false;
    free_.push_back(e);
  }
  Index made = kInvalidIndex;
  for (const Plan& plan : plans) {
    const Index e = new_element(plan.v);
    made = e;
    const int face = plan.face;
    elements_[e].across[face] = plan.beyond;
    if (plan.beyond != kInvalidIndex) elements_[plan.beyond].across[plan.back] = e;
    const Tet& v = plan.v;
    for (int j = 0; j < 4; ++j) {
      if (j == face) continue;
      // The face opposite v[j] holds x and the boundary face's two corners other than v[j].
      Index ends[2];
      int n = 0;
      for (int m = 0; m < 4; ++m)
        if (m != j && m != face) ends[n++] = v[m];
      const Index a = std::min(ends[0], ends[1]), bb = std::max(ends[0], ends[1]);
      const std::uint64_t key =
          static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint32_t>(bb);
      const auto [slot, first] = open.try_emplace(key, Open{e, j});
      if (!first) {
        elements_[e].across[j] = slot->second.element;
        elements_[slot->second.element].across[slot->second.face] = e;
      }
    }
  }
  if (seen_.size() < elements_.size()) {
    seen_.resize(elements_.size(), 0);
    in_cavity_.resize(elements_.size(), false);
  }
  last_ = made;
  return absl::OkStatus();
}

absl::StatusOr<Index> Delaunay3::insert(const Point& x) {
  if (!is_finite(x)) return absl::InvalidArgumentError("a Delaunay point is not finite");
  if (!elements_[last_].alive) {
    last_ = 0;
    while (!elements_[last_].alive) ++last_;
  }
  const Index e = locate(x, last_);
  if (e == kInvalidIndex)
    return absl::InvalidArgumentError(absl::StrFormat(
        "Delaunay point (%g, %g, %g) lies outside the box the tetrahedralisation was made for",
        x[0], x[1], x[2]));
  for (const Index v : elements_[e].v)
    if (vertices_[v] == x) {
      if (v < kFar)
        return absl::InvalidArgumentError("a Delaunay point lies on a far corner");
      return v - kFar;
    }
  const Index id = static_cast<Index>(vertices_.size());
  vertices_.push_back(x);
  points_.push_back(x);
  if (absl::Status st = fill_cavity(e, id); !st.ok()) return st;
  return id - kFar;
}

std::vector<Tet> Delaunay3::tets() const {
  std::vector<Tet> out;
  for (const Element& e : elements_) {
    if (!e.alive) continue;
    if (std::any_of(e.v.begin(), e.v.end(), [](Index v) { return v < kFar; })) continue;
    out.push_back({e.v[0] - kFar, e.v[1] - kFar, e.v[2] - kFar, e.v[3] - kFar});
  }
  return out;
}

absl::StatusOr<DelaunayTets> delaunay_tetrahedralise(const std::vector<Point>& points) {
  Box box = empty_box();
  for (const Point& x : points) {
    if (!is_finite(x)) return absl::InvalidArgumentError("a Delaunay point is not finite");
    enclose(box, x);
  }
  DelaunayTets out;
  out.vertex_of_point.assign(points.size(), kInvalidIndex);
  if (points.empty()) return out;
  std::vector<std::pair<std::uint64_t, Index>> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    order[i] = {z_order(points[i], box), static_cast<Index>(i)};
  std::sort(order.begin(), order.end());
  Delaunay3 d(box);
  std::vector<Index> point_of_vertex;
  point_of_vertex.reserve(points.size());
  for (const auto& [key, i] : order) {
    const absl::StatusOr<Index> v = d.insert(points[i]);
    if (!v.ok()) return v.status();
    if (*v == static_cast<Index>(point_of_vertex.size())) point_of_vertex.push_back(i);
    out.vertex_of_point[i] = point_of_vertex[*v];
  }
  out.tets = d.tets();
  for (Tet& t : out.tets)
    for (Index& v : t) v = point_of_vertex[v];
  return out;
}

}  // namespace afmesh
