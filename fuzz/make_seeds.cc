// afmesh-fuzz-seeds OUT_DIR: writes small, valid seed inputs for every fuzz target into
// OUT_DIR/<target>/ (a unit cube as a surface and as six tets, written by core/io's own writers;
// MeshVolume and MeshSurface request streams of that cube; shape descriptions for the volume and
// surface meshers). make_corpora.sh adds the files of tests/data and examples/ beside them.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "afmesh/v1/mesher.pb.h"
#include "core/io/medit.h"
#include "core/io/msh.h"
#include "core/io/obj.h"
#include "core/io/stl.h"
#include "google/protobuf/util/json_util.h"
#include "proto/size_spec_convert.h"
#include "proto/slice_codec.h"

namespace {

namespace fs = std::filesystem;

afmesh::Mesh cube_surface() {
  afmesh::Mesh m;
  for (int i = 0; i < 8; ++i) {
    m.points.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  }
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  m.triangle_tags = {1, 1, 2, 2, 1, 1, 2, 2, 1, 1, 2, 2};
  return m;
}

// The cube split into six positive tets around its diagonal 0-7.
afmesh::Mesh cube_tets() {
  afmesh::Mesh m = cube_surface();
  m.tets = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  m.tet_tags.assign(m.tets.size(), 3);
  return m;
}

void write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
}

template <typename Writer>
std::string written(Writer writer) {
  std::string text;
  afmesh::OutputBuffer out(&text);
  if (!writer(out).ok()) {
    std::fprintf(stderr, "afmesh-fuzz-seeds: a writer failed\n");
    std::exit(1);
  }
  return text;
}

// The bytes of a fuzz input written as numbers.
std::string bytes(std::initializer_list<unsigned char> values) {
  return std::string(values.begin(), values.end());
}

// A length-prefixed stream of serialized requests (fuzz_volume_request's and
// fuzz_surface_request's input).
template <class Request>
std::string stream(const std::vector<Request>& requests) {
  std::string bytes;
  for (const Request& r : requests) {
    const std::string one = r.SerializeAsString();
    bytes.push_back(static_cast<char>(one.size() & 0xff));
    bytes.push_back(static_cast<char>(one.size() >> 8));
    bytes += one;
  }
  return bytes;
}

// The cube's stream at size 0.4: header, points, triangles (with tags), and with
// `streamed_grid` a background grid slice (the six tets, size 0.3 at every point). MeshVolume's
// and MeshSurface's streams have the same parts and fields, so Request is either.
template <class Request>
std::vector<Request> cube_requests(bool streamed_grid) {
  const afmesh::Mesh surface = cube_surface();
  std::vector<Request> requests(3);
  auto& header = *requests[0].mutable_header();
  header.mutable_options()->mutable_size()->set_max_size(0.4);
  header.set_point_count(surface.points.size());
  header.set_triangle_count(surface.triangles.size());
  afmesh::wire::encode_points(surface.points, 0, surface.points.size(),
                              *requests[1].mutable_points());
  afmesh::wire::encode_triangles(surface.triangles, surface.triangle_tags, 0,
                                 surface.triangles.size(), *requests[2].mutable_triangles());
  if (streamed_grid) {
    const afmesh::Mesh grid = cube_tets();
    header.set_grid_point_count(grid.points.size());
    header.set_grid_tet_count(grid.tets.size());
    afmesh::v1::BackgroundGridSlice& slice = *requests.emplace_back().mutable_background_grid();
    afmesh::wire::encode_grid_points(grid.points, 0, grid.points.size(), slice);
    afmesh::wire::encode_grid_sizes(std::vector<double>(grid.points.size(), 0.3), 0,
                                    grid.points.size(), slice);
    afmesh::wire::encode_grid_tets(grid.tets, 0, grid.tets.size(), slice);
  }
  return requests;
}

std::vector<afmesh::v1::MeshVolumeRequest> cube_volume_requests(afmesh::v1::EnvironmentMode mode,
                                                                bool streamed_grid) {
  std::vector<afmesh::v1::MeshVolumeRequest> requests =
      cube_requests<afmesh::v1::MeshVolumeRequest>(streamed_grid);
  requests[0].mutable_header()->mutable_options()->set_environments(mode);
  return requests;
}

// MeshSurface's cube stream; with `angles`, ridge and corner angles of 45 and 100 degrees.
std::vector<afmesh::v1::MeshSurfaceRequest> cube_surface_requests(bool angles, bool streamed_grid) {
  std::vector<afmesh::v1::MeshSurfaceRequest> requests =
      cube_requests<afmesh::v1::MeshSurfaceRequest>(streamed_grid);
  if (angles) {
    afmesh::v1::SurfaceOptions& options = *requests[0].mutable_header()->mutable_options();
    options.set_ridge_angle_deg(45.0);
    options.set_corner_angle_deg(100.0);
  }
  return requests;
}

std::string inline_grid_spec_json() {
  const afmesh::Mesh grid = cube_tets();
  afmesh::SizeSpec spec;
  spec.max_size = 0.5;
  spec.growth = 1.3;
  spec.sources.push_back({.points = {{0.5, 0.5, 0.5}}, .delta0 = 0.1, .r0 = 0.1, .r1 = 0.3,
                          .law = afmesh::PowerLaw{.gamma = 1.5}});
  spec.background = afmesh::BackgroundGridSpec{
      .points = grid.points, .tets = grid.tets, .sizes = std::vector<double>(8, 0.4)};
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(afmesh::size_spec_to_proto(spec), &json);
  return json;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: afmesh-fuzz-seeds OUT_DIR\n");
    return 2;
  }
  const fs::path out(argv[1]);
  const afmesh::Mesh surface = cube_surface();
  const afmesh::Mesh tets = cube_tets();
  const std::vector<double> sizes(tets.points.size(), 0.25);

  write(out / "stl", "cube_binary.stl", written([&](auto& o) {
          return afmesh::write_stl(surface, afmesh::StlEncoding::kBinary, o);
        }));
  write(out / "stl", "cube_ascii.stl", written([&](auto& o) {
          return afmesh::write_stl(surface, afmesh::StlEncoding::kAscii, o);
        }));
  write(out / "obj", "cube.obj", written([&](auto& o) { return afmesh::write_obj(surface, o); }));
  write(out / "msh", "cube_41.msh", written([&](auto& o) { return afmesh::write_msh(tets, o); }));
  write(out / "msh", "cube_41_sizes.msh", written([&](auto& o) {
          return afmesh::write_msh_sized_grid(tets, sizes, o);
        }));
  write(out / "medit", "cube.mesh",
        written([&](auto& o) { return afmesh::write_medit(tets, o); }));
  write(out / "medit_sol", "cube.sol",
        std::string(1, static_cast<char>(tets.points.size())) +
            written([&](auto& o) { return afmesh::write_medit_sol(sizes, o); }));
  write(out / "size_spec", "inline_grid.json", inline_grid_spec_json());

  write(out / "volume_request", "cube_none",
        stream(cube_volume_requests(afmesh::v1::ENVIRONMENT_MODE_NONE, false)));
  write(out / "volume_request", "cube_tags",
        stream(cube_volume_requests(afmesh::v1::ENVIRONMENT_MODE_TAGS, false)));
  write(out / "volume_request", "cube_streamed_grid",
        stream(cube_volume_requests(afmesh::v1::ENVIRONMENT_MODE_NONE, true)));

  write(out / "surface_request", "cube_default", stream(cube_surface_requests(false, false)));
  write(out / "surface_request", "cube_angles", stream(cube_surface_requests(true, false)));
  write(out / "surface_request", "cube_streamed_grid", stream(cube_surface_requests(false, true)));

  // Free triangles (shape 2, options 0, size 0x80) for both meshers: the corner tetrahedron's
  // boundary: 4 points (the count byte 0, then the origin and the three unit points on the
  // 1/32 lattice) and 4 triangles.
  const std::string points = bytes({0, 0, 0, 0x20, 0, 0, 0, 0x20, 0, 0, 0, 0x20});
  const std::string tetrahedron_free =
      bytes({2, 0, 0x80, 0}) + points + bytes({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});

  // fuzz_volume_mesher: shape, mode, size, then corner moves, flips and tags (all zero here).
  write(out / "volume_mesher", "cube", std::string("\x00\x00\x80", 3));
  write(out / "volume_mesher", "octahedron_tags", std::string("\x01\x01\x40", 3));
  write(out / "volume_mesher", "cube_cavity_auto", std::string("\x00\x06\xc0", 3));
  write(out / "volume_mesher", "tetrahedron_free", tetrahedron_free);

  // fuzz_surface_mesher: shape, options, size, then (closed shapes) corner moves and flips,
  // then tags; zero where not given.
  write(out / "surface_mesher", "cube", std::string("\x00\x00\x80", 3));
  write(out / "surface_mesher", "cube_small", std::string("\x00\x00\x00", 3));
  // Ridges at 150 degrees, corners at 20, no curvature bound.
  write(out / "surface_mesher", "cube_angles", std::string("\x00\x17\x80", 3));
  write(out / "surface_mesher", "cube_cavity", std::string("\x00\x20\xc0", 3));
  // Corner i moved by (8i, -4i, 2i) / 256, triangles 0, 2 and 5 flipped, tags 1 and 2.
  std::string moved("\x00\x00\x80", 3);
  for (int corner = 0; corner < 8; ++corner) {
    for (const int move : {8 * corner, -4 * corner, 2 * corner})
      moved.push_back(static_cast<char>(move));
  }
  moved += std::string("\x25\x00", 2);
  for (int t = 0; t < 12; ++t) moved.push_back(static_cast<char>(1 + t / 6));
  write(out / "surface_mesher", "cube_moved_flipped_tags", moved);
  // The octahedron, its two halves tagged 1 and 2 (a tag line round its equator).
  std::string octahedron("\x01\x00\x60", 3);
  octahedron += std::string(6 * 3 + 1, '\0');
  for (int t = 0; t < 8; ++t) octahedron.push_back(static_cast<char>(1 + (t & 4) / 4));
  write(out / "surface_mesher", "octahedron_tags", octahedron);
  // Free triangles: the tetrahedron, and an open square of two triangles (a boundary line).
  write(out / "surface_mesher", "tetrahedron_free", tetrahedron_free);
  write(out / "surface_mesher", "square_free",
        bytes({2, 0, 0x80, 0, 0, 0, 0, 0x20, 0, 0, 0x20, 0x20, 0, 0, 0x20, 0, 0, 1, 2, 0, 2, 3}));
  return 0;
}
