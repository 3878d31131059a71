#!/usr/bin/python3
"""Checks an MSH or Medit file written by afmesh by loading it in gmsh itself (the gmsh Python
API).

Usage: gmsh_check.py MESH_FILE EXPECTED_JSON   (the JSON of check_common.py)

Compares node coordinates (node tag i+1 is point i, exactly), triangles and tetrahedra with
their tags (as multisets of (corners, tag)), and that gmsh reports no other element types.
Where the tag is, by extension:
  .msh   the entity's physical group: afmesh gives every entity exactly one, 0 for untagged
         elements (msh.h), so an entity with no or several physical groups is a difference;
  .mesh  the entity itself: gmsh's Medit reader puts the elements of each reference in the
         elementary entity of that number and makes no physical groups.
When the JSON has "sizes" (one per point), also checks that gmsh finds exactly one
post-processing view holding them as NodeData (node tag i+1 -> sizes[i], exactly, one
component). Exit status: 0 same mesh, 1 different, 2 usage, 3 no gmsh.
"""
import sys

from check_common import element_problems, empty_elements, finish, load_expected

try:
    import gmsh
except ImportError as error:
    print(f"gmsh_check: cannot import gmsh ({error}); install python3-gmsh")
    sys.exit(3)

GMSH_TYPES = {2: "triangles", 4: "tets"}


def msh_tag(dim, entity, problems):
    groups = [int(t) for t in gmsh.model.getPhysicalGroupsForEntity(dim, entity)]
    if len(groups) != 1:
        problems.append(f"entity {(dim, entity)} has physical groups {groups}, expected one")
        return None
    return groups[0]


def medit_tag(dim, entity, problems):
    groups = [int(t) for t in gmsh.model.getPhysicalGroupsForEntity(dim, entity)]
    if groups:
        problems.append(f"entity {(dim, entity)} of a Medit file has physical groups {groups}")
    return entity


def read_elements(tag_of, problems):
    """Elements by kind as Counters of (corner point indices, tag)."""
    found = empty_elements()
    for dim, entity in gmsh.model.getEntities():
        types, _, node_tags = gmsh.model.mesh.getElements(dim, entity)
        if len(types) == 0:
            continue
        tag = tag_of(dim, entity, problems)
        for element_type, nodes in zip(types, node_tags):
            if element_type not in GMSH_TYPES:
                problems.append(f"unexpected element type {element_type} on entity {(dim, entity)}")
                continue
            size = 3 if element_type == 2 else 4
            for k in range(0, len(nodes), size):
                corners = tuple(int(n) - 1 for n in nodes[k:k + size])
                found[GMSH_TYPES[element_type]][(corners, tag)] += 1
    return found


def check_nodes(points, problems):
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    if len(node_tags) != len(points):
        problems.append(f"gmsh has {len(node_tags)} nodes, expected {len(points)}")
    for i, tag in enumerate(node_tags):
        actual = [float(c) for c in coords[3 * i:3 * i + 3]]
        if tag < 1 or tag > len(points) or actual != points[int(tag) - 1]:
            problems.append(f"node {tag}: gmsh {actual}")
            break


def check_sizes(sizes, problems):
    views = gmsh.view.getTags()
    if len(views) != 1:
        problems.append(f"gmsh has {len(views)} views, expected 1 with the sizes")
        return
    data_type, tags, data, _, components = gmsh.view.getModelData(views[0], 0)
    if data_type != "NodeData" or components != 1:
        problems.append(f"the view holds {data_type} with {components} components")
        return
    found = {int(tag): [float(v) for v in values] for tag, values in zip(tags, data)}
    want = {i + 1: [size] for i, size in enumerate(sizes)}
    if found != want:
        problems.append(f"view sizes differ: gmsh {sorted(found.items())[:5]}..., "
                        f"expected {sorted(want.items())[:5]}...")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    mesh_file, expected_file = sys.argv[1], sys.argv[2]
    tag_of = {"msh": msh_tag, "mesh": medit_tag}.get(mesh_file.rsplit(".", 1)[-1].lower())
    if tag_of is None:
        print(f"gmsh_check: {mesh_file}: expected a .msh or .mesh file")
        return 2
    expected = load_expected(expected_file)
    gmsh.initialize(["gmsh_check", "-v", "2"])
    problems = []
    try:
        gmsh.open(mesh_file)
        check_nodes(expected["points"], problems)
        if "sizes" in expected:
            check_sizes(expected["sizes"], problems)
        problems += element_problems(read_elements(tag_of, problems), expected)
    finally:
        gmsh.finalize()
    return finish("gmsh_check", "gmsh", mesh_file, problems)


if __name__ == "__main__":
    sys.exit(main())
