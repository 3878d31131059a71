// Quality-raising point smoothing: the geometric step of the optimiser (optimise_steps.h).
#include <algorithm>
#include <cmath>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/optimise_steps.h"

namespace afmesh {
namespace {

// Hill-climbing iterations per call, and halvings of the step in each line search.
constexpr int kClimbIterations = 8;
constexpr int kLineSearchHalvings = 8;
// The first step of a line search, in mean edge lengths around the point; a later search starts
// at four times the previous step.
constexpr double kFirstStep = 0.25;
// Climbing stops after a step that raises the smallest quality by less than this.
constexpr double kMinGain = 1e-3;
// Tets within this of the worst quality count as active (their gradients steer the step).
constexpr double kActiveBand = 1e-3;

// The smallest quality over the ball with point v at its current place, or -infinity when a tet
// is not positive by exact orient3d. Fills scratch.quality.
double ball_quality(const TetComplex& c, SmoothingScratch& scratch) {
  const std::vector<Point>& points = c.points();
  scratch.quality.resize(scratch.ball.size());
  double worst = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scratch.ball.size(); ++i) {
    const Tet& k = c.tet(scratch.ball[i]);
    if (orient3d(points[k[0]], points[k[1]], points[k[2]], points[k[3]]) <= 0)
      return -std::numeric_limits<double>::infinity();
    scratch.quality[i] = tet_min_sine(points, k);
    worst = std::min(worst, scratch.quality[i]);
  }
  return worst;
}

// True when every tet of the ball has quality above `floor` and is positive by exact orient3d
// (the exact test only once the qualities pass); the qualities are left in scratch.trial. Looks
// at the tets in scratch.order first: the worst ones, which are the likeliest to fail.
bool ball_above(const TetComplex& c, double floor, SmoothingScratch& scratch) {
  const std::vector<Point>& points = c.points();
  scratch.trial.resize(scratch.ball.size());
  for (std::size_t i : scratch.order) {
    scratch.trial[i] = tet_min_sine(points, c.tet(scratch.ball[i]));
    if (!(scratch.trial[i] > floor)) return false;
  }
  for (Index t : scratch.ball) {
    const Tet& k = c.tet(t);
    if (orient3d(points[k[0]], points[k[1]], points[k[2]], points[k[3]]) <= 0) return false;
  }
  return true;
}

// scratch.order: the ball's positions, by ascending scratch.quality.
void sort_worst_first(SmoothingScratch& scratch) {
  scratch.order.resize(scratch.ball.size());
  for (std::size_t i = 0; i < scratch.order.size(); ++i) scratch.order[i] = i;
  std::sort(scratch.order.begin(), scratch.order.end(), [&](std::size_t x, std::size_t y) {
    return scratch.quality[x] < scratch.quality[y] ||
           (scratch.quality[x] == scratch.quality[y] && x < y);
  });
}

// Gradient of the quality of tet k (quality q at the current place) with respect to the
// position of point v, by forward differences with step h.
Point quality_gradient(TetComplex& c, const Tet& k, double q, Index v, double h) {
  Point g{0, 0, 0};
  const Point x = c.point(v);
  for (int axis = 0; axis < 3; ++axis) {
    Point y = x;
    y[axis] = x[axis] + h;
    c.move_point(v, y);
    g[axis] = (tet_min_sine(c.points(), k) - q) / h;
  }
  c.move_point(v, x);
  return g;
}

// Tries the position `to` for v; keeps it (true) when the ball's smallest quality rises above
// `current`, which is then updated (with scratch.quality and scratch.order).
bool try_position(TetComplex& c, Index v, const Point& to, double& current,
                  SmoothingScratch& scratch) {
  const Point from = c.point(v);
  c.move_point(v, to);
  if (!ball_above(c, current, scratch)) {
    c.move_point(v, from);
    return false;
  }
  std::swap(scratch.quality, scratch.trial);
  current = *std::min_element(scratch.quality.begin(), scratch.quality.end());
  sort_worst_first(scratch);
  return true;
}

// Mean length of the edges from v to its neighbours in the ball.
double mean_edge_length(const TetComplex& c, Index v, const std::vector<Index>& ball) {
  const std::vector<Point>& points = c.points();
  double sum = 0;
  int n = 0;
  for (Index t : ball)
    for (Index p : c.tet(t))
      if (p != v) sum += distance(points[v], points[p]), ++n;
  return n > 0 ? sum / n : 0.0;
}

// Direction that raises every active tet's quality when one exists: the sum of their unit
// gradients, or the worst tet's gradient alone. Zero when neither raises all of them.
Point ascent_direction(const std::vector<Point>& gradients) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    Point d{0, 0, 0};
    if (attempt == 0) {
      for (const Point& g : gradients) {
        const double n = norm(g);
        if (n > 0) d = add(d, scale(g, 1.0 / n));
      }
    } else {
      d = gradients.front();
    }
    bool ascends = norm(d) > 0;
    for (const Point& g : gradients) ascends = ascends && dot(g, d) > 0;
    if (ascends) return d;
  }
  return {0, 0, 0};
}

// Laplacian step: v to the centroid of its neighbours, or halfway, when that beats `current`.
bool move_toward_centroid(TetComplex& c, Index v, double& current, SmoothingScratch& scratch) {
  Point centroid{0, 0, 0};
  int count = 0;
  for (Index t : scratch.ball)
    for (Index p : c.tet(t))
      if (p != v) centroid = add(centroid, c.point(p)), ++count;
  centroid = scale(centroid, 1.0 / count);
  const Point start = c.point(v);
  for (double w : {1.0, 0.5})
    if (try_position(c, v, lerp(start, centroid, w), current, scratch)) return true;
  return false;
}

// Hill climbing on the smallest quality of the ball: a step along a direction that raises
// every nearly-worst tet, found by a backtracking line search; repeated while it gains.
bool climb(TetComplex& c, Index v, double& current, SmoothingScratch& scratch) {
  const double length = mean_edge_length(c, v, scratch.ball);
  if (!(length > 0)) return false;
  bool moved = false;
  double last_step = kFirstStep * length;
  for (int iteration = 0; iteration < kClimbIterations; ++iteration) {
    scratch.gradients.clear();
    for (std::size_t i : scratch.order) {
      if (!scratch.gradients.empty() && scratch.quality[i] > current + kActiveBand) break;
      scratch.gradients.push_back(
          quality_gradient(c, c.tet(scratch.ball[i]), scratch.quality[i], v, 1e-7 * length));
    }
    const Point d = ascent_direction(scratch.gradients);
    const double dn = norm(d);
    if (!(dn > 0)) break;
    const Point unit = scale(d, 1.0 / dn);
    const Point from = c.point(v);
    const double before = current;
    bool stepped = false;
    double step = std::min(kFirstStep * length, 4 * last_step);
    for (int h = 0; h < kLineSearchHalvings && !stepped; ++h, step *= 0.5)
      stepped = try_position(c, v, add(from, scale(unit, step)), current, scratch);
    if (!stepped) break;
    moved = true;
    last_step = 2 * step;  // the step taken (halved once more by the loop)
    if (current - before < kMinGain) break;
  }
  return moved;
}

}  // namespace

bool smooth_point(TetComplex& c, Index v, Index fixed_points, bool climb_too,
                  SmoothingScratch& scratch) {
  if (v < fixed_points) return false;
  c.ball(v, scratch.ball);
  if (scratch.ball.empty()) return false;
  double current = ball_quality(c, scratch);
  if (current == -std::numeric_limits<double>::infinity()) return false;
  sort_worst_first(scratch);
  const bool centred = move_toward_centroid(c, v, current, scratch);
  const bool climbed = climb_too && climb(c, v, current, scratch);
  return centred || climbed;
}

}  // namespace afmesh
