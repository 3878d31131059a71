#include "core/quality/validate_common.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "core/quality/compensated_sum.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

template <typename Element>
constexpr std::string_view element_name() {
  return std::tuple_size_v<Element> == 4 ? "tet" : "triangle";
}

template <typename Element>
Check check_indices_impl(const std::vector<Element>& elements, std::size_t tag_count,
                         std::size_t point_count, const ValidationParams& params) {
  constexpr std::string_view kind = element_name<Element>();
  CheckBuilder builder(check::kIndices, params);
  if (tag_count != elements.size()) {
    builder.add([&] {
      return Finding{absl::StrFormat("%s_tags has %d entries for %d %ss", kind, tag_count,
                                     elements.size(), kind)};
    });
  }
  for (Index e = 0; e < static_cast<Index>(elements.size()); ++e) {
    for (Index v : elements[e]) {
      if (v >= 0 && static_cast<std::size_t>(v) < point_count) continue;
      builder.add([&] {
        Finding f{absl::StrFormat("%s %d has point index %d outside [0, %d)", kind, e, v,
                                  point_count)};
        (kind == "tet" ? f.tets : f.triangles).push_back(e);
        return f;
      });
    }
  }
  return builder.finish(
      absl::StrFormat("all %d %ss reference points in [0, %d)", elements.size(), kind,
                      point_count),
      absl::StrFormat("%d bad %s", builder.count(), plural(builder.count(), "index", "indices")));
}

template <typename Element>
Check check_unused_impl(std::size_t point_count, const std::vector<Element>& elements,
                        const ValidationParams& params) {
  constexpr std::string_view kind = element_name<Element>();
  std::vector<bool> used(point_count, false);
  for (const Element& e : elements) {
    for (Index v : e) used[v] = true;
  }
  CheckBuilder builder(check::kUnusedPoints, params);
  for (Index p = 0; p < static_cast<Index>(point_count); ++p) {
    if (used[p]) continue;
    builder.add([&] {
      return Finding{absl::StrFormat("point %d is not used by any %s", p, kind), {p}};
    });
  }
  return builder.finish(absl::StrFormat("every point is used by a %s", kind),
                        absl::StrFormat("%d of %d points %s not used by any %s",
                                        builder.count(), point_count,
                                        plural(builder.count(), "is", "are"), kind),
                        CheckOutcome::kWarning);
}

template <typename Element>
bool indices_in_range_impl(const std::vector<Element>& elements, std::size_t point_count) {
  for (const Element& e : elements) {
    for (Index v : e) {
      if (v < 0 || static_cast<std::size_t>(v) >= point_count) return false;
    }
  }
  return true;
}

}  // namespace

CheckBuilder::CheckBuilder(std::string_view name, const ValidationParams& params)
    : max_findings_(std::max(params.max_findings_per_check, 0)) {
  check_.name = std::string(name);
}

void CheckBuilder::add(absl::FunctionRef<Finding()> make) {
  ++check_.finding_count;
  if (static_cast<std::int64_t>(check_.findings.size()) < max_findings_) {
    check_.findings.push_back(make());
  }
}

Check CheckBuilder::finish(std::string clean_summary, std::string found_summary,
                           CheckOutcome if_found) {
  if (check_.finding_count == 0) {
    check_.outcome = CheckOutcome::kPassed;
    check_.summary = std::move(clean_summary);
    return std::move(check_);
  }
  check_.outcome = if_found;
  check_.summary = std::move(found_summary);
  const std::int64_t dropped = check_.finding_count - static_cast<std::int64_t>(check_.findings.size());
  if (dropped > 0) {
    absl::StrAppendFormat(&check_.summary, " (first %d listed, and %d more)",
                          check_.findings.size(), dropped);
  }
  return std::move(check_);
}

Check not_run(std::string_view name, std::string_view reason) {
  Check check;
  check.name = std::string(name);
  check.outcome = CheckOutcome::kNotRun;
  check.summary = absl::StrFormat("not run: %s", reason);
  return check;
}

std::string join_indices(const std::vector<Index>& ids) {
  if (ids.size() <= 1) return absl::StrJoin(ids, "");
  std::vector<Index> head(ids.begin(), ids.end() - 1);
  return absl::StrCat(absl::StrJoin(head, ", "), " and ", ids.back());
}

std::string format_triple(const Triangle& t) {
  return absl::StrFormat("(%d,%d,%d)", t[0], t[1], t[2]);
}

std::string plural(std::int64_t n, std::string_view singular, std::string_view plural_form) {
  return std::string(n == 1 ? singular : plural_form);
}

Check check_element_indices(const std::vector<Tet>& elements, std::size_t tag_count,
                            std::size_t point_count, const ValidationParams& params) {
  return check_indices_impl(elements, tag_count, point_count, params);
}

Check check_element_indices(const std::vector<Triangle>& elements, std::size_t tag_count,
                            std::size_t point_count, const ValidationParams& params) {
  return check_indices_impl(elements, tag_count, point_count, params);
}

Check check_finite_coordinates(const std::vector<Point>& points, const ValidationParams& params) {
  CheckBuilder builder(check::kFiniteCoordinates, params);
  for (Index p = 0; p < static_cast<Index>(points.size()); ++p) {
    const Point& x = points[p];
    if (std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])) continue;
    builder.add([&] {
      return Finding{
          absl::StrFormat("point %d has a non-finite coordinate (%g, %g, %g)", p, x[0], x[1], x[2]),
          {p}};
    });
  }
  return builder.finish(
      absl::StrFormat("all %d points have finite coordinates", points.size()),
      absl::StrFormat("%d %s non-finite coordinates", builder.count(),
                      plural(builder.count(), "point has", "points have")));
}

Check check_unused_points(std::size_t point_count, const std::vector<Tet>& tets,
                          const ValidationParams& params) {
  return check_unused_impl(point_count, tets, params);
}

Check check_unused_points(std::size_t point_count, const std::vector<Triangle>& triangles,
                          const ValidationParams& params) {
  return check_unused_impl(point_count, triangles, params);
}

bool all_indices_in_range(const std::vector<Tet>& tets, std::size_t point_count) {
  return indices_in_range_impl(tets, point_count);
}

bool all_indices_in_range(const std::vector<Triangle>& triangles, std::size_t point_count) {
  return indices_in_range_impl(triangles, point_count);
}

bool indices_and_coordinates_ok(const std::vector<Point>& points,
                                const std::vector<Triangle>& triangles) {
  if (!all_indices_in_range(triangles, points.size())) return false;
  return std::all_of(points.begin(), points.end(), [](const Point& x) {
    return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
  });
}

double enclosed_volume(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                       double* magnitude) {
  Box extent = empty_box();
  for (const Triangle& t : triangles) enclose(extent, triangle_box(points, t));
  Point o{0.0, 0.0, 0.0};
  if (!triangles.empty()) {
    for (int k = 0; k < 3; ++k) o[k] = 0.5 * (extent.lo[k] + extent.hi[k]);
  }
  CompensatedSum volume, scale;
  for (const Triangle& t : triangles) {
    Point a, b, c;
    for (int k = 0; k < 3; ++k) {
      a[k] = points[t[0]][k] - o[k];
      b[k] = points[t[1]][k] - o[k];
      c[k] = points[t[2]][k] - o[k];
    }
    const double term = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                         a[2] * (b[0] * c[1] - b[1] * c[0])) /
                        6.0;
    volume.add(term);
    scale.add(std::abs(term));
  }
  if (magnitude != nullptr) *magnitude = scale.value();
  return volume.value();
}

}  // namespace afmesh
