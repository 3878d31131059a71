#!/usr/bin/python3
"""Checks a .vtu file written by afmesh by loading it with VTK's own XML reader
(vtkXMLUnstructuredGridReader, Debian's python3-vtk9).

Usage: vtk_check.py VTU_FILE EXPECTED_JSON   (the JSON of check_common.py)

Compares point coordinates (exactly, point i is point i), the cells (VTK_TRIANGLE = 5 and
VTK_TETRA = 10 only, as multisets of (corners, tag)) and the one-component cell array "tag".
A reader error (vtk's error event) is a difference. Exit status: 0 same mesh, 1 different,
2 usage, 3 no vtk module.
"""
import sys

from check_common import element_problems, empty_elements, finish, load_expected

try:
    import vtk
except ImportError as error:
    print(f"vtk_check: cannot import vtk ({error}); install python3-vtk9")
    sys.exit(3)

VTK_KINDS = {5: "triangles", 10: "tets"}


def read_grid(vtu_file, problems):
    reader = vtk.vtkXMLUnstructuredGridReader()
    errors = []
    reader.AddObserver("ErrorEvent", lambda _obj, _event: errors.append("reader error"))
    reader.SetFileName(vtu_file)
    reader.Update()
    if errors or reader.GetErrorCode() != 0:
        problems.append(f"vtkXMLUnstructuredGridReader reports an error "
                        f"(code {reader.GetErrorCode()})")
    return reader.GetOutput()


def read_cells(grid, problems):
    found = empty_elements()
    tags = grid.GetCellData().GetArray("tag")
    if grid.GetNumberOfCells() > 0 and (tags is None or tags.GetNumberOfComponents() != 1):
        problems.append("no one-component cell array 'tag'")
        return found
    for c in range(grid.GetNumberOfCells()):
        cell_type = grid.GetCellType(c)
        if cell_type not in VTK_KINDS:
            problems.append(f"cell {c} has VTK type {cell_type}")
            continue
        ids = grid.GetCell(c).GetPointIds()
        corners = tuple(ids.GetId(k) for k in range(ids.GetNumberOfIds()))
        found[VTK_KINDS[cell_type]][(corners, int(tags.GetTuple1(c)))] += 1
    return found


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    vtu_file, expected_file = sys.argv[1], sys.argv[2]
    expected = load_expected(expected_file)
    problems = []
    grid = read_grid(vtu_file, problems)
    points = [list(grid.GetPoint(i)) for i in range(grid.GetNumberOfPoints())]
    if points != expected["points"]:
        problems.append(f"points differ: vtk has {len(points)} ({points[:3]}...), "
                        f"expected {len(expected['points'])} ({expected['points'][:3]}...)")
    problems += element_problems(read_cells(grid, problems), expected)
    return finish("vtk_check", "VTK", vtu_file, problems)


if __name__ == "__main__":
    sys.exit(main())
