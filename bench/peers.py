#!/usr/bin/python3
"""Peer meshers on the same surface as afmesh-bench-volume: gmsh (3-D Delaunay and HXT), netgen
and tetgen, each on one thread and in a fresh process, with the same speed, memory and quality
figures (see /work/shared/peers.md for how each is driven).

  peers.py volume --surface PREFIX --size H [--tools gmsh-delaunay,gmsh-hxt,netgen,tetgen]
                  [--timeout SECONDS] [--out-dir DIR] [--gmsh-sizes h|surface] [--json]
      PREFIX.mesh (Medit, exact coordinates) and PREFIX.smesh (tetgen) are written by
      `afmesh-bench-volume --surface PREFIX`; without PREFIX.smesh tetgen gets one written from
      PREFIX.mesh. --out-dir DIR: each tool's volume mesh goes to DIR/TOOL.mesh (Medit), for
      tools/check_volume.py. Two more tools for thin or crossing surfaces: tetgen-p (plain
      `tetgen -p`) and tetgen-d (`tetgen -d`: counts the intersecting face pairs, meshes nothing).
      A failed run reports its exit status (and signal) and the first line of its log that names
      the problem.
  peers.py io --stl IN.stl --out OUT.msh [--json]
      gmsh converting binary STL to MSH 4.1 (merge + write), the peer of afmesh-bench-io.
  peers.py quality MESH.mesh [--size H]
      the quality figures of a Medit volume mesh, computed as below (a cross-check of the C++);
      with --size, also its interior edge lengths against H (how bench/run_bench.py measures
      afmesh's meshes, so every tool's edges are measured by the same code).

What is measured, per tool:
  time       wall seconds of the volume phase only: gmsh model.mesh.generate(3), netgen
             GenerateVolumeMesh, tetgen's own "Total running seconds" minus "Output seconds"
             (so reading the small .smesh is included, writing the result is not).
  bytes/tet  (peak resident memory during that phase - resident memory before it) / tets. For
             gmsh and netgen the peak (VmHWM) is reset just before the phase, as in
             afmesh-bench-volume; for tetgen, a separate process, it is its peak RSS minus the peak
             RSS of tetgen meshing a single tetrahedron (the program's own footprint).
  quality    as core/quality/measures.h: per tet the smallest of the six dihedral angles (pi minus
             the angle between outward face normals) and the radius ratio 3 r_in / r_circ =
             108 V^2 / (A |m|); over the mesh the min dihedral, the shares below 10 and 20 degrees,
             and the min and mean radius ratio.
  edges      (edge_length_summary) the interior edges of the tet mesh, i.e. every tet edge that
             is not an edge of a boundary triangle (a tet face that belongs to one tet only):
             their mean length / h and the share of them in [0.7 h, 1.4 h], where h is the size
             asked of that tool (--size: gmsh Mesh.MeshSizeMax, netgen maxh, tetgen -a 0.34 h^3,
             afmesh's --size). A mesh that takes the size asked has mean edge / h near 1.

gmsh is asked h as Mesh.MeshSizeMax = h with Mesh.MeshSizeExtendFromBoundary = 0, so its interior
takes h whether the surface is finer or coarser (with the default, sizes are interpolated from the
surface and h has no effect, so its count could not be adjusted to another tool's);
--gmsh-sizes surface keeps that default (the thin inputs of bench/run_bench.py, whose surfaces are
graded by a size field).
"""

import argparse
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

TOOLS = ("gmsh-delaunay", "gmsh-hxt", "netgen", "tetgen")
TETGEN_VARIANTS = ("tetgen-p", "tetgen-d")  # for thin or crossing surfaces (bench/run_bench.py)
ALL_TOOLS = TOOLS + TETGEN_VARIANTS
GMSH_ALGORITHM_3D = {"gmsh-delaunay": 1, "gmsh-hxt": 10}
TETGEN_VOLUME_FACTOR = 0.34  # tetgen -a: max tet volume = 0.34 h^3 (peers.md)
TETGEN_QUALITY = "1.2"        # tetgen -q: radius-edge bound
QUALITY_CHUNK = 500_000       # tets per numpy batch when measuring quality
EDGE_BAND = (0.7, 1.4)        # the band of edge lengths (times h) whose share is reported


# ---------------------------------------------------------------------------------------------
# Resident memory of this process (Linux /proc), as bench/process_memory.h.

def _status_kilobytes(key):
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(key + ":"):
                return int(line.split()[1]) * 1024
    raise RuntimeError(f"/proc/self/status has no {key} line")


class PeakMemoryProbe:
    """Peak resident memory of one phase: start() resets VmHWM, finish() reads it."""

    def start(self):
        try:
            with open("/proc/self/clear_refs", "w") as clear_refs:
                clear_refs.write("5")
            self.peak_was_reset = True
        except OSError:
            self.peak_was_reset = False
        self.start_bytes = _status_kilobytes("VmRSS")

    def finish(self):
        self.peak_bytes = _status_kilobytes("VmHWM")

    def figures(self, tets):
        return {"rss_before_bytes": self.start_bytes, "rss_peak_bytes": self.peak_bytes,
                "bytes_per_tet": (self.peak_bytes - self.start_bytes) / max(tets, 1),
                "peak_reset": self.peak_was_reset}


class PhaseClock:
    """Wall and CPU seconds of one phase of this process."""

    def __enter__(self):
        self._wall, self._cpu = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.seconds = time.perf_counter() - self._wall
        self.cpu_seconds = time.process_time() - self._cpu


# ---------------------------------------------------------------------------------------------
# Quality, as core/quality/measures.cc.

def _angle_between(u, v):
    """Angles in [0, pi] between rows of u and v (atan2 of |u x v| and u.v); 0 if both vanish."""
    sine = np.linalg.norm(np.cross(u, v), axis=1)
    cosine = np.einsum("ij,ij->i", u, v)
    return np.where((sine == 0.0) & (cosine == 0.0), 0.0, np.arctan2(sine, cosine))


def _min_dihedral_degrees(p0, p1, p2, p3):
    """Smallest dihedral angle (degrees) of each tet; rows of p0..p3 are its corners."""
    normals = [np.cross(p2 - p1, p3 - p1), np.cross(p3 - p0, p2 - p0),
               np.cross(p1 - p0, p3 - p0), np.cross(p2 - p0, p1 - p0)]
    defined = [np.einsum("ij,ij->i", n, n) > 0.0 for n in normals]
    smallest = np.full(len(p0), np.inf)
    for i in range(4):
        for j in range(i + 1, 4):
            angle = np.where(defined[i] & defined[j], _angle_between(normals[i], -normals[j]), 0.0)
            smallest = np.minimum(smallest, angle)
    return np.degrees(smallest)


def _radius_ratio(p0, p1, p2, p3):
    """3 r_in / r_circ = 108 V^2 / (A |m|) of each tet; 0 for a flat one."""
    b, c, d = p1 - p0, p2 - p0, p3 - p0
    volume = np.einsum("ij,ij->i", np.cross(b, c), d) / 6.0
    area = 0.5 * (np.linalg.norm(np.cross(p2 - p1, p3 - p1), axis=1)
                  + np.linalg.norm(np.cross(c, d), axis=1)
                  + np.linalg.norm(np.cross(b, d), axis=1)
                  + np.linalg.norm(np.cross(b, c), axis=1))
    sq = lambda v: np.einsum("ij,ij->i", v, v)[:, None]
    m = sq(b) * np.cross(c, d) + sq(c) * np.cross(d, b) + sq(d) * np.cross(b, c)
    denominator = area * np.linalg.norm(m, axis=1)
    ok = (volume != 0.0) & (denominator > 0.0)
    return np.where(ok, 108.0 * volume * volume / np.where(ok, denominator, 1.0), 0.0)


def tet_quality_summary(points, tets):
    """Quality figures of tets (K x 4, 0-based) over points (N x 3), as summarize_quality."""
    points = np.asarray(points, dtype=np.float64)
    tets = np.asarray(tets, dtype=np.int64)
    if len(tets) == 0:
        return {"min_dihedral": None, "share_below_10": None, "share_below_20": None,
                "min_radius_ratio": None, "mean_radius_ratio": None}
    min_dihedral, below_10, below_20, min_ratio, ratios = math.inf, 0, 0, math.inf, []
    for start in range(0, len(tets), QUALITY_CHUNK):
        corners = [points[tets[start:start + QUALITY_CHUNK, k]] for k in range(4)]
        dihedral = _min_dihedral_degrees(*corners)
        ratio = _radius_ratio(*corners)
        min_dihedral = min(min_dihedral, float(dihedral.min()))
        below_10 += int(np.count_nonzero(dihedral < 10.0))
        below_20 += int(np.count_nonzero(dihedral < 20.0))
        min_ratio = min(min_ratio, float(ratio.min()))
        ratios.append(ratio)
    return {"min_dihedral": min_dihedral, "share_below_10": below_10 / len(tets),
            "share_below_20": below_20 / len(tets), "min_radius_ratio": min_ratio,
            "mean_radius_ratio": math.fsum(np.concatenate(ratios)) / len(tets)}



def _row_keys(rows, base):
    """One int64 key per row of sorted small non-negative integers (rows K x m, values < base)."""
    keys = np.zeros(len(rows), dtype=np.int64)
    for column in range(rows.shape[1]):
        keys = keys * base + rows[:, column]
    return keys


def edge_length_summary(points, tets, size):
    """Interior edges of a tet mesh against the size h asked of its tool: {"interior_edges",
    "mean_edge_over_h", "share_edges_in_band"} (band EDGE_BAND times h). An edge is interior when
    it is not an edge of a boundary triangle, a tet face that belongs to one tet only (so the
    boundary is the mesh's own, whatever the tool did to the input surface)."""
    points = np.asarray(points, dtype=np.float64)
    tets = np.sort(np.asarray(tets, dtype=np.int64), axis=1)
    empty = {"interior_edges": 0, "mean_edge_over_h": None, "share_edges_in_band": None}
    if len(tets) == 0 or not size or size <= 0.0:
        return empty
    base = int(tets.max()) + 1
    if base ** 3 >= 2 ** 63:
        raise ValueError(f"edge_length_summary: {base} points are too many for int64 face keys")
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 2, 3]], tets[:, [0, 1, 3]],
                            tets[:, [0, 1, 2]]])
    face_keys, first, counts = np.unique(_row_keys(faces, base), return_index=True,
                                         return_counts=True)
    boundary = faces[first[counts == 1]]
    del faces, face_keys
    boundary_edges = np.unique(_row_keys(np.concatenate(
        [boundary[:, [0, 1]], boundary[:, [0, 2]], boundary[:, [1, 2]]]), base))
    edges = np.unique(_row_keys(np.concatenate(
        [tets[:, [a, b]] for a in range(4) for b in range(a + 1, 4)]), base))
    interior = edges[~np.isin(edges, boundary_edges, assume_unique=True)]
    if len(interior) == 0:
        return empty
    lengths = np.linalg.norm(points[interior // base] - points[interior % base], axis=1) / size
    in_band = np.count_nonzero((lengths >= EDGE_BAND[0]) & (lengths <= EDGE_BAND[1]))
    return {"interior_edges": int(len(interior)),
            "mean_edge_over_h": math.fsum(lengths) / len(lengths),
            "share_edges_in_band": in_band / len(lengths)}

# ---------------------------------------------------------------------------------------------
# Input: the surface afmesh-bench-volume wrote.

def read_medit(path):
    """Points (N x 3), triangles (M x 3) and tets (K x 4), 0-based, of a Medit ascii file."""
    import meshio
    mesh = meshio.read(path, file_format="medit")
    cells = mesh.cells_dict
    empty = lambda n: np.zeros((0, n), dtype=np.int64)
    return (np.asarray(mesh.points, dtype=np.float64),
            np.asarray(cells.get("triangle", empty(3)), dtype=np.int64),
            np.asarray(cells.get("tetra", empty(4)), dtype=np.int64))


# ---------------------------------------------------------------------------------------------
# The peers, each run inside a child process (see run_child).

def gmsh_volume(tool, points, triangles, size, sizes_from="h"):
    """gmsh: the triangles as one discrete surface, a surface loop and a volume; times
    generate(3) with Mesh.Algorithm3D = 1 (Delaunay) or 10 (HXT), one thread, the interior sized
    h (Mesh.MeshSizeMax = h, Mesh.MeshSizeExtendFromBoundary = 0), or with sizes_from "surface"
    by gmsh's default, the sizes interpolated from the surface."""
    sized = ([("Mesh.MeshSizeMax", size), ("Mesh.MeshSizeExtendFromBoundary", 0)]
             if sizes_from == "h" else [])
    import gmsh
    gmsh.initialize([], False)
    try:
        for name, value in (("General.Terminal", 1), ("General.Verbosity", 2),
                            ("General.NumThreads", 1), ("Mesh.MaxNumThreads3D", 1),
                            ("Mesh.Algorithm3D", GMSH_ALGORITHM_3D[tool]), *sized):
            gmsh.option.setNumber(name, value)
        gmsh.model.add("case")
        surface = gmsh.model.addDiscreteEntity(2)
        gmsh.model.mesh.addNodes(2, surface, np.arange(1, len(points) + 1), points.ravel())
        gmsh.model.mesh.addElementsByType(surface, 2, [], (triangles + 1).ravel())
        loop = gmsh.model.geo.addSurfaceLoop([surface])
        gmsh.model.geo.addVolume([loop])
        gmsh.model.geo.synchronize()
        probe = PeakMemoryProbe()
        probe.start()
        with PhaseClock() as clock:
            gmsh.model.mesh.generate(3)
        probe.finish()
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        _, tet_nodes = gmsh.model.mesh.getElementsByType(4)
        index = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
        index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
        mesh_points = coords.reshape(-1, 3)
        tets = index[tet_nodes.astype(np.int64)].reshape(-1, 4)
    finally:
        gmsh.finalize()
    return clock, probe, mesh_points, tets, {
        "options": f"Mesh.Algorithm3D={GMSH_ALGORITHM_3D[tool]}"
                   + "".join(f" {name}={value:g}" for name, value in sized)}


def netgen_volume(tool, points, triangles, size):
    """netgen: the triangles as outward Element2Ds of one face descriptor; times
    GenerateVolumeMesh(MeshingParameters(maxh=h)) (Delaunay core, advancing front near the
    boundary, then optimisation)."""
    from netgen.csg import Pnt
    from netgen.meshing import Element2D, FaceDescriptor, MeshingParameters, MeshPoint, Mesh
    mesh = Mesh(dim=3)
    face = mesh.Add(FaceDescriptor(surfnr=1, domin=1, domout=0, bc=1))
    ids = [mesh.Add(MeshPoint(Pnt(*p))) for p in points.tolist()]
    for a, b, c in triangles.tolist():
        mesh.Add(Element2D(face, [ids[a], ids[b], ids[c]]))
    parameters = MeshingParameters(maxh=size)
    probe = PeakMemoryProbe()
    probe.start()
    with PhaseClock() as clock:
        mesh.GenerateVolumeMesh(parameters)
    probe.finish()
    mesh_points = np.array([p.p for p in mesh.Points()], dtype=np.float64)
    tets = np.array([[v.nr - 1 for v in e.vertices] for e in mesh.Elements3D()],
                    dtype=np.int64).reshape(-1, 4)
    return clock, probe, mesh_points, tets, {"options": f"maxh={size:g}"}


# tetgen's timing lines, e.g. "Total running seconds:  1.23".
_TETGEN_SECONDS = re.compile(r"^(Total running|Output) seconds:\s+([0-9.eE+-]+)", re.M)
# tetgen -d's verdict, e.g. "!! Found 2461 pairs of faces are intersecting."
_TETGEN_PAIRS = re.compile(r"Found (\d+) pairs? of faces (?:are )?intersecting")
# A log line naming a problem (the first one is reported beside a failure's exit status).
_PROBLEM_LINE = re.compile(r"error|intersect|overlap|terminate|abort|segmentation|exception|"
                           r"invalid|fail|cannot|unable", re.I)


def first_problem_line(text):
    """The first line of a log that names a problem (an error, an intersection, ...), or ''.
    A Python traceback ends the search: its frames quote source code, and its last line (the
    exception) is reported on its own."""
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("Traceback (most recent call last)"):
            break
        if _PROBLEM_LINE.search(line):
            return line
    return ""


def exit_status_text(status):
    """'exit status 1', or for a signal (a negative status, or a shell's 128 + n) its name."""
    number = -status if status < 0 else status - 128 if status > 128 else 0
    if number:
        try:
            return f"exit status {status} ({signal.Signals(number).name})"
        except ValueError:
            pass
    return f"exit status {status}"


def write_smesh(points, triangles, path):
    """tetgen's .smesh of a triangulated surface (1-based, no holes, no regions); repr keeps the
    coordinates exact."""
    with open(path, "w") as f:
        f.write(f"{len(points)} 3 0 0\n")
        for i, (x, y, z) in enumerate(points.tolist(), start=1):
            f.write(f"{i} {x!r} {y!r} {z!r}\n")
        f.write(f"{len(triangles)} 0\n")
        for a, b, c in (triangles + 1).tolist():
            f.write(f"3 {a} {b} {c}\n")
        f.write("0\n0\n")


def _run_tetgen(arguments, cwd):
    """Runs tetgen under /usr/bin/time, returning (stdout, peak RSS bytes, cpu seconds, exit
    status). GNU time forks from its own small process: a child forked from this Python process
    would count Python's resident memory in its peak (ru_maxrss survives exec). stdbuf -oL: the
    lines tetgen printed before an abort or a crash are not lost in its stdio buffer."""
    usage_path = os.path.join(cwd, "usage.txt")
    process = subprocess.run(["/usr/bin/time", "-f", "%M %U %S", "-o", usage_path, "stdbuf",
                              "-oL", "tetgen", *arguments], cwd=cwd, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True)
    with open(usage_path) as f:
        usage = f.read().split()
    if process.returncode != 0 or len(usage) < 3:
        return process.stdout, 0, 0.0, process.returncode or 1
    kilobytes, user, system = usage[-3:]
    return process.stdout, int(kilobytes) * 1024, float(user) + float(system), 0


def _tetgen_footprint(workdir):
    """Peak RSS of tetgen meshing one tetrahedron: what the program costs without a mesh."""
    with open(os.path.join(workdir, "one.smesh"), "w") as f:
        f.write("4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
                "4 0\n3 1 3 2\n3 1 2 4\n3 1 4 3\n3 2 3 4\n0\n0\n")
    _, peak, _, _ = _run_tetgen(["-pYQ", "one.smesh"], workdir)
    return peak


def _read_tetgen_table(path, columns):
    """Indices and the first `columns` values after them of each row of a tetgen .node/.ele file
    (header line, then one row per item; '#' starts a comment)."""
    with open(path) as f:
        lines = [line.split("#", 1)[0].strip() for line in f]
    lines = [line for line in lines if line]
    count = int(lines[0].split()[0])
    rows = lines[1:1 + count]
    width = len(rows[0].split()) if rows else columns + 1
    values = np.array(" ".join(rows).split(), dtype=np.float64).reshape(count, width)
    return values[:, 0], values[:, 1:1 + columns]


def _tetgen_case(workdir, points, triangles, smesh_path):
    """case.smesh in workdir: a copy of smesh_path, or written from the surface when there is none.
    A name without dots (tetgen takes "a.b" as iteration b of "a"), and the .smesh alone (given
    "case.smesh", tetgen opens case.poly instead when one exists)."""
    case = os.path.join(workdir, "case.smesh")
    if smesh_path and os.path.exists(smesh_path):
        shutil.copy(smesh_path, case)
    else:
        write_smesh(points, triangles, case)


def _tetgen_failure(arguments, status, output):
    """The error of a failed tetgen run: exit status, the first problem line and the last step."""
    lines = [line.strip() for line in output.splitlines() if line.strip()]
    problem = first_problem_line(output)
    steps = [line for line in lines if line.endswith("...")]
    step = f" (last step: {steps[-1]})" if steps else ""
    if problem:
        return f"tetgen {' '.join(arguments)}: {exit_status_text(status)}: {problem}{step}"
    return (f"tetgen {' '.join(arguments)}: {exit_status_text(status)}, no error message"
            f"{step or (': ' + lines[-1] if lines else ', no output')}")


def tetgen_volume(tool, points, triangles, size, smesh_path):
    """tetgen -pYq1.2 -a<0.34 h^3> on the .smesh (-Y keeps the surface as given), or for
    tetgen-p plain -p (no quality or size bound, may split the surface)."""
    workdir = tempfile.mkdtemp(prefix="afmesh-tetgen-")
    try:
        _tetgen_case(workdir, points, triangles, smesh_path)
        footprint = _tetgen_footprint(workdir)
        if tool == "tetgen-p":
            arguments = ["-p", "case.smesh"]
        else:
            max_volume = TETGEN_VOLUME_FACTOR * size ** 3
            arguments = [f"-pYq{TETGEN_QUALITY}", f"-a{max_volume:.6g}", "case.smesh"]
        started = time.perf_counter()
        output, peak, cpu, status = _run_tetgen(arguments, workdir)
        wall = time.perf_counter() - started
        if status != 0:
            raise RuntimeError(_tetgen_failure(arguments, status, output))
        seconds = dict(_TETGEN_SECONDS.findall(output))
        clock = PhaseClock()
        clock.seconds = float(seconds["Total running"]) - float(seconds.get("Output", 0.0))
        clock.cpu_seconds = cpu
        probe = PeakMemoryProbe()
        probe.start_bytes, probe.peak_bytes, probe.peak_was_reset = footprint, peak, True
        first, node_xyz = _read_tetgen_table(os.path.join(workdir, "case.1.node"), 3)
        _, ele = _read_tetgen_table(os.path.join(workdir, "case.1.ele"), 4)
        tets = ele.astype(np.int64) - int(first[0])
        extra = {"options": " ".join(arguments[:-1]), "process_wall_seconds": wall}
        return clock, probe, node_xyz, tets, extra
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def tetgen_detect(surface_prefix):
    """tetgen -d: the number of intersecting face pairs it finds on the surface (no mesh)."""
    points, triangles, _ = read_medit(surface_prefix + ".mesh")
    workdir = tempfile.mkdtemp(prefix="afmesh-tetgen-")
    try:
        _tetgen_case(workdir, points, triangles, surface_prefix + ".smesh")
        arguments = ["-d", "case.smesh"]
        started = time.perf_counter()
        output, _, cpu, status = _run_tetgen(arguments, workdir)
        wall = time.perf_counter() - started
        if status != 0:
            raise RuntimeError(_tetgen_failure(arguments, status, output))
        found = _TETGEN_PAIRS.search(output)
        pairs = int(found.group(1)) if found else 0
        return {"tool": "tetgen-d", "options": "-d", "surface_points": len(points),
                "surface_triangles": len(triangles), "seconds": wall,
                "cpu_seconds": cpu, "intersecting_pairs": pairs,
                "verdict": found.group(0) if found else first_problem_line(output)
                or "no intersecting face pairs reported"}
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def write_volume_medit(points, tets, path):
    """The tets as a Medit file (no boundary triangles: check_volume.py takes them from the input)."""
    import meshio
    meshio.write(path, meshio.Mesh(points, [("tetra", tets)]), file_format="medit")


def measure_volume(tool, surface_prefix, size, out=None, gmsh_sizes="h"):
    """Runs one peer on the surface and returns its figures (a dict); with `out`, writes the
    volume mesh there (Medit) when it has tets."""
    if tool == "tetgen-d":
        return tetgen_detect(surface_prefix)
    points, triangles, _ = read_medit(surface_prefix + ".mesh")
    if tool in GMSH_ALGORITHM_3D:
        run = gmsh_volume(tool, points, triangles, size, gmsh_sizes)
    elif tool == "netgen":
        run = netgen_volume(tool, points, triangles, size)
    else:
        run = tetgen_volume(tool, points, triangles, size, surface_prefix + ".smesh")
    clock, probe, mesh_points, tets, extra = run
    figures = {"tool": tool, "size": size, "surface_points": len(points),
               "surface_triangles": len(triangles), "tets": len(tets),
               "points": len(mesh_points), "seconds": clock.seconds,
               "cpu_seconds": clock.cpu_seconds}
    figures.update(probe.figures(len(tets)))
    figures.update(tet_quality_summary(mesh_points, tets))
    if tool != "tetgen-p" and not (tool in GMSH_ALGORITHM_3D and gmsh_sizes != "h"):
        figures.update(edge_length_summary(mesh_points, tets, size))
    figures.update(extra)
    if out and len(tets):
        write_volume_medit(mesh_points, tets, out)
        figures["mesh_file"] = out
    return figures


def measure_io(stl_path, msh_path):
    """gmsh: merge a binary STL and write it as MSH 4.1 ascii, timing both."""
    import gmsh
    probe = PeakMemoryProbe()
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 1)
        gmsh.option.setNumber("General.Verbosity", 2)
        gmsh.option.setNumber("General.NumThreads", 1)
        probe.start()
        with PhaseClock() as read_clock:
            gmsh.merge(stl_path)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        with PhaseClock() as write_clock:
            gmsh.write(msh_path)
        probe.finish()
        node_tags, _, _ = gmsh.model.mesh.getNodes()
        triangle_tags, _ = gmsh.model.mesh.getElementsByType(2)
    finally:
        gmsh.finalize()
    return {"tool": "gmsh", "points": len(node_tags), "triangles": len(triangle_tags),
            "read_seconds": read_clock.seconds, "write_seconds": write_clock.seconds,
            "seconds": read_clock.seconds + write_clock.seconds,
            "stl_bytes": os.path.getsize(stl_path), "msh_bytes": os.path.getsize(msh_path),
            "rss_before_bytes": probe.start_bytes, "rss_peak_bytes": probe.peak_bytes,
            "bytes_per_triangle": (probe.peak_bytes - probe.start_bytes) / max(len(triangle_tags), 1)}


# ---------------------------------------------------------------------------------------------
# Fresh process per measurement.

def run_child(job, result_path):
    """In the child: runs `job` (a dict) and writes its figures as JSON to result_path."""
    if job["kind"] == "volume":
        figures = measure_volume(job["tool"], job["surface"], job["size"], job.get("out"),
                                 job.get("gmsh_sizes", "h"))
    else:
        figures = measure_io(job["stl"], job["out"])
    with open(result_path, "w") as f:
        json.dump(figures, f)


def _log_lines(path):
    with open(path, errors="replace") as f:
        return [line.strip() for line in f if line.strip() and not set(line.strip()) <= set("+*^~")]


_NETGEN_PAIR = re.compile(r"Intersecting elements (\d+) and (\d+)")


def netgen_intersecting_pairs(text):
    """Distinct surface element pairs netgen warned about ("WARNING: Intersecting elements a
    and b"; it may name a pair more than once)."""
    return len({tuple(sorted(map(int, m))) for m in _NETGEN_PAIR.findall(text)})


def in_fresh_process(job, timeout):
    """Runs `job` in a new Python process (one thread: OMP_NUM_THREADS=1) and returns its figures,
    or {"error": ...} naming what went wrong (the child's last log lines; "first_problem": the
    first log line naming a problem, "last_line": the last one, e.g. the exception). Either way
    "process_seconds" is the child's wall time from start to exit (start-up and reading
    included)."""
    with tempfile.TemporaryDirectory(prefix="afmesh-peer-") as tmp:
        result_path, log_path = os.path.join(tmp, "result.json"), os.path.join(tmp, "log.txt")
        env = dict(os.environ, OMP_NUM_THREADS="1")
        command = [sys.executable, os.path.abspath(__file__), "_child", json.dumps(job), result_path]
        started = time.perf_counter()
        with open(log_path, "w") as log:
            child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env,
                                     start_new_session=True)
            try:
                child.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(child.pid, signal.SIGKILL)  # the child and its tetgen, nothing else
                child.wait()
                return {"error": f"timed out after {timeout:g} s (killed)", "timed_out": True,
                        "process_seconds": time.perf_counter() - started}
        elapsed = time.perf_counter() - started
        lines = _log_lines(log_path)
        text = "\n".join(lines)
        if child.returncode != 0 or not os.path.exists(result_path):
            figures = {"error": f"{exit_status_text(child.returncode)}: {' | '.join(lines[-4:])}",
                       "last_line": lines[-1] if lines else ""}
        else:
            with open(result_path) as f:
                figures = json.load(f)
        figures["process_seconds"] = elapsed
        if first_problem_line(text):
            figures["first_problem"] = first_problem_line(text)
        if job.get("tool") == "netgen" and netgen_intersecting_pairs(text):
            figures["intersecting_pairs"] = netgen_intersecting_pairs(text)
        return figures


# ---------------------------------------------------------------------------------------------
# Printing.

def _fmt(value, spec):
    return "-" if value is None else format(value, spec)


def print_volume(figures):
    tool = figures.get("tool", "?")
    if "error" in figures:
        print(f"{tool:14s} FAILED: {figures['error']}")
        return
    if "intersecting_pairs" in figures and tool == "tetgen-d":
        print(f"{tool:14s} {figures['verdict']} ({figures['seconds']:.3f} s)")
        return
    if figures["tets"] == 0:
        print(f"{tool:14s} no tets: only the surface came out ({figures.get('options', '')})")
        return
    print(f"{tool:14s} {figures['tets']} tets, {figures['points']} points "
          f"({figures.get('options', '')})")
    print(f"  time         {figures['seconds']:.3f} s wall, {figures['cpu_seconds']:.3f} s cpu: "
          f"{figures['tets'] / figures['seconds']:.0f} tets/s")
    print(f"  memory       before {figures['rss_before_bytes'] / 2**20:.1f} MiB, peak "
          f"{figures['rss_peak_bytes'] / 2**20:.1f} MiB: {figures['bytes_per_tet']:.0f} bytes/tet")
    print(f"  quality      min dihedral {_fmt(figures['min_dihedral'], '.2f')} deg, "
          f"<10 deg {100 * figures['share_below_10']:.3f}%, "
          f"<20 deg {100 * figures['share_below_20']:.3f}%, radius ratio min "
          f"{_fmt(figures['min_radius_ratio'], '.4f')} mean {_fmt(figures['mean_radius_ratio'], '.4f')}")
    if figures.get("mean_edge_over_h") is not None:
        print(f"  edges        {figures['interior_edges']} interior: mean length / h "
              f"{figures['mean_edge_over_h']:.3f}, {100 * figures['share_edges_in_band']:.1f}% in "
              f"[{EDGE_BAND[0]:g} h, {EDGE_BAND[1]:g} h] (h = {figures['size']:g})")


def print_io(figures):
    if "error" in figures:
        print(f"gmsh io FAILED: {figures['error']}")
        return
    print(f"gmsh merge + write MSH 4.1: {figures['points']} points, {figures['triangles']} triangles")
    print(f"  time         read {figures['read_seconds']:.3f} s + write {figures['write_seconds']:.3f} s"
          f" = {figures['seconds']:.3f} s")
    print(f"  memory       before {figures['rss_before_bytes'] / 2**20:.1f} MiB, peak "
          f"{figures['rss_peak_bytes'] / 2**20:.1f} MiB: {figures['bytes_per_triangle']:.0f} bytes/triangle")


# ---------------------------------------------------------------------------------------------

def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    volume = commands.add_parser("volume", help="mesh a surface with the peers")
    volume.add_argument("--surface", required=True, help="PREFIX of PREFIX.mesh and PREFIX.smesh")
    volume.add_argument("--size", type=float, required=True, help="target edge length h")
    volume.add_argument("--tools", default=",".join(TOOLS),
                        help="comma-separated: " + ",".join(ALL_TOOLS))
    volume.add_argument("--timeout", type=float, default=3600.0, help="seconds per tool")
    volume.add_argument("--out-dir", help="write each tool's volume mesh to OUT_DIR/TOOL.mesh")
    volume.add_argument("--gmsh-sizes", choices=("h", "surface"), default="h",
                        help="gmsh's interior size: h (Mesh.MeshSizeMax, default) or interpolated "
                             "from the surface (gmsh's default; h has no effect)")
    volume.add_argument("--json", action="store_true", help="one JSON object per tool and line")
    io = commands.add_parser("io", help="gmsh converting STL to MSH 4.1")
    io.add_argument("--stl", required=True)
    io.add_argument("--out", required=True)
    io.add_argument("--timeout", type=float, default=3600.0)
    io.add_argument("--json", action="store_true")
    quality = commands.add_parser("quality", help="quality figures of a Medit volume mesh")
    quality.add_argument("mesh")
    quality.add_argument("--size", type=float, help="also the interior edge lengths against h")
    return parser.parse_args(argv)


def main(argv):
    if len(argv) == 3 and argv[0] == "_child":
        run_child(json.loads(argv[1]), argv[2])
        return 0
    args = parse_arguments(argv)
    if args.command == "quality":
        points, _, tets = read_medit(args.mesh)
        figures = tet_quality_summary(points, tets)
        if args.size is not None:
            figures.update(edge_length_summary(points, tets, args.size))
        print(json.dumps(figures))
        return 0
    if args.command == "io":
        figures = in_fresh_process({"kind": "io", "stl": args.stl, "out": args.out}, args.timeout)
        if args.json:
            print(json.dumps(figures))
        else:
            print_io(figures)
        return 1 if "error" in figures else 0
    failed = False
    for tool in args.tools.split(","):
        if tool not in ALL_TOOLS:
            sys.exit(f"peers.py: unknown tool '{tool}'; known: {', '.join(ALL_TOOLS)}")
        job = {"kind": "volume", "tool": tool, "surface": args.surface, "size": args.size,
               "gmsh_sizes": args.gmsh_sizes}
        if args.out_dir:
            job["out"] = os.path.join(os.path.abspath(args.out_dir), f"{tool}.mesh")
        figures = in_fresh_process(job, args.timeout)
        figures.setdefault("tool", tool)
        failed |= "error" in figures
        if args.json:
            print(json.dumps(figures))
        else:
            print_volume(figures)
        sys.stdout.flush()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
