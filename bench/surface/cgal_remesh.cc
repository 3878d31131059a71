// The CGAL peer of the surface benchmark, and the judge of every tool's output (issue 11).
//
//   cgal_remesh remesh IN OUT --size H [--ridge-angle DEG] [--iterations N]
//       Reads IN (.stl ascii or binary, .off, .obj, .ply), marks its sharp edges
//       (PMP::detect_sharp_edges: adjacent face normals more than DEG apart, default 30) as
//       constrained and the vertices with other than 0 or 2 sharp edges as fixed corners, runs
//       PMP::isotropic_remeshing at target edge length H (N iterations, default 3, CGAL's
//       examples; constrained edges may be split and collapsed and their vertices slide along
//       them, points are projected onto the input), and writes OUT (.obj/.off, 17 digits).
//       Prints one JSON line: seconds (detection + remeshing, not reading or writing),
//       rss_before_bytes / rss_peak_bytes (VmRSS before that phase, VmHWM reset at its start:
//       the same probe as bench/peers.py), triangles, points, sharp_edges, corners.
//
//   cgal_remesh measure INPUT OUTPUT [--size H] [--ridge-angle DEG] [--tolerance T]
//       Judges OUTPUT against INPUT, both read as triangle soups (no manifoldness assumed), with
//       CGAL's AABB trees and none of afmesh's code. Prints one JSON line:
//       - triangles, points, boundary_edges / nonmanifold_edges (edges in 1 / more than 2 faces);
//       - min_angle, mean_min_angle, max_angle (degrees), share_min_angle_ge_30 (share of
//         triangles whose smallest angle is at least 30°), count_min_angle_lt_15;
//       - mean_edge and, with --size, mean_edge_over_h and share_edges_in_band ([0.7 H, 1.4 H]);
//       - hausdorff: the two-sided distance, each side sampled at its vertices, the midpoints
//         of its edges and the centroids of its triangles, distances to the other side's
//         triangles (exact closest points); hausdorff_in_to_out, hausdorff_out_to_in,
//         mean_in_to_out, mean_out_to_in, diag (the input's bounding-box diagonal) and
//         hausdorff_over_diag;
//       - ridges: the input's sharp edges (normals more than DEG apart, plus its boundary and
//         non-manifold edges); ridge_length_kept = length of the output edges whose two ends and
//         midpoint lie within T * diag (default 1e-6) of an input ridge / total ridge length;
//         corners = input vertices with 3 or more ridge edges, corners_kept = those with an
//         output vertex within T * diag.
//
// Exit status: 0 done; 2 bad command line; 3 a file cannot be read; 4 remeshing failed.
// Compiled by bench/surface/run_surface_bench.py with g++ (cached beside the build).

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Resident memory of this process (Linux /proc), as bench/process_memory.h.

long StatusBytes(const char* key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(status, line)) {
    if (line.rfind(prefix, 0) == 0) return std::atol(line.c_str() + prefix.size()) * 1024;
  }
  return 0;
}

// Resets VmHWM to the current RSS (clear_refs 5) so that the peak read later is the phase's.
bool ResetPeak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  return static_cast<bool>(clear);
}

// ---------------------------------------------------------------------------------------------
// remesh

struct RemeshParams {
  double size = 0.0;              // target edge length H, model units
  double ridge_angle_deg = 30.0;  // detect_sharp_edges bound, degrees
  unsigned iterations = 3;        // isotropic_remeshing iterations (CGAL examples use 3)
};

int Remesh(const std::string& in, const std::string& out, const RemeshParams& params) {
  Mesh mesh;
  if (!PMP::IO::read_polygon_mesh(in, mesh) || mesh.number_of_faces() == 0) {
    std::fprintf(stderr, "cgal_remesh: cannot read %s as a polygon mesh\n", in.c_str());
    return 3;
  }
  const bool peak_reset = ResetPeak();
  const long rss_before = StatusBytes("VmRSS");
  const auto started = std::chrono::steady_clock::now();

  auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  PMP::detect_sharp_edges(mesh, params.ridge_angle_deg, sharp);
  auto corner = mesh.add_property_map<Mesh::Vertex_index, bool>("v:corner", false).first;
  std::size_t sharp_edges = 0, corners = 0;
  for (Mesh::Edge_index e : mesh.edges()) sharp_edges += sharp[e] ? 1 : 0;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    int count = 0;
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_target(v, mesh)) {
      count += sharp[mesh.edge(h)] ? 1 : 0;
    }
    corner[v] = count != 0 && count != 2;
    corners += corner[v] ? 1 : 0;
  }
  try {
    PMP::isotropic_remeshing(mesh.faces(), params.size, mesh,
                             CGAL::parameters::number_of_iterations(params.iterations)
                                 .edge_is_constrained_map(sharp)
                                 .vertex_is_constrained_map(corner)
                                 .protect_constraints(false)
                                 .relax_constraints(true));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "cgal_remesh: isotropic_remeshing failed: %s\n", error.what());
    return 4;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const long rss_peak = StatusBytes("VmHWM");
  mesh.collect_garbage();
  if (!CGAL::IO::write_polygon_mesh(out, mesh, CGAL::parameters::stream_precision(17))) {
    std::fprintf(stderr, "cgal_remesh: cannot write %s\n", out.c_str());
    return 3;
  }
  std::printf(
      "{\"seconds\": %.6f, \"rss_before_bytes\": %ld, \"rss_peak_bytes\": %ld, "
      "\"peak_reset\": %s, \"triangles\": %zu, \"points\": %zu, \"sharp_edges\": %zu, "
      "\"corners\": %zu, \"options\": \"isotropic_remeshing target %g, %u iterations, "
      "detect_sharp_edges %g deg constrained (relaxed, not protected), corners fixed\"}\n",
      seconds, rss_before, rss_peak, peak_reset ? "true" : "false", mesh.number_of_faces(),
      mesh.number_of_vertices(), sharp_edges, corners, params.size, params.iterations,
      params.ridge_angle_deg);
  return 0;
}

// ---------------------------------------------------------------------------------------------
// measure: everything on triangle soups (points N x 3, triangles M x 3, 0-based).

struct Soup {
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

bool ReadSoup(const std::string& path, Soup& soup) {
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, soup.points, polygons)) return false;
  for (const auto& polygon : polygons) {
    // Fans any polygon into triangles (every tool here writes triangles only).
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      soup.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
  }
  return !soup.triangles.empty();
}

// Unique undirected edges, each with the triangles that use it (in order of appearance).
using EdgeKey = std::pair<std::size_t, std::size_t>;
std::map<EdgeKey, std::vector<std::size_t>> EdgeFaces(const Soup& soup) {
  std::map<EdgeKey, std::vector<std::size_t>> faces;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    for (int k = 0; k < 3; ++k) {
      std::size_t a = tri[k], b = tri[(k + 1) % 3];
      faces[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  }
  return faces;
}

Triangle TriangleOf(const Soup& soup, std::size_t t) {
  const auto& tri = soup.triangles[t];
  return Triangle(soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]);
}

struct AngleStats {
  double min_angle = 180.0, max_angle = 0.0, mean_min_angle = 0.0, share_ge_30 = 0.0;
  std::size_t count_lt_15 = 0;
};

// Angles from the side lengths (law of cosines, clamped); a degenerate triangle has angle 0.
AngleStats Angles(const Soup& soup) {
  AngleStats stats;
  std::size_t ge_30 = 0;
  double sum = 0.0;
  for (const auto& tri : soup.triangles) {
    double side[3];
    for (int k = 0; k < 3; ++k) {
      side[k] = std::sqrt(CGAL::squared_distance(soup.points[tri[(k + 1) % 3]],
                                                 soup.points[tri[(k + 2) % 3]]));
    }
    double smallest = 180.0, largest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double b = side[(k + 1) % 3], c = side[(k + 2) % 3];
      double angle = 0.0;
      if (b > 0.0 && c > 0.0) {
        const double cosine = (b * b + c * c - side[k] * side[k]) / (2.0 * b * c);
        angle = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / kPi;
      }
      smallest = std::min(smallest, angle);
      largest = std::max(largest, angle);
    }
    stats.min_angle = std::min(stats.min_angle, smallest);
    stats.max_angle = std::max(stats.max_angle, largest);
    sum += smallest;
    ge_30 += smallest >= 30.0 ? 1 : 0;
    stats.count_lt_15 += smallest < 15.0 ? 1 : 0;
  }
  stats.mean_min_angle = sum / soup.triangles.size();
  stats.share_ge_30 = static_cast<double>(ge_30) / soup.triangles.size();
  return stats;
}

using TriangleTree =
    CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<
                                                  Kernel, std::vector<Triangle>::const_iterator>>>;
using SegmentTree =
    CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_segment_primitive<
                                                  Kernel, std::vector<Segment>::const_iterator>>>;

// The soup's triangles without the collinear ones (whose closest points are undefined; their
// points are covered by their neighbours).
std::vector<Triangle> SolidTriangles(const Soup& soup) {
  std::vector<Triangle> triangles;
  triangles.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    Triangle triangle = TriangleOf(soup, t);
    if (!triangle.is_degenerate()) triangles.push_back(triangle);
  }
  return triangles;
}

// Vertices, edge midpoints and centroids of a soup: where its distance to the other is sampled.
std::vector<Point> Samples(const Soup& soup, const std::map<EdgeKey, std::vector<std::size_t>>& edges) {
  std::vector<Point> samples(soup.points);
  for (const auto& [edge, faces] : edges) {
    samples.push_back(CGAL::midpoint(soup.points[edge.first], soup.points[edge.second]));
  }
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    samples.push_back(CGAL::centroid(TriangleOf(soup, t)));
  }
  return samples;
}

struct OneSided {
  double max = 0.0, mean = 0.0;
};

OneSided Distances(const std::vector<Point>& samples, const TriangleTree& tree) {
  OneSided result;
  double sum = 0.0;
  for (const Point& p : samples) {
    const double d = std::sqrt(tree.squared_distance(p));
    result.max = std::max(result.max, d);
    sum += d;
  }
  result.mean = samples.empty() ? 0.0 : sum / samples.size();
  return result;
}

// Ridge edges of the input: boundary, non-manifold, or whose two face normals are more than
// ridge_angle_deg apart (the second face's normal turned when the two disagree in orientation).
std::vector<EdgeKey> RidgeEdges(const Soup& soup,
                                const std::map<EdgeKey, std::vector<std::size_t>>& edges,
                                double ridge_angle_deg) {
  const double cos_bound = std::cos(ridge_angle_deg * kPi / 180.0);
  std::vector<EdgeKey> ridges;
  for (const auto& [edge, faces] : edges) {
    if (faces.size() != 2) {
      ridges.push_back(edge);
      continue;
    }
    Vector n0 = CGAL::normal(soup.points[soup.triangles[faces[0]][0]],
                             soup.points[soup.triangles[faces[0]][1]],
                             soup.points[soup.triangles[faces[0]][2]]);
    Vector n1 = CGAL::normal(soup.points[soup.triangles[faces[1]][0]],
                             soup.points[soup.triangles[faces[1]][1]],
                             soup.points[soup.triangles[faces[1]][2]]);
    const double l0 = std::sqrt(n0.squared_length()), l1 = std::sqrt(n1.squared_length());
    if (l0 == 0.0 || l1 == 0.0) continue;  // next to a degenerate face: no normal to compare
    // Same orientation: the shared edge runs opposite ways in the two faces.
    auto runs_forward = [&](std::size_t t) {
      const auto& tri = soup.triangles[t];
      for (int k = 0; k < 3; ++k) {
        if (tri[k] == edge.first && tri[(k + 1) % 3] == edge.second) return true;
      }
      return false;
    };
    const double sign = runs_forward(faces[0]) != runs_forward(faces[1]) ? 1.0 : -1.0;
    if (sign * (n0 * n1) / (l0 * l1) < cos_bound) ridges.push_back(edge);
  }
  return ridges;
}

struct Args {
  std::vector<std::string> positional;
  double size = 0.0, ridge_angle_deg = 30.0, tolerance = 1e-6;
  unsigned iterations = 3;
};

int Measure(const Args& args) {
  Soup in, out;
  if (!ReadSoup(args.positional[1], in) || !ReadSoup(args.positional[2], out)) {
    std::fprintf(stderr, "cgal_remesh: cannot read %s or %s as triangles\n",
                 args.positional[1].c_str(), args.positional[2].c_str());
    return 3;
  }
  const auto in_edges = EdgeFaces(in), out_edges = EdgeFaces(out);
  const CGAL::Bbox_3 box = CGAL::bbox_3(in.points.begin(), in.points.end());
  const double diag = std::sqrt(CGAL::square(box.xmax() - box.xmin()) +
                                CGAL::square(box.ymax() - box.ymin()) +
                                CGAL::square(box.zmax() - box.zmin()));
  const double tolerance = args.tolerance * diag;

  const AngleStats angles = Angles(out);
  std::size_t boundary = 0, nonmanifold = 0, in_band = 0;
  double edge_sum = 0.0;
  for (const auto& [edge, faces] : out_edges) {
    boundary += faces.size() == 1 ? 1 : 0;
    nonmanifold += faces.size() > 2 ? 1 : 0;
    const double length = std::sqrt(CGAL::squared_distance(out.points[edge.first],
                                                            out.points[edge.second]));
    edge_sum += length;
    if (args.size > 0.0) in_band += length >= 0.7 * args.size && length <= 1.4 * args.size;
  }
  const double mean_edge = edge_sum / out_edges.size();

  const std::vector<Triangle> in_triangles = SolidTriangles(in), out_triangles = SolidTriangles(out);
  TriangleTree in_tree(in_triangles.begin(), in_triangles.end());
  TriangleTree out_tree(out_triangles.begin(), out_triangles.end());
  in_tree.accelerate_distance_queries();
  out_tree.accelerate_distance_queries();
  const OneSided in_to_out = Distances(Samples(in, in_edges), out_tree);
  const OneSided out_to_in = Distances(Samples(out, out_edges), in_tree);
  const double hausdorff = std::max(in_to_out.max, out_to_in.max);

  // Ridges and corners of the input, and how much of them the output kept.
  const std::vector<EdgeKey> ridges = RidgeEdges(in, in_edges, args.ridge_angle_deg);
  std::vector<Segment> ridge_segments;
  std::unordered_map<std::size_t, int> ridge_degree;
  double ridge_length = 0.0;
  for (const auto& [a, b] : ridges) {
    ridge_segments.emplace_back(in.points[a], in.points[b]);
    ridge_length += std::sqrt(ridge_segments.back().squared_length());
    ++ridge_degree[a];
    ++ridge_degree[b];
  }
  double kept_length = 0.0;
  if (!ridge_segments.empty()) {
    SegmentTree ridge_tree(ridge_segments.begin(), ridge_segments.end());
    ridge_tree.accelerate_distance_queries();
    const double bound = tolerance * tolerance;
    for (const auto& [edge, faces] : out_edges) {
      const Point& p = out.points[edge.first];
      const Point& q = out.points[edge.second];
      if (ridge_tree.squared_distance(p) <= bound && ridge_tree.squared_distance(q) <= bound &&
          ridge_tree.squared_distance(CGAL::midpoint(p, q)) <= bound) {
        kept_length += std::sqrt(CGAL::squared_distance(p, q));
      }
    }
  }
  std::vector<Point> sorted(out.points);
  std::sort(sorted.begin(), sorted.end(),
            [](const Point& a, const Point& b) { return a.x() < b.x(); });
  std::size_t corners = 0, corners_kept = 0;
  for (const auto& [vertex, degree] : ridge_degree) {
    if (degree < 3) continue;
    ++corners;
    const Point& c = in.points[vertex];
    auto it = std::lower_bound(sorted.begin(), sorted.end(), c.x() - tolerance,
                               [](const Point& p, double x) { return p.x() < x; });
    for (; it != sorted.end() && it->x() <= c.x() + tolerance; ++it) {
      if (CGAL::squared_distance(*it, c) <= tolerance * tolerance) {
        ++corners_kept;
        break;
      }
    }
  }

  std::printf(
      "{\"triangles\": %zu, \"points\": %zu, \"boundary_edges\": %zu, \"nonmanifold_edges\": %zu, "
      "\"min_angle\": %.4f, \"mean_min_angle\": %.4f, \"max_angle\": %.4f, "
      "\"share_min_angle_ge_30\": %.6f, \"count_min_angle_lt_15\": %zu, \"mean_edge\": %.9g, ",
      out.triangles.size(), out.points.size(), boundary, nonmanifold, angles.min_angle,
      angles.mean_min_angle, angles.max_angle, angles.share_ge_30, angles.count_lt_15, mean_edge);
  if (args.size > 0.0) {
    std::printf("\"size\": %.9g, \"mean_edge_over_h\": %.6f, \"share_edges_in_band\": %.6f, ",
                args.size, mean_edge / args.size,
                static_cast<double>(in_band) / out_edges.size());
  }
  std::printf(
      "\"hausdorff\": %.9g, \"hausdorff_in_to_out\": %.9g, \"hausdorff_out_to_in\": %.9g, "
      "\"mean_in_to_out\": %.9g, \"mean_out_to_in\": %.9g, \"diag\": %.9g, "
      "\"hausdorff_over_diag\": %.9g, \"ridge_angle\": %g, \"ridge_edges\": %zu, "
      "\"ridge_length\": %.9g, \"ridge_length_kept\": %.6f, \"corners\": %zu, "
      "\"corners_kept\": %zu, \"tolerance\": %.3g}\n",
      hausdorff, in_to_out.max, out_to_in.max, in_to_out.mean, out_to_in.mean, diag,
      hausdorff / diag, args.ridge_angle_deg, ridges.size(), ridge_length,
      ridge_length > 0.0 ? kept_length / ridge_length : 1.0, corners, corners_kept, tolerance);
  return 0;
}

// ---------------------------------------------------------------------------------------------

bool ParseArgs(int argc, char** argv, Args& args) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](double& target) {
      if (i + 1 >= argc) return false;
      char* end = nullptr;
      target = std::strtod(argv[++i], &end);
      return *end == '\0';
    };
    double number = 0.0;
    if (arg == "--size") {
      if (!value(args.size)) return false;
    } else if (arg == "--ridge-angle") {
      if (!value(args.ridge_angle_deg)) return false;
    } else if (arg == "--tolerance") {
      if (!value(args.tolerance)) return false;
    } else if (arg == "--iterations") {
      if (!value(number) || number < 1) return false;
      args.iterations = static_cast<unsigned>(number);
    } else if (arg.rfind("--", 0) == 0) {
      return false;
    } else {
      args.positional.push_back(arg);
    }
  }
  return args.positional.size() == 3 &&
         (args.positional[0] == "remesh" || args.positional[0] == "measure");
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!ParseArgs(argc, argv, args) || (args.positional[0] == "remesh" && args.size <= 0.0)) {
    std::fprintf(stderr,
                 "usage: cgal_remesh remesh IN OUT --size H [--ridge-angle DEG] [--iterations N]\n"
                 "       cgal_remesh measure INPUT OUTPUT [--size H] [--ridge-angle DEG] "
                 "[--tolerance T]\n");
    return 2;
  }
  if (args.positional[0] == "measure") return Measure(args);
  return Remesh(args.positional[1], args.positional[2],
                {args.size, args.ridge_angle_deg, args.iterations});
}
