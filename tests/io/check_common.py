"""What meshio_check.py, gmsh_check.py and vtk_check.py share: the expectation file afmesh's
external_readers_test writes, the comparison of elements with their tags, and the report.

The expectation file (JSON) holds the mesh afmesh wrote:
  {"points": [[x, y, z], ...], "triangles": [[a, b, c], ...], "triangle_tags": [...],
   "tets": [[a, b, c, d], ...], "tet_tags": [...], ...}   # plus keys read by each checker
"""
import collections
import json

KINDS = (("triangles", "triangle_tags"), ("tets", "tet_tags"))


def load_expected(path):
    with open(path) as f:
        return json.load(f)


def empty_elements():
    """Elements by kind, as Counters of (corner point indices, tag)."""
    return {kind: collections.Counter() for kind, _ in KINDS}


def element_problems(found, expected, with_tags=True):
    """Differences between the elements a reader found and the expected ones, per kind,
    compared as multisets of (corners, tag) since formats may group elements by tag."""
    problems = []
    for kind, tag_name in KINDS:
        want = collections.Counter(
            (tuple(e), t if with_tags else None)
            for e, t in zip(expected[kind], expected[tag_name]))
        if found[kind] != want:
            missing = list((want - found[kind]).elements())[:5]
            extra = list((found[kind] - want).elements())[:5]
            problems.append(f"{kind}: {sum(found[kind].values())} read, "
                            f"{len(expected[kind])} expected; "
                            f"missing {missing}, unexpected {extra}")
    return problems


def finish(tool, reader, mesh_file, problems):
    """Prints the problems (or that all agrees) and returns the exit status."""
    for problem in problems:
        print(f"{tool}: {mesh_file}: {problem}")
    if not problems:
        print(f"{tool}: {mesh_file}: {reader} reads the expected mesh")
    return 1 if problems else 0
