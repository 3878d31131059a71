#!/usr/bin/python3
"""Surface re-triangulation side by side (issue 11): afmesh against CGAL isotropic_remeshing,
gmsh classifySurfaces + createGeometry and netgen's STL mesher, on the same inputs at the same
target edge length h and ridge angle, every output judged by the same code that is not ours
(bench/surface/cgal_remesh.cc, measure mode). See bench/surface/README.md.

Every run is a fresh process, one after the other, on one thread (OMP_NUM_THREADS=1; gmsh
General.NumThreads = 1): afmesh as `AFMESH surface IN -o OUT --size H --ridge-angle A --quiet`
(row afmesh: its default curvature bound on; row afmesh-h: `--curvature-angle 0`, the size alone
as the peers are given it; row afmesh-d: `--curvature-deviation 0.001`, the accuracy goal asked),
CGAL as `cgal_remesh remesh` (compiled once with g++ and cached in the build directory), gmsh and
netgen as a child of this script. Each runs under /usr/bin/time (process wall seconds, peak
RSS) with a timeout; a tool that fails shows its exit status and message in its row.

Columns, per tool: tris = output triangles; phase s = wall seconds of the remeshing phase (gmsh:
classifySurfaces + createGeometry + generate(2); netgen: GenerateMesh; CGAL: detect_sharp_edges
+ isotropic_remeshing; afmesh: the whole command, marked '*', as its phases are not exposed);
tris/s = tris / phase s; proc s = the whole process (start-up, reading and writing included),
cpu s = its CPU seconds (user + system; on a loaded machine wall > cpu);
min / %>=30 / <15 = smallest triangle angle, share of triangles whose smallest angle is >= 30
degrees, count under 15; H/diag = two-sided Hausdorff distance (each side sampled at vertices,
edge midpoints and centroids) over the input's bounding-box diagonal, in percent; ridge = share
of the input's ridge length (normals > A apart) covered by output edges; corners = input corners
(3+ ridges) with an output vertex on them; edge/h = mean output edge length / h; B/tri = (peak
RSS of the phase - RSS before it) / tris (afmesh: the peak RSS of its largest process / tris,
marked '*'). The ratio lines (one per afmesh row) divide afmesh's tris/s (whole command) by each peer's tris/s over
its whole process (by wall and by CPU seconds), and its B/tri by the peer's: > 1 means afmesh
is faster (or uses more memory per triangle).
"""

import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

SURFACE_DIR = os.path.dirname(os.path.abspath(__file__))
BENCH_DIR = os.path.dirname(SURFACE_DIR)
REPO_DIR = os.path.dirname(BENCH_DIR)
sys.path.insert(0, BENCH_DIR)
import peers  # noqa: E402  bench/peers.py: phase clock, memory probe, exit status and error lines
import run_bench  # noqa: E402  bench/run_bench.py: run_process, machine/load/source lines, cells

CORPUS_DIR = os.path.join(REPO_DIR, "..", "shared", "corpus")
CGAL_SOURCE = os.path.join(SURFACE_DIR, "cgal_remesh.cc")
# afmesh-h: afmesh with the size alone (--curvature-angle 0), as the peers are driven (gmsh without
# MeshSizeFromCurvature, CGAL and netgen with h only): afmesh's default also bounds the turn of
# its elements where the input curves (30 degrees), which on a scan asks for far more triangles
# than h does. afmesh-d: afmesh asked to stay within issue 11's accuracy goal, 0.1% of the
# diagonal (--curvature-deviation 0.001), which refines where the input curves or creases under
# the ridge angle. Every row is shown; each has its own ratio line.
AFMESH_FLAGS = {"afmesh": [], "afmesh-h": ["--curvature-angle", "0"],
                "afmesh-d": ["--curvature-deviation", "0.001"]}
AFMESH_TOOLS = tuple(AFMESH_FLAGS)
TOOLS = AFMESH_TOOLS + ("cgal", "gmsh", "netgen")
DEFAULT_RIDGE_ANGLE = 30.0  # afmesh's default, and netgen's STL yangle (which it cannot be told)
SPHERE_AREA = 4.0 * math.pi
EQUILATERAL_AREA = math.sqrt(3.0) / 4.0  # of a triangle of edge 1

# Inputs: name -> (how it is made, h in the full run, h in --quick, title, whether the two h
# are shares of the input's bounding-box diagonal). Shapes are unit-sized; corpus files are
# closed, oriented, intersection-free (../shared/corpus/README.md): a smooth scan (bunny) and CAD
# parts with sharp edges.
INPUTS = {
    "cube": ("cube", 0.05, 0.1,
             "unit cube, 12 ridges and 8 corners, 40 x 40 squares halved per face", False),
    "sphere": ("sphere", 0.05, 0.1, "sphere r = 1, gmsh OCC at size 0.02", False),
    "torus": ("torus", 0.05, 0.1, "torus R = 1, r = 0.35, gmsh OCC at size 0.02", False),
    "scan": ("scan", 0.05, 0.1,
             "scan-like sphere r = 1: sizes 0.011 to 0.044 across x, radial noise sd 2e-4", False),
    "cgal_bunny00": ("corpus", 1 / 60, 1 / 25, "corpus: Stanford bunny scan", True),
    "netgen_part1": ("corpus", 1 / 40, 1 / 20, "corpus: CAD part", True),
    "netgen_hinge": ("corpus", 1 / 40, 1 / 20, "corpus: CAD hinge", True),
    "gmsh_lever": ("corpus", 1 / 40, 1 / 20, "corpus: CAD lever", True),
    "cgal_pinion": ("corpus", 1 / 40, 1 / 20, "corpus: gear pinion", True),
}
DEFAULT_INPUTS = ("cube", "sphere", "torus", "scan", "cgal_bunny00", "netgen_part1",
                  "netgen_hinge", "gmsh_lever", "cgal_pinion")
QUICK_INPUTS = ("cube", "sphere", "netgen_part1")
# The ~1M-triangle scan (1 027 214) re-triangulated at h = 0.012 (about 200k triangles on the unit sphere).
SCAN_900K = ("scan900k", 0.012,
             "scan-like sphere, ~1M triangles, sizes 0.0028 to 0.011 across x, noise sd 2e-4")
# A mean edge above this many h means the tool did not take the size asked (not comparable).
SIZE_NOT_TAKEN = 1.5
# --scaling: the sphere's input at h giving about these output triangle counts.
SCALING_COUNTS = (10_000, 30_000, 100_000, 300_000, 1_000_000)


def sphere_size_for(count):
    """h at which equilateral triangles of edge h tile the unit sphere `count` times."""
    return math.sqrt(SPHERE_AREA / (count * EQUILATERAL_AREA))


# ---------------------------------------------------------------------------------------------
# Inputs, written once into WORK/inputs as NAME.stl (binary: afmesh, CGAL, gmsh, the judge) and
# NAME.ascii.stl (netgen reads ASCII STL only) with the same float32 coordinates.

def write_stl(points, triangles, path, ascii_path):
    corners = points[triangles].astype(np.float32)  # M x 3 x 3
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1)[:, None]
    safe = np.where(lengths > 0, lengths, 1)
    normals = np.where(lengths > 0, normals / safe, 0).astype(np.float32)
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rows = np.zeros(len(triangles), dtype=record)
    rows["n"], rows["v"] = normals, corners
    with open(path, "wb") as f:
        f.write(b"afmesh bench/surface input".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        f.write(rows.tobytes())
    with open(ascii_path, "w") as f:
        f.write("solid input\n")
        for n, (a, b, c) in zip(normals.tolist(), corners.tolist()):
            f.write("facet normal %.9g %.9g %.9g\nouter loop\n" % tuple(n))
            f.write("vertex %.9g %.9g %.9g\nvertex %.9g %.9g %.9g\nvertex %.9g %.9g %.9g\n"
                    % (*a, *b, *c))
            f.write("endloop\nendfacet\n")
        f.write("endsolid input\n")


def make_cube(per_edge=40):
    """The unit cube, each face an n x n grid of squares split into two triangles, outward."""
    t = np.linspace(0.0, 1.0, per_edge + 1)
    u, v = np.meshgrid(t, t, indexing="ij")
    points, triangles = [], []
    for axis in range(3):
        for side in (0.0, 1.0):
            grid = np.zeros((per_edge + 1, per_edge + 1, 3))
            grid[..., axis] = side
            grid[..., (axis + 1) % 3], grid[..., (axis + 2) % 3] = u, v
            base = sum(len(p) for p in points)
            points.append(grid.reshape(-1, 3))
            idx = base + np.arange((per_edge + 1) ** 2).reshape(per_edge + 1, per_edge + 1)
            a, b, c, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
            quads = np.stack([a, b, c, d], axis=-1).reshape(-1, 4)
            tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
            # (axis+1, axis+2, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
            triangles.append(tris if side == 1.0 else tris[:, ::-1])
    points = np.concatenate(points)
    triangles = np.concatenate(triangles)
    # Merge the duplicated points along the cube's edges.
    unique, inverse = np.unique(np.round(points * per_edge).astype(np.int64), axis=0,
                                return_inverse=True)
    return unique.astype(np.float64) / per_edge, inverse.reshape(-1)[triangles]


def gmsh_shape(kind, size, size_field=None):
    """A gmsh OCC sphere (r = 1) or torus (R = 1, r = 0.35) meshed at `size` (or a MathEval size
    field), as points and 0-based triangles."""
    import gmsh
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        if kind == "torus":
            gmsh.model.occ.addTorus(0, 0, 0, 1.0, 0.35)
        else:
            gmsh.model.occ.addSphere(0, 0, 0, 1.0)
        gmsh.model.occ.synchronize()
        if size_field:
            field = gmsh.model.mesh.field.add("MathEval")
            gmsh.model.mesh.field.setString(field, "F", size_field)
            gmsh.model.mesh.field.setAsBackgroundMesh(field)
            for name in ("Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature",
                         "Mesh.MeshSizeExtendFromBoundary"):
                gmsh.option.setNumber(name, 0)
            gmsh.option.setNumber("Mesh.Algorithm", 5)
        else:
            gmsh.option.setNumber("Mesh.MeshSizeMin", size)
            gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(2)
        return gmsh_triangles(gmsh)
    finally:
        gmsh.finalize()


def gmsh_triangles(gmsh):
    """All triangles of the current gmsh model over the nodes they use: (points, triangles)."""
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    _, tri_nodes = gmsh.model.mesh.getElementsByType(2)
    index = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
    index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
    triangles = index[tri_nodes.astype(np.int64)].reshape(-1, 3)
    return compact(coords.reshape(-1, 3), triangles)


def compact(points, triangles):
    """Drops the points no triangle uses and renumbers the triangles."""
    used, inverse = np.unique(triangles, return_inverse=True)
    return np.asarray(points)[used], inverse.reshape(-1, 3)


def make_scan(smallest):
    """A scan-like sphere: element sizes from `smallest` at x = -1 to 4x that at x = 1, every
    point moved radially by Gaussian noise of standard deviation 2e-4 (fixed seed)."""
    points, triangles = gmsh_shape("sphere", None, f"{smallest!r} * (1 + 1.5 * (x + 1))")
    radial = 1.0 + np.random.default_rng(11).normal(0.0, 2e-4, len(points))
    return points * radial[:, None], triangles


def read_corpus(name):
    import meshio
    mesh = meshio.read(os.path.join(CORPUS_DIR, name + ".stl"))
    return np.asarray(mesh.points, dtype=np.float64), np.asarray(mesh.cells_dict["triangle"])


def make_input(name, work):
    """WORK/inputs/NAME.stl (and .ascii.stl), made once; returns (path, ascii path, triangles,
    bounding-box diagonal)."""
    folder = os.path.join(work, "inputs")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name + ".stl")
    ascii_path = os.path.join(folder, name + ".ascii.stl")
    if not (os.path.exists(path) and os.path.exists(ascii_path)):
        kind = INPUTS[name][0] if name in INPUTS else name
        if kind == "cube":
            points, triangles = make_cube()
        elif kind in ("sphere", "torus"):
            points, triangles = gmsh_shape(kind, 0.02)
        elif kind == "scan":
            points, triangles = make_scan(0.011)
        elif kind == "scan900k":
            points, triangles = make_scan(0.00284)
        else:
            points, triangles = read_corpus(name)
        write_stl(points, triangles, path + ".tmp", ascii_path + ".tmp")
        os.replace(ascii_path + ".tmp", ascii_path)
        os.replace(path + ".tmp", path)
    with open(path, "rb") as f:
        f.seek(80)
        count = struct.unpack("<I", f.read(4))[0]
        rows = np.frombuffer(f.read(50 * count), dtype=np.dtype(
            [("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    corners = rows["v"].reshape(-1, 3).astype(np.float64)
    diag = float(np.linalg.norm(corners.max(0) - corners.min(0)))
    return path, ascii_path, count, diag


# ---------------------------------------------------------------------------------------------
# The peers run inside a child of this script (gmsh, netgen) or as their own program (CGAL).

def write_obj(points, triangles, path):
    with open(path, "w") as f:
        f.write("".join("v %r %r %r\n" % tuple(p) for p in np.asarray(points).tolist()))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in (np.asarray(triangles) + 1).tolist()))


def gmsh_remesh(job):
    """gmsh as /work/shared/peers.md says: classifySurfaces(A, True, True, pi), createGeometry,
    Mesh.MeshSizeMin = Max = h, no curvature sizes, Algorithm 6 (Frontal-Delaunay), generate(2)."""
    import gmsh
    gmsh.initialize([], False)
    try:
        for name, value in (("General.Terminal", 1), ("General.Verbosity", 2),
                            ("General.NumThreads", 1), ("Mesh.MeshSizeMin", job["size"]),
                            ("Mesh.MeshSizeMax", job["size"]), ("Mesh.MeshSizeFromCurvature", 0),
                            ("Mesh.Algorithm", 6)):
            gmsh.option.setNumber(name, value)
        gmsh.merge(job["input"])
        probe = peers.PeakMemoryProbe()
        probe.start()
        with peers.PhaseClock() as clock:
            gmsh.model.mesh.classifySurfaces(math.radians(job["ridge_angle"]), True, True, math.pi)
            gmsh.model.mesh.createGeometry()
            gmsh.model.mesh.generate(2)
        probe.finish()
        points, triangles = gmsh_triangles(gmsh)
    finally:
        gmsh.finalize()
    return clock, probe, points, triangles, (
        f"classifySurfaces({job['ridge_angle']:g} deg, True, True, pi) + createGeometry, "
        f"MeshSizeMin = Max = {job['size']:g}, Algorithm 6")


def netgen_remesh(job):
    """netgen's STL mesher: LoadSTLGeometry (ASCII) then GenerateMesh(MeshingParameters(maxh=h,
    perfstepsend=MESHSURFACE)); its ridge angle is its default yangle (30 degrees)."""
    from netgen.meshing import MeshingParameters, MeshingStep
    from netgen.stl import LoadSTLGeometry
    geometry = LoadSTLGeometry(job["ascii_input"])
    parameters = MeshingParameters(maxh=job["size"], perfstepsend=MeshingStep.MESHSURFACE)
    probe = peers.PeakMemoryProbe()
    probe.start()
    with peers.PhaseClock() as clock:
        mesh = geometry.GenerateMesh(mp=parameters)
    probe.finish()
    points = np.array([p.p for p in mesh.Points()], dtype=np.float64)
    triangles = np.array([[v.nr - 1 for v in e.vertices] for e in mesh.Elements2D()],
                         dtype=np.int64).reshape(-1, 3)
    points, triangles = compact(points, triangles)
    return clock, probe, points, triangles, f"maxh={job['size']:g}, yangle 30 (default)"


def run_child(job, result_path):
    """In the child: remeshes with job["tool"], writes the output and its figures (JSON)."""
    clock, probe, points, triangles, options = (gmsh_remesh if job["tool"] == "gmsh"
                                                else netgen_remesh)(job)
    write_obj(points, triangles, job["output"])
    figures = {"seconds": clock.seconds, "cpu_seconds": clock.cpu_seconds,
               "triangles": len(triangles), "points": len(points), "options": options}
    figures.update(probe.figures(len(triangles)))
    with open(result_path, "w") as f:
        json.dump(figures, f)


# ---------------------------------------------------------------------------------------------
# Running one tool on one case.

def timed(command, timeout, workdir):
    """Runs `command` under /usr/bin/time in its own session (killed with its children on
    timeout). Returns (status or None, stdout, stderr, wall seconds, peak RSS bytes or None,
    CPU seconds (user + system) or None)."""
    usage = os.path.join(workdir, "usage.txt")
    if os.path.exists(usage):
        os.remove(usage)
    status, out, err, wall = run_bench.run_process(
        ["/usr/bin/time", "-f", "usage %M %U %S", "-o", usage, *command], timeout)
    peak = cpu = None
    if os.path.exists(usage):
        with open(usage) as f:
            rows = [line.split() for line in f if line.startswith("usage ")]
        if rows:
            peak, cpu = int(rows[-1][1]) * 1024, float(rows[-1][2]) + float(rows[-1][3])
    return status, out, err, wall, peak, cpu


def failure(status, out, err, timeout):
    if status is None:
        return f"timed out after {timeout:g} s (killed)"
    if status == 0:
        return "exit status 0 but no output file"
    lines = [l.strip() for l in (err + "\n" + out).splitlines()
             if l.strip() and not l.startswith("Command exited") and not set(l.strip()) <= set(".")]
    problem = peers.first_problem_line("\n".join(lines))
    tail = problem or (" | ".join(lines[:2]) if lines else "no message")
    return f"{peers.exit_status_text(status)}: {tail}"


def run_tool(args, tool, case, workdir):
    """Figures of one tool on one case (a dict; "error" when it failed)."""
    output = os.path.join(workdir, f"{case['name']}-{case['label']}-{tool}.obj")
    if os.path.exists(output):
        os.remove(output)
    h, angle = case["size"], args.ridge_angle
    if tool in AFMESH_TOOLS:
        command = [args.afmesh, "surface", case["input"], "-o", output, "--size", repr(h),
                   "--ridge-angle", repr(angle), "--quiet"]
        command += AFMESH_FLAGS[tool]
    elif tool == "cgal":
        if not args.cgal_binary:
            return {"error": f"not measured: {args.cgal_missing}"}
        command = [args.cgal_binary, "remesh", case["input"], output, "--size", repr(h),
                   "--ridge-angle", repr(angle)]
    else:
        job = {"tool": tool, "input": case["input"], "ascii_input": case["ascii_input"],
               "output": output, "size": h, "ridge_angle": angle}
        command = [sys.executable, os.path.abspath(__file__), "_child", json.dumps(job),
                   os.path.join(workdir, "result.json")]
    if tool in AFMESH_TOOLS and not os.access(args.afmesh, os.X_OK):
        return {"error": f"not run: {args.afmesh} is not an executable (build afmesh first)"}
    result_path = os.path.join(workdir, "result.json")
    if os.path.exists(result_path):
        os.remove(result_path)
    status, out, err, wall, peak, cpu = timed(command, args.timeout, workdir)
    if status != 0 or not os.path.exists(output):
        return {"error": failure(status, out, err, args.timeout), "process_seconds": wall}
    figures = {"process_seconds": wall, "process_cpu_seconds": cpu,
               "process_peak_rss_bytes": peak}
    if tool == "cgal":
        figures.update(json.loads(next(l for l in out.splitlines() if l.startswith("{"))))
    elif tool in ("gmsh", "netgen"):
        with open(result_path) as f:
            figures.update(json.load(f))
    else:  # afmesh: its phases are not exposed; the whole command stands for them
        figures.update({"seconds": wall, "cpu_seconds": cpu, "seconds_whole_process": True,
                        "options": " ".join([f"--size {h:g} --ridge-angle {angle:g}"]
                                            + AFMESH_FLAGS[tool])})
    figures["output"] = output
    return figures


def judge(args, case, figures):
    """Adds the measure mode's figures of the tool's output against the input."""
    if "error" in figures or not args.cgal_binary:
        return
    status, out, err, _ = run_bench.run_process(
        [args.cgal_binary, "measure", case["input"], figures["output"], "--size",
         repr(case["size"]), "--ridge-angle", repr(args.ridge_angle)], args.timeout)
    line = next((l for l in (out or "").splitlines() if l.startswith("{")), None)
    if status != 0 or line is None:
        figures["measure_error"] = failure(status, out or "", err or "", args.timeout)
        return
    measured = json.loads(line)
    reported = figures.get("triangles")
    figures.update(measured)
    if reported is not None and reported != measured["triangles"]:
        figures["triangles_reported"] = reported


def derived(figures):
    """tris/s (phase and whole process) and bytes per triangle."""
    tris = figures.get("triangles") or 0
    if not tris or "error" in figures:
        return
    figures["triangles_per_second"] = tris / figures["seconds"] if figures.get("seconds") else None
    figures["triangles_per_process_second"] = tris / figures["process_seconds"]
    if figures.get("seconds_whole_process"):
        peak = figures.get("process_peak_rss_bytes")
        figures["bytes_per_triangle"] = peak / tris if peak else None
    elif "rss_peak_bytes" in figures:
        phase_bytes = figures["rss_peak_bytes"] - figures["rss_before_bytes"]
        figures["bytes_per_triangle"] = phase_bytes / tris


# ---------------------------------------------------------------------------------------------
# Printing.

COLUMNS = (("tool", 8, "s"), ("tris", 9, "d"), ("phase s", 9, ".3f"), ("tris/s", 9, ".0f"),
           ("proc s", 8, ".2f"), ("cpu s", 7, ".2f"), ("min", 6, ".1f"), ("%>=30", 7, ".2f"),
           ("<15", 6, "d"),
           ("H/diag%", 8, ".4f"), ("ridge%", 7, ".1f"), ("corners", 8, "s"), ("edge/h", 7, ".3f"),
           ("B/tri", 7, ".0f"))


def row_cells(row):
    pct = lambda v: None if v is None else 100.0 * v
    star = "*" if row.get("seconds_whole_process") else ""
    corners = (f"{row['corners_kept']}/{row['corners']}" if row.get("corners") else "-")
    cells = [row["tool"], row.get("triangles"), row.get("seconds"),
             row.get("triangles_per_second"), row.get("process_seconds"),
             row.get("process_cpu_seconds"), row.get("min_angle"),
             pct(row.get("share_min_angle_ge_30")), row.get("count_min_angle_lt_15"),
             pct(row.get("hausdorff_over_diag")),
             pct(row.get("ridge_length_kept")) if row.get("ridge_edges") else None, corners,
             row.get("mean_edge_over_h"), row.get("bytes_per_triangle")]
    text = [run_bench._cell(v, w, s) for v, (_, w, s) in zip(cells, COLUMNS)]
    if star:
        text[2], text[-1] = text[2] + "*", text[-1] + "*"
    return " ".join(text)


def print_case(case, rows):
    print(f"\n{case['name']} [{case['label']}]: {case['title']}; input {case['input_triangles']} "
          f"triangles, diag {case['diag']:.4g}, h = {case['size']:.5g}, ridge angle "
          f"{case['ridge_angle']:g} deg")
    print("   " + " ".join(name.ljust(w) if i == 0 else name.rjust(w)
                           for i, (name, w, _) in enumerate(COLUMNS)))
    for row in rows:
        if "error" in row:
            print(f"   {row['tool']:8s} {row['error']}")
            continue
        print("   " + row_cells(row))
        if "measure_error" in row:
            print(f"   {'':8s} not judged: {row['measure_error']}")
        if (row.get("mean_edge_over_h") or 0) > SIZE_NOT_TAKEN:
            print(f"   {'':8s} ^ mean edge {row['mean_edge_over_h']:.2f} h: the size asked was not "
                  "taken (netgen's STL mesher ignores maxh from Python, README.md)")
    for name in AFMESH_TOOLS:
        if any(row["tool"] == name for row in rows):
            print_ratios(name, rows)


def print_ratios(name, rows):
    """The ratio line of afmesh variant `name` against each peer's row."""
    ours = next((r for r in rows if r["tool"] == name and "error" not in r), None)
    ratios = []
    for row in rows:
        if row["tool"] in AFMESH_TOOLS or "error" in row or ours is None:
            continue
        speed = ours["triangles_per_process_second"] / row["triangles_per_process_second"]
        cpu = (row["process_cpu_seconds"] / row["triangles"]
               / (ours["process_cpu_seconds"] / ours["triangles"])
               if ours.get("process_cpu_seconds") and row.get("process_cpu_seconds") else None)
        memory = (ours["bytes_per_triangle"] / row["bytes_per_triangle"]
                  if ours.get("bytes_per_triangle") and row.get("bytes_per_triangle") else None)
        ratios.append(f"{row['tool']} {speed:.2f}x tris/s (wall), "
                      f"{run_bench._cell(cpu, 0, '.2f')}x tris per cpu s, "
                      f"{run_bench._cell(memory, 0, '.2f')}x B/tri")
    if ours is None:
        print(f"   {name} / peer: not yet ({name} gave no output)")
    elif ratios:
        print(f"   {name} / peer (whole processes): " + "; ".join(ratios))


# ---------------------------------------------------------------------------------------------
# The cases and the CGAL driver.

def cgal_binary(build_dir):
    """The compiled driver (built with g++ when missing or older than its source), or
    (None, reason)."""
    binary = os.path.join(build_dir, "bench", "surface", "cgal_remesh")
    if os.path.exists(binary) and os.path.getmtime(binary) >= os.path.getmtime(CGAL_SOURCE):
        return binary, None
    if not os.path.exists("/usr/include/CGAL/version.h"):
        return None, "libcgal-dev is not installed (scripts/install-deps.sh --peers)"
    os.makedirs(os.path.dirname(binary), exist_ok=True)
    print(f"compiling {binary} (once, about a minute) ...", file=sys.stderr, flush=True)
    done = subprocess.run(["g++", "-std=c++17", "-O2", "-DNDEBUG", "-DCGAL_NDEBUG", "-o",
                           binary + ".tmp", CGAL_SOURCE, "-lgmp", "-lmpfr"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        return None, "cgal_remesh.cc did not compile: " + done.stderr.strip()[-300:]
    os.replace(binary + ".tmp", binary)
    return binary, None


def cases(args):
    """(name, label, h, title) of every case of this run."""
    chosen = []
    names = (args.inputs.split(",") if args.inputs
             else QUICK_INPUTS if args.quick else DEFAULT_INPUTS)
    for name in names:
        if name not in INPUTS:
            sys.exit(f"run_surface_bench.py: unknown input '{name}'; known: {', '.join(INPUTS)}")
        chosen.append((name, "quick" if args.quick else "equal h",
                       INPUTS[name][2 if args.quick else 1], INPUTS[name][3], INPUTS[name][4]))
    if args.scan:
        chosen.append((SCAN_900K[0], "~200k", SCAN_900K[1], SCAN_900K[2], False))
    if args.scaling:
        for count in SCALING_COUNTS:
            chosen.append(("sphere", f"~{count // 1000}k", sphere_size_for(count),
                           INPUTS["sphere"][3], False))
    return chosen


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--afmesh", default=os.path.join(REPO_DIR, "build", "release", "client",
                                                         "afmesh"), help="the afmesh CLI")
    parser.add_argument("--build-dir", default=os.path.join(REPO_DIR, "build", "release"),
                        help="where the CGAL driver is compiled to (bench/surface/cgal_remesh)")
    parser.add_argument("--work-dir", default=os.path.join(REPO_DIR, "build", "surface-bench"),
                        help="inputs (made once) and every tool's output")
    parser.add_argument("--inputs", help="comma-separated, of " + ",".join(INPUTS))
    parser.add_argument("--tools", default=",".join(TOOLS), help="comma-separated, of "
                        + ",".join(TOOLS))
    parser.add_argument("--size", action="append", default=[], metavar="NAME=H",
                        help="h for an input instead of its share of the diagonal (repeatable)")
    parser.add_argument("--ridge-angle", type=float, default=DEFAULT_RIDGE_ANGLE,
                        help="degrees between face normals that make a ridge (netgen keeps 30)")
    parser.add_argument("--timeout", type=float, help="seconds per run (default 600, --quick 30)")
    parser.add_argument("--quick", action="store_true",
                        help="cube, sphere and netgen_part1 at coarse sizes: under 2 minutes")
    parser.add_argument("--scaling", action="store_true",
                        help="also the sphere at h for ~10k, 30k, 100k, 300k and 1M triangles")
    parser.add_argument("--scan", action="store_true",
                        help="also the ~1M-triangle scan at h for ~200k triangles")
    parser.add_argument("--only-extra", action="store_true",
                        help="with --scaling / --scan: only those cases")
    parser.add_argument("--json", action="store_true", help="also one JSON object per run")
    args = parser.parse_args(argv)
    if args.timeout is None:
        args.timeout = 30.0 if args.quick else 600.0
    args.sizes = {}
    for override in args.size:
        name, h = override.split("=")
        args.sizes[name] = float(h)
    return args


def main(argv):
    if len(argv) == 3 and argv[0] == "_child":
        run_child(json.loads(argv[1]), argv[2])
        return 0
    args = parse_arguments(argv)
    tools = args.tools.split(",")
    for tool in tools:
        if tool not in TOOLS:
            sys.exit(f"run_surface_bench.py: unknown tool '{tool}'; known: {', '.join(TOOLS)}")
    os.environ["OMP_NUM_THREADS"] = "1"
    args.cgal_binary, args.cgal_missing = cgal_binary(args.build_dir)
    work = os.path.abspath(args.work_dir)
    print(run_bench.machine_line())
    print(run_bench.load_line())
    print(run_bench.source_line() + f"; afmesh binary {args.afmesh}")
    if not args.cgal_binary:
        print(f"CGAL: {args.cgal_missing}; outputs are not judged")
    workdir = tempfile.mkdtemp(prefix="afmesh-surface-bench-")
    try:
        for name, label, share_or_h, title, relative in cases(args):
            if args.only_extra and label in ("quick", "equal h"):
                continue
            path, ascii_path, count, diag = make_input(name, work)
            h = args.sizes.get(name, share_or_h * diag if relative else share_or_h)
            case = {"name": name, "label": label, "title": title, "input": path,
                    "ascii_input": ascii_path, "input_triangles": count, "diag": diag,
                    "size": h, "ridge_angle": args.ridge_angle}
            outputs = os.path.join(work, "outputs")
            os.makedirs(outputs, exist_ok=True)
            rows = []
            for tool in tools:
                figures = run_tool(args, tool, case, workdir)
                judge(args, case, figures)
                derived(figures)
                figures["tool"] = tool
                if "output" in figures:
                    kept = os.path.join(outputs, os.path.basename(figures["output"]))
                    shutil.move(figures["output"], kept)
                    figures["output"] = kept
                rows.append(figures)
                if args.json:
                    print(json.dumps({"input": name, "case": label, "size": h,
                                      "ridge_angle": args.ridge_angle,
                                      "input_triangles": count, **figures}), flush=True)
            print_case(case, rows)
            sys.stdout.flush()
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
