// write_msh: MSH 4.1 ascii with one entity per (dimension, tag), each carrying exactly one
// physical tag (0 for untagged, see msh.h); write_msh_sized_grid adds a $NodeData view of sizes.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/io/mesh_checks.h"
#include "core/io/msh.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh {
namespace {

constexpr int kGmshTriangle = 2;
constexpr int kGmshTet = 4;

// The gmsh entities of one dimension: one per distinct element tag, numbered 1, 2, ... in
// increasing tag order, and the elements of each in their mesh order.
struct EntityPlan {
  std::vector<Index> tags;                   // entity e+1 holds the elements with tags[e]
  std::vector<std::array<double, 6>> boxes;  // per entity: min x y z, max x y z
  std::vector<std::size_t> first;            // entity e's elements: order[first[e], first[e+1])
  std::vector<std::size_t> order;            // element indices grouped by entity
};

template <typename Element>
EntityPlan plan_entities(const std::vector<Element>& elements, const std::vector<Index>& tags,
                         const std::vector<Point>& points) {
  EntityPlan plan;
  plan.tags = tags;
  std::sort(plan.tags.begin(), plan.tags.end());
  plan.tags.erase(std::unique(plan.tags.begin(), plan.tags.end()), plan.tags.end());
  const std::size_t num_entities = plan.tags.size();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  plan.boxes.assign(num_entities, {kInf, kInf, kInf, -kInf, -kInf, -kInf});
  plan.first.assign(num_entities + 1, 0);
  std::vector<std::size_t> entity_of(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i) {
    entity_of[i] = static_cast<std::size_t>(
        std::lower_bound(plan.tags.begin(), plan.tags.end(), tags[i]) - plan.tags.begin());
    ++plan.first[entity_of[i] + 1];
    std::array<double, 6>& box = plan.boxes[entity_of[i]];
    for (const Index v : elements[i]) {
      for (int axis = 0; axis < 3; ++axis) {
        box[axis] = std::min(box[axis], points[v][axis]);
        box[axis + 3] = std::max(box[axis + 3], points[v][axis]);
      }
    }
  }
  for (std::size_t e = 0; e < num_entities; ++e) plan.first[e + 1] += plan.first[e];
  plan.order.resize(elements.size());
  std::vector<std::size_t> next(plan.first.begin(), plan.first.end() - 1);
  for (std::size_t i = 0; i < elements.size(); ++i) plan.order[next[entity_of[i]]++] = i;
  return plan;
}

absl::Status check_tags_not_negative(const std::vector<Index>& tags, std::string_view kind) {
  for (std::size_t i = 0; i < tags.size(); ++i) {
    if (tags[i] < 0) {
      return absl::InvalidArgumentError(
          str_cat("gmsh physical tags must be positive (0: none), but ", kind, " ", i, " has tag ",
                  tags[i]));
    }
  }
  return absl::OkStatus();
}

// Every entity lists exactly one physical tag, its element tag, 0 included: meshio 5 keeps one
// gmsh:physical array per element block only for blocks whose entity has a physical tag, so a
// single entity without one leaves its arrays out of step with the blocks and meshio refuses
// the file ("Incompatible cell data 'gmsh:physical'"). Physical 0 is what MSH 2 and meshio
// use for "no physical group", and gmsh keeps such elements when it saves the mesh again.
void write_entity_lines(const EntityPlan& plan, OutputBuffer& out) {
  for (std::size_t e = 0; e < plan.tags.size(); ++e) {
    out.put_int(static_cast<std::int64_t>(e + 1));
    for (const double bound : plan.boxes[e]) {
      out.put(' ');
      out.put_double(bound);
    }
    out.put(" 1 ");
    out.put_int(plan.tags[e]);
    out.put(" 0\n");  // no bounding entities
  }
}

// $Entities: no points or curves; surfaces and volumes from the plans. A mesh of points only
// gets one empty surface entity to hold its node block.
void write_entities(const EntityPlan& surfaces, const EntityPlan& volumes, bool placeholder,
                    OutputBuffer& out) {
  out.put(str_cat("$Entities\n0 0 ", surfaces.tags.size() + (placeholder ? 1 : 0), " ",
                  volumes.tags.size(), "\n"));
  write_entity_lines(surfaces, out);
  if (placeholder) out.put("1 0 0 0 0 0 0 0 0\n");
  write_entity_lines(volumes, out);
  out.put("$EndEntities\n");
}

// $Nodes: one block, node tags 1..N in point order, on entity (node_dim, 1).
void write_nodes(const std::vector<Point>& points, int node_dim, OutputBuffer& out) {
  const std::size_t n = points.size();
  out.put("$Nodes\n");
  if (n == 0) {
    out.put("0 0 0 0\n$EndNodes\n");
    return;
  }
  out.put(str_cat("1 ", n, " 1 ", n, "\n", node_dim, " 1 0 ", n, "\n"));
  for (std::size_t i = 1; i <= n; ++i) {
    out.put_int(static_cast<std::int64_t>(i));
    out.put('\n');
  }
  for (const Point& p : points) {
    out.put_double(p[0]);
    out.put(' ');
    out.put_double(p[1]);
    out.put(' ');
    out.put_double(p[2]);
    out.put('\n');
  }
  out.put("$EndNodes\n");
}

// One element block per entity; element tags are `first_tag` + the element's index.
template <typename Element>
void write_element_blocks(const std::vector<Element>& elements, const EntityPlan& plan, int dim,
                          int gmsh_type, std::int64_t first_tag, OutputBuffer& out) {
  for (std::size_t e = 0; e < plan.tags.size(); ++e) {
    out.put(str_cat(dim, " ", e + 1, " ", gmsh_type, " ", plan.first[e + 1] - plan.first[e], "\n"));
    for (std::size_t k = plan.first[e]; k < plan.first[e + 1]; ++k) {
      const std::size_t i = plan.order[k];
      out.put_int(first_tag + static_cast<std::int64_t>(i));
      for (const Index v : elements[i]) {
        out.put(' ');
        out.put_int(std::int64_t{v} + 1);
      }
      out.put('\n');
    }
  }
}

void write_elements(const Mesh& mesh, const EntityPlan& surfaces, const EntityPlan& volumes,
                    OutputBuffer& out) {
  const std::size_t total = mesh.triangles.size() + mesh.tets.size();
  out.put("$Elements\n");
  if (total == 0) {
    out.put("0 0 0 0\n$EndElements\n");
    return;
  }
  out.put(str_cat(surfaces.tags.size() + volumes.tags.size(), " ", total, " 1 ", total, "\n"));
  write_element_blocks(mesh.triangles, surfaces, 2, kGmshTriangle, 1, out);
  write_element_blocks(mesh.tets, volumes, 3, kGmshTet,
                       1 + static_cast<std::int64_t>(mesh.triangles.size()), out);
  out.put("$EndElements\n");
}

}  // namespace

absl::Status write_msh(const Mesh& mesh, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  AFMESH_RETURN_IF_ERROR(check_tags_not_negative(mesh.triangle_tags, "triangle"));
  AFMESH_RETURN_IF_ERROR(check_tags_not_negative(mesh.tet_tags, "tetrahedron"));
  const EntityPlan surfaces = plan_entities(mesh.triangles, mesh.triangle_tags, mesh.points);
  const EntityPlan volumes = plan_entities(mesh.tets, mesh.tet_tags, mesh.points);
  const bool placeholder = surfaces.tags.empty() && volumes.tags.empty();
  out.put("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  write_entities(surfaces, volumes, placeholder, out);
  write_nodes(mesh.points, volumes.tags.empty() ? 2 : 3, out);
  write_elements(mesh, surfaces, volumes, out);
  return out.flush();
}

absl::Status write_msh_sized_grid(const Mesh& mesh, std::span<const double> sizes,
                                  OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_sizes_for_writing(sizes, mesh.points.size()));
  AFMESH_RETURN_IF_ERROR(write_msh(mesh, out));
  // View "size", time 0; time step 0, one component, one value per node.
  out.put(str_cat("$NodeData\n1\n\"size\"\n1\n0\n3\n0\n1\n", sizes.size(), "\n"));
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    out.put_int(static_cast<std::int64_t>(i + 1));
    out.put(' ');
    out.put_double(sizes[i]);
    out.put('\n');
  }
  out.put("$EndNodeData\n");
  return out.flush();
}

}  // namespace afmesh
