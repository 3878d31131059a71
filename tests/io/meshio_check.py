#!/usr/bin/python3
"""Checks a mesh file written by afmesh against what meshio reads from it.

Usage: meshio_check.py MESH_FILE EXPECTED_JSON

EXPECTED_JSON is the JSON of check_common.py with two more keys:
   "tag_key": "gmsh:physical" | "medit:ref" | "tag" | null,   # meshio cell-data name, if any
   "match_points_by": "index" | "coordinates"                 # STL: meshio renumbers points
Points must agree to 1e-12 relative (the count of bit-exact ones is printed); elements are
compared as multisets of (corners, tag) since formats may group elements by tag. meshio
refusing the file (e.g. cell data out of step with its cell blocks) is a difference.
Exit status: 0 when meshio reads the same mesh, 1 when it differs, 2 on usage errors,
3 when meshio is not installed.
"""
import sys

from check_common import element_problems, empty_elements, finish, load_expected

try:
    import meshio
    import numpy as np
except ImportError as error:
    print(f"meshio_check: cannot import meshio ({error}); install python3-meshio")
    sys.exit(3)

CELL_TYPES = {"triangle": "triangles", "tetra": "tets"}


def read_cells(mesh, tag_key):
    """Elements of each kind as Counters of (corner tuple, tag or None), meshio's numbering."""
    cells = empty_elements()
    for block_index, block in enumerate(mesh.cells):
        if block.type not in CELL_TYPES:
            raise ValueError(f"unexpected cell type {block.type!r} ({len(block.data)} cells)")
        tags = [None] * len(block.data)
        if tag_key is not None:
            if tag_key not in mesh.cell_data:
                raise ValueError(f"no cell data {tag_key!r}; meshio has {list(mesh.cell_data)}")
            tags = [int(t) for t in mesh.cell_data[tag_key][block_index]]
        for corners, tag in zip(block.data, tags):
            cells[CELL_TYPES[block.type]][(tuple(int(c) for c in corners), tag)] += 1
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


def renumbered(cells, mapping):
    """`cells` with meshio's point indices replaced by the expected ones."""
    result = empty_elements()
    for kind, counter in cells.items():
        for (corners, tag), count in counter.items():
            result[kind][(tuple(mapping[c] for c in corners), tag)] += count
    return result


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    mesh_file, expected_file = sys.argv[1], sys.argv[2]
    expected = load_expected(expected_file)
    try:
        mesh = meshio.read(mesh_file)
    except Exception as error:  # meshio raises ValueError, ReadError, KeyError, ...
        return finish("meshio_check", "meshio", mesh_file,
                      [f"meshio cannot read it: {type(error).__name__}: {error}"])
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
            problems += element_problems(renumbered(cells, mapping), expected,
                                         with_tags=tag_key is not None)
    return finish("meshio_check", "meshio", mesh_file, problems)


if __name__ == "__main__":
    sys.exit(main())
