#!/usr/bin/python3
"""Checks an MSH file written by afmesh by loading it in gmsh itself (the gmsh Python API).

Usage: gmsh_check.py MSH_FILE EXPECTED_JSON   (the same JSON as meshio_check.py)

Compares node coordinates (node tag i+1 is point i, exactly), triangles and tetrahedra with
their physical tags (as multisets of (corners, tag); 0 = no physical group), and that gmsh
reports no other element types. When the JSON has "sizes" (one per point), also checks that gmsh
finds exactly one post-processing view holding them as NodeData (node tag i+1 -> sizes[i],
exactly, one component). Exit status: 0 same mesh, 1 different, 2 usage, 3 no gmsh.
"""
import collections
import json
import sys

try:
    import gmsh
except ImportError as error:
    print(f"gmsh_check: cannot import gmsh ({error}); install python3-gmsh")
    sys.exit(3)

GMSH_TYPES = {2: "triangles", 4: "tets"}


def physical_tag_of(dim, entity):
    tags = gmsh.model.getPhysicalGroupsForEntity(dim, entity)
    return int(tags[0]) if len(tags) else 0


def read_elements(problems):
    """Elements by kind as Counters of (corner point indices, physical tag)."""
    found = {"triangles": collections.Counter(), "tets": collections.Counter()}
    for dim, entity in gmsh.model.getEntities():
        types, _, node_tags = gmsh.model.mesh.getElements(dim, entity)
        for element_type, nodes in zip(types, node_tags):
            if element_type not in GMSH_TYPES:
                problems.append(f"unexpected element type {element_type} on entity {(dim, entity)}")
                continue
            size = 3 if element_type == 2 else 4
            tag = physical_tag_of(dim, entity)
            for k in range(0, len(nodes), size):
                corners = tuple(int(n) - 1 for n in nodes[k:k + size])
                found[GMSH_TYPES[element_type]][(corners, tag)] += 1
    return found


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
    msh_file, expected_file = sys.argv[1], sys.argv[2]
    with open(expected_file) as f:
        expected = json.load(f)
    gmsh.initialize(["gmsh_check", "-v", "2"])
    problems = []
    try:
        gmsh.open(msh_file)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        points = expected["points"]
        if len(node_tags) != len(points):
            problems.append(f"gmsh has {len(node_tags)} nodes, expected {len(points)}")
        for i, tag in enumerate(node_tags):
            actual = [float(c) for c in coords[3 * i:3 * i + 3]]
            if tag < 1 or tag > len(points) or actual != points[int(tag) - 1]:
                problems.append(f"node {tag}: gmsh {actual}")
                break
        if "sizes" in expected:
            check_sizes(expected["sizes"], problems)
        found = read_elements(problems)
        for kind, tag_name in (("triangles", "triangle_tags"), ("tets", "tet_tags")):
            want = collections.Counter(
                (tuple(e), t) for e, t in zip(expected[kind], expected[tag_name]))
            if found[kind] != want:
                missing = list((want - found[kind]).elements())[:5]
                extra = list((found[kind] - want).elements())[:5]
                problems.append(f"{kind}: missing {missing}, unexpected {extra}")
    finally:
        gmsh.finalize()
    for problem in problems:
        print(f"gmsh_check: {msh_file}: {problem}")
    if not problems:
        print(f"gmsh_check: {msh_file}: gmsh reads the expected mesh")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
