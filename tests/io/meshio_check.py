#!/usr/bin/python3
"""Checks a mesh file written by afmesh against what meshio reads from it.

Usage: meshio_check.py MESH_FILE EXPECTED_JSON

EXPECTED_JSON holds the mesh afmesh wrote:
  {"points": [[x, y, z], ...], "triangles": [[a, b, c], ...], "triangle_tags": [...],
   "tets": [[a, b, c, d], ...], "tet_tags": [...],
   "tag_key": "gmsh:physical" | "medit:ref" | "tag" | null,   # meshio cell-data name, if any
   "match_points_by": "index" | "coordinates"}                # STL: meshio renumbers points
Points must agree to 1e-12 relative (the count of bit-exact ones is printed); elements are
compared as multisets of (corners, tag) since formats may group elements by tag.
Exit status: 0 when meshio reads the same mesh, 1 when it differs, 2 on usage errors,
3 when meshio is not installed.
"""
import collections
import json
import sys

try:
    import meshio
    import numpy as np
except ImportError as error:
    print(f"meshio_check: cannot import meshio ({error}); install python3-meshio")
    sys.exit(3)

CELL_TYPES = {"triangle": "triangles", "tetra": "tets"}


def read_cells(mesh, tag_key):
    """Elements of each kind as lists of (corner tuple, tag or None)."""
    cells = {"triangles": [], "tets": []}
    for block_index, block in enumerate(mesh.cells):
        if block.type not in CELL_TYPES:
            raise ValueError(f"unexpected cell type {block.type!r} ({len(block.data)} cells)")
        tags = [None] * len(block.data)
        if tag_key is not None:
            if tag_key not in mesh.cell_data:
                raise ValueError(f"no cell data {tag_key!r}; meshio has {list(mesh.cell_data)}")
            tags = [int(t) for t in mesh.cell_data[tag_key][block_index]]
        for corners, tag in zip(block.data, tags):
            cells[CELL_TYPES[block.type]].append((tuple(int(c) for c in corners), tag))
    return cells


def point_map(actual_points, expected_points, mode):
    """For each meshio point, the index of the expected point it stands for."""
    if mode == "index":
        return list(range(len(actual_points)))
    index_of = {tuple(p): i for i, p in enumerate(expected_points)}
    mapping = []
    for p in actual_points:
        key = tuple(float(c) for c in p)
        if key not in index_of:
            raise ValueError(f"meshio point {key} is not among the expected points")
        mapping.append(index_of[key])
    return mapping


def compare_points(actual, expected, mapping):
    problems = []
    exact = 0
    for i, p in enumerate(actual):
        q = expected[mapping[i]]
        for a, b in zip(p, q):
            if a == b:
                exact += 1
            elif abs(a - b) > 1e-12 * max(abs(a), abs(b)):
                problems.append(f"point {i}: meshio {list(p)} vs expected {q}")
                break
    print(f"meshio_check: {exact} of {3 * len(actual)} coordinates bit-exact")
    return problems


def compare_elements(kind, actual, expected, tags, mapping, with_tags):
    want = collections.Counter(
        (tuple(e), t if with_tags else None) for e, t in zip(expected, tags))
    have = collections.Counter(
        (tuple(mapping[c] for c in corners), tag) for corners, tag in actual)
    if want == have:
        return []
    missing = list((want - have).elements())[:5]
    extra = list((have - want).elements())[:5]
    return [f"{kind}: {len(actual)} read, {len(expected)} expected; "
            f"missing {missing}, unexpected {extra}"]


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    mesh_file, expected_file = sys.argv[1], sys.argv[2]
    with open(expected_file) as f:
        expected = json.load(f)
    mesh = meshio.read(mesh_file)
    points = np.asarray(mesh.points, dtype=float)
    problems = []
    if points.shape != (len(expected["points"]), 3):
        problems.append(f"points: meshio has shape {points.shape}, "
                        f"expected ({len(expected['points'])}, 3)")
    else:
        tag_key = expected["tag_key"]
        try:
            mapping = point_map(points.tolist(), expected["points"], expected["match_points_by"])
            cells = read_cells(mesh, tag_key)
        except ValueError as error:
            problems.append(str(error))
        else:
            problems += compare_points(points.tolist(), expected["points"], mapping)
            for kind, tag_name in (("triangles", "triangle_tags"), ("tets", "tet_tags")):
                problems += compare_elements(kind, cells[kind], expected[kind],
                                             expected[tag_name], mapping, tag_key is not None)
    for problem in problems:
        print(f"meshio_check: {mesh_file}: {problem}")
    if not problems:
        print(f"meshio_check: {mesh_file}: meshio reads the expected mesh")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
