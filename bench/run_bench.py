#!/usr/bin/python3
"""The benchmark tables: afmesh's volume mesher against gmsh (Delaunay, HXT), netgen and tetgen on
the same surfaces, core/io converting a ~1M-triangle STL against gmsh, and the size field's
evaluations per second with 1 to 1000 sources (afmesh alone: the peers have no source fields),
and the thin examples (THIN_INPUTS: crossing surfaces with environment tags) given to afmesh and
to each peer as they are, side by side. Run by scripts/bench.sh.

Every measurement is a fresh process, run one after the other (never in parallel): afmesh by
afmesh-bench-volume / afmesh-bench-io, the peers by bench/peers.py. Each case first runs afmesh,
which writes the surface the peers then mesh.

Columns: tets; time = wall seconds of the volume phase (cpu = its CPU seconds: on a loaded
machine wall > cpu); tets/s = tets / wall seconds; bytes/tet = (peak resident memory during the
phase - resident before) / tets; min dihedral (degrees), shares of tets with min dihedral under 10
and 20 degrees, min and mean radius ratio (3 r_in / r_circ); edge/h = mean length of the interior
edges (tet edges that are no edge of a boundary triangle) / h, the size asked of that tool, and
%e in band = the share of them in [0.7 h, 1.4 h] (peers.edge_length_summary measures every
tool's mesh, afmesh's written out as Medit); afmesh/peer = afmesh's tets/s (or bytes/tet) over the
peer's, so > 1 means afmesh is faster (or uses more memory per tet). The peers are asked h as
gmsh Mesh.MeshSizeMax (not extended from the boundary), netgen maxh and tetgen -a 0.34 h^3; at
the same h they give from about 0.4x to 1.2x afmesh's count, hence:

Equal counts (--equal-count, in the full run at --count-targets 50k; --equal-count-only; e.g.
--count-targets 50k,500k,2M): for each shape and target N, afmesh's h is found first (its
surface changes with h), then on that surface each peer's size, each by secant / regula falsi
steps on log(size) against log(tets) (count ~ size^-3) until the count is within
--count-tolerance (10%) of N, in at most --count-max-runs (6) runs of at most --count-timeout
(900 s) each. Per tool: what it was asked, the runs it took, tets, how far from N ("!": not
within the tolerance after all runs, the closest run shown), the volume phase's seconds, tets/s,
bytes/tet, min dihedral, %<20°, edge/h, %e in band and the afmesh/peer ratios at those counts. A
tool that fails or times out says so, with its error, instead of a row.

Thin inputs (--thin, in the full run; --thin-only): each of THIN_INPUTS, and of THIN_GENERATED
(written by make-thin-examples into the work directory), goes as it is to afmesh
(`afmesh volume IN -o OUT.msh --spec SIZES --envs tags`, then `--envs auto`) and to every peer.
Per tool: outcome (valid / INVALID with the failing checks / FAILED or CRASHED with exit status,
or TIMED OUT; the reason line below the table: the exception or error, and the first log line
that names a problem), tets, min dihedral, share under 20 degrees, gap tets (tets joining two
different positive environments, by `afmesh stats --envs tags` for afmesh's meshes and by
tools/check_volume.py --envs for every mesh) and the wall seconds of the whole process. A peer
whose run gives no tets is reported as "surface only".
"""

import argparse
import datetime
import json
import math
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import time

import peers  # bench/peers.py: the peers' driving, error lines and the Medit reader

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(BENCH_DIR)
PEERS = ("gmsh-delaunay", "gmsh-hxt", "netgen", "tetgen")
TARGETS = ("50k", "500k", "2M")
TARGET_TETS = {"50k": 50_000, "500k": 500_000, "2M": 2_000_000}

# Target edge length h for about 50k, 500k and 2M tets with afmesh, found by trying at commit
# fbb6c09. The surfaces change in steps (the sphere's icosahedron edge 1.0515 is split into
# round(1.0515 / h) parts; the torus into round(2 pi / h) by round(0.7 pi / h) quads), and some
# steps made that mesher fail with "the front did not close": sphere h = 0.047-0.048 and every
# h tried from 0.0284 to 0.0329 (1.6M-2.6M tets), torus h = 0.024, 0.025, 0.038 and 0.040. Where a
# neighbouring h meshed it is used (torus 2M: h = 0.026 gives 1.46M tets); sphere 2M stays at
# 0.030 and shows the failure beside the peers.
SIZES = {
    "sphere": {"50k": 0.1, "500k": 0.05, "2M": 0.030},
    "torus": {"50k": 0.08, "500k": 0.039, "2M": 0.026},
    # found at commit 76bd97b; no 2M size tried yet
    "box": {"50k": 0.057, "500k": 0.0265},
    "lblock": {"50k": 0.07, "500k": 0.0325},
}
# The thin (crossing) inputs of --thin: name, surface (Medit, triangle refs = crossing
# environments), size specification (JSON, design.md), title. One line per input.
THIN_INPUTS = (
    ("dome", "examples/dome/dome.mesh", "examples/dome/dome-sizes.json",
     "quarter dome, shell 1/1000 of the radius thick (paper §5 (a))"),
    ("sails", "examples/sails/sails.mesh", "examples/sails/sails-sizes.json",
     "two sails 1 mm thick in a 70 m box (paper §5 (b))"),
    ("crossing", "examples/crossing/crossing.mesh", "examples/crossing/crossing-sizes.json",
     "an X of two plates 1/1000 thick crossing each other (paper §2, Figures 3 and 4)"),
)
# Thin inputs written by make-thin-examples (core/shapes/thin_shapes.h) into the work directory
# before they are run like THIN_INPUTS: name, its arguments, size specification, title.
THIN_GENERATED = (
    ("shell", ["--shell", "0.001", "20", "22"], "examples/dome/dome-sizes.json",
     "whole hemispherical shell 1/1000 of the radius thick, sides in rings of 20 and 22 steps "
     "(issue 10)"),
    ("strip-plates", ["--plates", "60", "0.001", "0.02", "4", "1"],
     "examples/crossing/crossing-sizes.json",
     "two plates 1/1000 thick crossing at ±30°, rims closed by strips of tag 0 (issue 10)"),
)
# What meshes a thin input: afmesh with each --envs mode, then the peers (tetgen three ways: the
# benchmark's -pYq1.2 -a, plain -p, and -d which only counts intersecting face pairs).
THIN_AFMESH_ENVS = ("tags", "auto")
THIN_PEERS = ("gmsh-delaunay", "gmsh-hxt", "netgen", "tetgen", "tetgen-p", "tetgen-d")
SHAPE_TITLES = {"sphere": "sphere, radius 1", "torus": "torus, R = 1, r = 0.35",
                "box": "unit cube", "lblock": "L-block with a square hole, voxels 0.5"}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default=os.path.join(REPO_DIR, "build", "release"),
                        help="build directory holding bench/afmesh-bench-volume and -io")
    parser.add_argument("--work-dir", default=os.path.join(REPO_DIR, "build", "bench-work"),
                        help="where surfaces, meshes and results.json go")
    parser.add_argument("--shapes", default="sphere,torus")
    parser.add_argument("--targets", default=",".join(TARGETS), help="of " + ",".join(TARGETS))
    parser.add_argument("--size", action="append", default=[], metavar="SHAPE:TARGET=H",
                        help="override an h, e.g. sphere:2M=0.031 (repeatable)")
    parser.add_argument("--tools", default="afmesh," + ",".join(PEERS))
    parser.add_argument("--skip", action="append", default=[], metavar="TOOL@TARGET",
                        help="skip one tool at one target, e.g. netgen@2M (repeatable)")
    parser.add_argument("--netgen-max-target", default="2M", choices=TARGETS,
                        help="skip netgen above this target (netgen at 2M tets takes tens of minutes)")
    parser.add_argument("--peer-timeout", type=float, default=1800.0,
                        help="seconds before a peer run is killed and reported as timed out")
    parser.add_argument("--no-before-optimise", action="store_true",
                        help="leave out the afmesh row without its optimisation step")
    parser.add_argument("--equal-count", dest="equal_count", action="store_true", default=True)
    parser.add_argument("--no-equal-count", dest="equal_count", action="store_false",
                        help="skip the equal-count comparison")
    parser.add_argument("--equal-count-only", action="store_true",
                        help="only the equal-count comparison: each tool's size adjusted until "
                             "its tet count is within --count-tolerance of each --count-targets")
    parser.add_argument("--count-targets", default="50k",
                        help="tet counts for the equal-count comparison, comma-separated, e.g. "
                             "50k,500k,2M (default 50k: a few minutes)")
    parser.add_argument("--count-tolerance", type=float, default=0.10,
                        help="relative distance of a count to its target that is equal enough")
    parser.add_argument("--count-max-runs", type=int, default=6,
                        help="meshings per tool and target to find its size")
    parser.add_argument("--count-timeout", type=float, default=900.0,
                        help="seconds before one run of the equal-count search is killed")
    parser.add_argument("--io", dest="io", action="store_true", default=True)
    parser.add_argument("--no-io", dest="io", action="store_false", help="skip the io benchmark")
    parser.add_argument("--io-only", action="store_true", help="only the io benchmark")
    parser.add_argument("--sizing", dest="sizing", action="store_true", default=True)
    parser.add_argument("--no-sizing", dest="sizing", action="store_false",
                        help="skip the size-field throughput benchmark")
    parser.add_argument("--sizing-only", action="store_true",
                        help="only the size-field throughput benchmark")
    parser.add_argument("--thin", dest="thin", action="store_true", default=True)
    parser.add_argument("--no-thin", dest="thin", action="store_false",
                        help="skip the thin (crossing) inputs")
    parser.add_argument("--thin-only", action="store_true",
                        help="only the thin inputs: afmesh and every peer on examples/dome, "
                             "examples/sails, examples/crossing and THIN_GENERATED")
    parser.add_argument("--thin-timeout", type=float, default=300.0,
                        help="seconds before one run on a thin input is killed (timed out)")
    args = parser.parse_args(argv)
    for override in args.size:
        key, h = override.split("=")
        shape, target = key.split(":")
        SIZES.setdefault(shape, {})[target] = float(h)
    return args


# ---------------------------------------------------------------------------------------------
# Running the measurements.

def machine_line():
    model = "unknown cpu"
    with open("/proc/cpuinfo") as cpuinfo:
        for line in cpuinfo:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return f"{platform.node()}: {model}, {os.cpu_count()} cores, Linux {platform.release()}"


def load_line():
    with open("/proc/loadavg") as f:
        one, five, fifteen = f.read().split()[:3]
    return f"load average {one}, {five}, {fifteen} (1, 5, 15 min) on {os.cpu_count()} cores"


def source_line():
    def git(*args):
        return subprocess.run(["git", "-C", REPO_DIR, *args], capture_output=True,
                              text=True).stdout.strip()
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    dirty = " + uncommitted changes" if git("status", "--porcelain", "--untracked-files=no") else ""
    return f"afmesh at commit {commit}{dirty}"


def run_json_lines(command, timeout=None):
    """Runs `command`, returning the JSON objects it printed one per line, or [{"error": ...}]."""
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return [{"error": f"timed out after {timeout:.0f} s (killed)", "timed_out": True}]
    results = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    if not results:
        tail = " | ".join((done.stderr or done.stdout).strip().splitlines()[-3:])
        return [{"error": f"exit status {done.returncode}: {tail}"}]
    return results


def measure_edges(figures, mesh_path, h):
    """Adds the interior edge figures of the Medit mesh at mesh_path (peers.edge_length_summary,
    the code that measures the peers' meshes) to figures, then deletes the file."""
    try:
        if "error" not in figures and os.path.exists(mesh_path):
            points, _, tets = peers.read_medit(mesh_path)
            figures.update(peers.edge_length_summary(points, tets, h))
    finally:
        if os.path.exists(mesh_path):
            os.remove(mesh_path)
    return figures


def run_afmesh(args, shape, h, prefix, optimise, timeout=None):
    """afmesh-bench-volume on SHAPE at h (with optimise: writing the surface to PREFIX.* for the
    peers), its mesh written to PREFIX-afmesh.mesh for measure_edges."""
    mesh_path = f"{prefix}-afmesh{'' if optimise else '-noopt'}.mesh"
    command = [os.path.join(args.build_dir, "bench", "afmesh-bench-volume"), "--shape", shape,
               "--size", repr(h), "--json", "--out", mesh_path]
    if optimise:
        command += ["--surface", prefix]
    else:
        command += ["--no-optimise"]
    figures = run_json_lines(command, timeout or args.peer_timeout)[0]
    figures["tool"] = "afmesh" if optimise else "afmesh no-opt"
    figures.setdefault("size", h)
    return measure_edges(figures, mesh_path, h)


def run_peer(args, tool, h, prefix, timeout=None):
    timeout = timeout or args.peer_timeout
    command = ["/usr/bin/python3", os.path.join(BENCH_DIR, "peers.py"), "volume", "--surface",
               prefix, "--size", repr(h), "--tools", tool, "--timeout", repr(timeout), "--json"]
    # peers.py kills its child at `timeout`; the margin covers its start-up and the surface read
    figures = run_json_lines(command, timeout + 120)[0]
    figures["tool"] = tool
    figures.setdefault("size", h)
    return figures


def skip_reason(args, tool, target):
    if f"{tool}@{target}" in args.skip:
        return f"skipped by --skip {tool}@{target}"
    if tool == "netgen" and TARGETS.index(target) > TARGETS.index(args.netgen_max_target):
        return f"skipped: --netgen-max-target {args.netgen_max_target} (netgen at {target} tets " \
               f"takes tens of minutes)"
    return None


def run_case(args, tools, shape, target):
    h = SIZES.get(shape, {}).get(target)
    if h is None:
        print(f"\n== {shape}: no size for target {target}; give one with --size {shape}:{target}=H ==")
        return [{"tool": "afmesh", "error": f"no size for {shape} at {target}"}]
    prefix = os.path.join(args.work_dir, f"{shape}-{target}")
    print(f"\n== {SHAPE_TITLES.get(shape, shape)}: target ~{target} tets (afmesh), h = {h:g} ==",
          flush=True)
    print(f"   start: {load_line()}", flush=True)
    rows = [run_afmesh(args, shape, h, prefix, optimise=True)]
    if "surface_points" not in rows[0]:  # no surface written: nothing for the peers to mesh
        print_table(rows)
        return rows
    if not args.no_before_optimise:
        rows.append(run_afmesh(args, shape, h, prefix, optimise=False))
    for tool in tools:
        if tool == "afmesh":
            continue
        reason = skip_reason(args, tool, target)
        rows.append({"tool": tool, "skipped": reason} if reason else run_peer(args, tool, h, prefix))
    print(f"   surface {rows[0]['surface_points']} points, {rows[0]['surface_triangles']} "
          f"triangles; end: {load_line()}")
    print_table(rows)
    return rows


def run_io(args):
    print("\n== io: sphere surface, ~1M triangles, binary STL -> MSH 4.1 (ascii) ==", flush=True)
    print(f"   start: {load_line()}", flush=True)
    ours = run_json_lines([os.path.join(args.build_dir, "bench", "afmesh-bench-io"), "--dir",
                           args.work_dir, "--json"])[0]
    stl = os.path.join(args.work_dir, "io_sphere.stl")
    gmsh = run_json_lines(["/usr/bin/python3", os.path.join(BENCH_DIR, "peers.py"), "io",
                           "--stl", stl, "--out", os.path.join(args.work_dir, "io_sphere_gmsh.msh"),
                           "--timeout", repr(args.peer_timeout), "--json"])[0]
    ours.setdefault("tool", "afmesh")
    gmsh.setdefault("tool", "gmsh")
    print_io_table([ours, gmsh])
    return [ours, gmsh]


def run_sizing(args):
    print("\n== size field: evaluations per second with 1 to 1000 sources, pruning off / on ==",
          flush=True)
    print(f"   start: {load_line()}", flush=True)
    rows = run_json_lines([os.path.join(args.build_dir, "bench", "afmesh-bench-sizing"), "--json"])
    print_sizing_table(rows)
    return rows


# ---------------------------------------------------------------------------------------------
# Thin inputs: afmesh through its CLI, the peers through bench/peers.py, every volume mesh checked
# by afmesh stats (afmesh's own meshes) and by the independent tools/check_volume.py (all).

CHECK_VOLUME = os.environ.get("AFMESH_CHECK_VOLUME") or os.path.join(
    REPO_DIR, "..", "shared", "tools", "check_volume.py")


def run_process(command, timeout, cwd=None):
    """Runs `command` in its own session (on timeout the whole group is killed: afmesh's private
    server too). Returns (exit status or None on timeout, stdout, stderr, wall seconds)."""
    started = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             cwd=cwd, start_new_session=True)
    try:
        out, err = child.communicate(timeout=timeout)
        status = child.returncode
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)
        out, err = child.communicate()
        status = None
    return status, out, err, time.perf_counter() - started


def check_volume(mesh, surface):
    """tools/check_volume.py MESH SURFACE --envs: {"pass", "gap_tets", "failed" (check names)}
    or {"error"}."""
    status, out, err, _ = run_process(["/usr/bin/python3", CHECK_VOLUME, mesh, surface, "--envs",
                                       "--json"], timeout=600)
    line = next((l for l in out.splitlines() if l.startswith("{")), None)
    if line is None:
        tail = " | ".join((err or out).strip().splitlines()[-2:])
        return {"error": f"check_volume.py: {peers.exit_status_text(status or 0)}: {tail}"}
    result = json.loads(line)
    failed = [k for k in ("positive", "conform", "boundary", "volume", "envs")
              if k in result and not result[k]["pass"]]
    return {"pass": result["pass"], "gap_tets": result.get("envs", {}).get("tets_joining_two_envs"),
            "failed": failed, "figures": result}


def afmesh_stats(afmesh, mesh):
    """afmesh stats --envs tags --json: {"valid", "gap_tets", "failed" (check names)} or
    {"error"}."""
    status, out, err, _ = run_process([afmesh, "stats", "--envs", "tags", "--json", mesh], 600)
    try:
        report = json.loads(out)
    except json.JSONDecodeError:
        return {"error": f"afmesh stats: {peers.exit_status_text(status or 0)}: "
                         f"{peers.first_problem_line(err) or err.strip()[-200:]}"}
    checks = report["validation"]["checks"]
    gap = next((c for c in checks if c["name"] == "environment_gap"), None)
    return {"valid": report["validation"]["valid"],
            "gap_tets": None if gap is None or gap["outcome"] == "not run"
            else gap["finding_count"],
            "failed": [c["name"] for c in checks if c["outcome"] == "failed"]}


def run_thin_afmesh(args, surface, spec, envs, work):
    """afmesh volume SURFACE -o OUT.msh --spec SPEC --envs ENVS (a private server), then its mesh
    through afmesh stats and, converted to Medit (meshio 5.0 rejects an MSH 4.1 file whose entities
    carry physical tags only in part), through check_volume.py."""
    afmesh = os.path.join(args.build_dir, "client", "afmesh")
    out = os.path.join(work, f"afmesh-{envs}.msh")
    command = [afmesh, "volume", surface, "-o", out, "--spec", spec, "--envs", envs, "--json"]
    status, stdout, stderr, seconds = run_process(command, args.thin_timeout)
    row = {"tool": f"afmesh --envs {envs}", "command": " ".join(command), "exit_status": status,
           "process_seconds": seconds}
    if status is None:
        row.update(error=f"timed out after {args.thin_timeout:g} s (killed)", timed_out=True)
        return row
    if status != 0:
        lines = [l for l in stderr.splitlines() if l.strip() and not l.startswith("afmesh: ")]
        row["error"] = (f"{peers.exit_status_text(status)}: "
                        f"{peers.first_problem_line(stderr) or (lines[-1] if lines else '')}")
        return row
    summary = json.loads(stdout)
    quality = summary.get("quality", {})
    row.update(tets=int(summary["tetCount"]), points=int(summary["pointCount"]),
               min_dihedral=quality.get("minDihedralDeg"),
               share_below_20=quality.get("shareBelow20Deg"),
               server_validation=summary.get("validation", {}).get("passed"),
               stages={t["stage"]: t["seconds"] for t in summary.get("timings", [])},
               warnings=[l.split("warning: ", 1)[1] for l in stderr.splitlines()
                         if "warning: " in l])
    row["stats"] = afmesh_stats(afmesh, out)
    medit = out[:-len(".msh")] + ".mesh"
    status, _, err, _ = run_process([afmesh, "convert", out, medit], 600)
    row["check"] = (check_volume(medit, surface) if status == 0
                    else {"error": f"afmesh convert: {err.strip()[-200:]}"})
    return row


def run_thin_peer(args, tool, prefix, size, work):
    """One peer on PREFIX.mesh in a fresh process (bench/peers.py), its mesh through
    check_volume.py."""
    command = ["/usr/bin/python3", os.path.join(BENCH_DIR, "peers.py"), "volume", "--surface",
               prefix, "--size", repr(size), "--tools", tool, "--timeout",
               repr(args.thin_timeout), "--out-dir", work, "--gmsh-sizes", "surface", "--json"]
    row = run_json_lines(command)[0]
    row["tool"] = tool
    if row.get("mesh_file"):
        row["check"] = check_volume(row["mesh_file"], prefix + ".mesh")
    return row


def thin_tools(tools):
    """The peers of THIN_PEERS that --tools asks for (tetgen stands for its three runs)."""
    return [t for t in THIN_PEERS if t in tools or (t.startswith("tetgen") and "tetgen" in tools)]


def generate_thin(args, name, generator_args):
    """Writes THIN_GENERATED's input `name` into the work directory; returns its path."""
    out = os.path.join(args.work_dir, "thin-inputs", name + ".mesh")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    tool = os.path.join(args.build_dir, "tests", "environments", "make-thin-examples")
    subprocess.run([tool, *generator_args, out], check=True)
    return out


def run_thin(args, tools, name, surface, spec, title):
    surface, spec = os.path.join(REPO_DIR, surface), os.path.join(REPO_DIR, spec)
    work = os.path.join(args.work_dir, "thin", name)
    os.makedirs(work, exist_ok=True)
    prefix = os.path.join(work, name)  # the peers read PREFIX.mesh (a copy of the input)
    shutil.copy(surface, prefix + ".mesh")
    with open(spec) as f:
        size = float(json.load(f)["maxSize"])
    points, triangles, _ = peers.read_medit(surface)
    print(f"\n== thin: {title}: {os.path.relpath(surface, REPO_DIR)}, {len(points)} points, "
          f"{len(triangles)} triangles ==", flush=True)
    print(f"   afmesh: --spec {os.path.relpath(spec, REPO_DIR)}; peers: h = its maxSize {size:g} "
          f"(netgen maxh, tetgen -a {peers.TETGEN_VOLUME_FACTOR} h^3; gmsh sizes from the "
          f"surface); timeout {args.thin_timeout:g} s each", flush=True)
    print(f"   start: {load_line()}", flush=True)
    rows = []
    if "afmesh" in tools:
        rows += [run_thin_afmesh(args, surface, spec, envs, work) for envs in THIN_AFMESH_ENVS]
    rows += [run_thin_peer(args, tool, prefix, size, work) for tool in thin_tools(tools)]
    print_thin_table(rows)
    return {"input": os.path.relpath(surface, REPO_DIR), "spec": os.path.relpath(spec, REPO_DIR),
            "surface_points": len(points), "surface_triangles": len(triangles),
            "peer_size": size, "rows": rows}


# ---------------------------------------------------------------------------------------------
# Equal element counts: each tool's size adjusted until its tet count is within a tolerance of
# a target N (count ~ size^-3, so secant steps on log size against log count).

def parse_count(text):
    """50k -> 50000, 2M -> 2000000, 120000 -> 120000."""
    match = re.fullmatch(r"(\d+(?:\.\d+)?)([kKmM]?)", text.strip())
    if not match:
        raise ValueError(f"bad tet count '{text}' (e.g. 50k, 500k, 2M, 120000)")
    return int(round(float(match.group(1)) * {"": 1, "k": 1e3, "m": 1e6}[match.group(2).lower()]))


def start_size(shape, count):
    """afmesh's first h for `count` tets: the SIZES entry nearest in count, scaled by
    (its count / count)^(1/3); None when SIZES has none for the shape."""
    known = [(TARGET_TETS[t], h) for t, h in SIZES.get(shape, {}).items() if t in TARGET_TETS]
    if not known:
        return None
    ref_count, ref_h = min(known, key=lambda k: abs(math.log(k[0] / count)))
    return ref_h * (ref_count / count) ** (1.0 / 3.0)


MAX_SIZE_STEP = 1.5  # the largest change of size from one run of an equal-count search to the next


def next_size(tried, target):
    """The next size to try from the runs so far (dicts with "size" and, when they meshed,
    "tets"). With runs either side of the target that bracket it (the largest size above the
    target smaller than the smallest size below it): regula falsi on (log size, log tets) inside
    that bracket; otherwise (no bracket, or counts that do not fall as the size grows, as netgen's
    sometimes) a secant through the two runs closest to the target, slope -3 when there is one
    run or the slope found is implausible (flatter than -1 counts as -1), and at most a factor
    MAX_SIZE_STEP from the closest run. Never a size already tried, nor one within 2% of a run
    that failed."""
    good = [(math.log(r["size"]), math.log(r["tets"])) for r in tried if r.get("tets")]
    goal = math.log(target)
    if not good:  # nothing meshed yet (e.g. afmesh's front did not close): a nearby size
        return tried[-1]["size"] * 1.03
    above = [g for g in good if g[1] > goal]  # too many tets: size too small
    below = [g for g in good if g[1] < goal]
    bracket = None
    if above and below:
        a, b = max(above), min(below)  # by log size
        if a[0] < b[0]:
            bracket = (a, b)
    if bracket is None:
        ranked = sorted(good, key=lambda g: abs(g[1] - goal))
        a, b = ranked[0], ranked[1] if len(ranked) > 1 else None
    else:
        a, b = bracket
    slope = -3.0
    if b is not None and abs(b[0] - a[0]) > 1e-9:
        slope = (b[1] - a[1]) / (b[0] - a[0])
        if not -8.0 < slope < -1.0:
            slope = -3.0 if slope > -0.3 or slope < -8.0 else -1.0
    log_size = a[0] + (goal - a[1]) / slope
    if bracket is not None:  # inside the bracket, away from its ends
        low, high = a[0], b[0]
        margin = 0.15 * (high - low)
        log_size = min(max(log_size, low + margin), high - margin)
    else:  # at most a factor MAX_SIZE_STEP from the closest run (a count 3.4 times or 1/3.4)
        step = math.log(MAX_SIZE_STEP)
        log_size = min(max(log_size, a[0] - step), a[0] + step)
    wanted = math.exp(log_size)
    # A size already tried gives the same count again, and one within 2% of a failed run (gmsh
    # HXT crashing, afmesh's front not closing) likely fails again: the nearest size 3%, 6%, ...
    # either side that is clear of both.
    clear = lambda size: all(abs(math.log(size / r["size"]))
                             >= (0.02 if not r.get("tets") else 0.005) for r in tried)
    for k in range(40):
        size = wanted * 1.03 ** ((k + 1) // 2 * (1 if k % 2 else -1))
        if clear(size):
            return size
    return wanted


def search_count(run, target, first_size, args, label):
    """Runs `run(size)` (figures with "tets", or "error") at first_size, then at sizes from
    next_size, until a count within args.count_tolerance of target or args.count_max_runs runs.
    Returns the chosen figures: the first within tolerance, else the run closest to target
    ("count_status" "closest"), else the last failure ("failed"; "timed out" stops the search at
    once). Each step is printed; "trail" lists them all."""
    tried, size = [], first_size
    for _ in range(args.count_max_runs):
        figures = run(size)
        tried.append(figures)
        tets = figures.get("tets") if "error" not in figures else None
        if tets:
            off = tets / target - 1.0
            print(f"   {label}: size {size:.5g} -> {tets:,} tets ({100 * off:+.1f}%)", flush=True)
            if abs(off) <= args.count_tolerance:
                figures["count_status"] = "within"
                break
        else:
            note = figures.get("error", "no tets")
            print(f"   {label}: size {size:.5g} -> {'TIMED OUT' if figures.get('timed_out') else 'FAILED'}"
                  f": {note[:200]}", flush=True)
            if figures.get("timed_out"):
                break
        size = next_size(tried, target)
    trail = [{"size": r["size"], "tets": r.get("tets") if "error" not in r else None,
              "seconds": r.get("seconds"), **({"error": r["error"]} if "error" in r else {})}
             for r in tried]
    meshed = [r for r in tried if "error" not in r and r.get("tets")]
    if tried[-1].get("count_status") == "within":
        chosen = tried[-1]
    elif meshed and not tried[-1].get("timed_out"):
        chosen = min(meshed, key=lambda r: abs(math.log(r["tets"] / target)))
        chosen["count_status"] = "closest"
    else:
        chosen = tried[-1]
        chosen["count_status"] = "timed out" if chosen.get("timed_out") else "failed"
        if meshed:
            chosen["closest_meshed"] = min(meshed, key=lambda r: abs(math.log(r["tets"] / target)))
    chosen["runs"] = len(tried)
    chosen["trail"] = trail
    return chosen


def equal_count_skip(args, tool, label, target):
    if f"{tool}@{label}" in args.skip:
        return f"skipped by --skip {tool}@{label}"
    if tool == "netgen" and target > TARGET_TETS[args.netgen_max_target]:
        return f"skipped: --netgen-max-target {args.netgen_max_target}"
    return None


def asked_text(row):
    """What the tool was asked, e.g. "maxh 0.0812" or "-a 0.00034"."""
    h = row.get("size")
    if h is None:
        return "-"
    tool = row["tool"]
    if tool.startswith("afmesh"):
        return f"--size {h:.4g}"
    if tool.startswith("gmsh"):
        return f"MeshSizeMax {h:.4g}"
    if tool == "netgen":
        return f"maxh {h:.4g}"
    if tool == "tetgen":
        return f"-a {peers.TETGEN_VOLUME_FACTOR * h ** 3:.4g} (h {h:.4g})"
    return f"{h:.4g}"


def run_equal_count(args, tools, shape, label):
    """One shape at one target count: afmesh's h found first (its surface changes with h), then
    on that surface each peer's size."""
    target = parse_count(label)
    base = os.path.join(args.work_dir, "equal-count", f"{shape}-{label}")
    os.makedirs(os.path.dirname(base), exist_ok=True)
    print(f"\n== equal count: {SHAPE_TITLES.get(shape, shape)}: {target:,} tets "
          f"(within {100 * args.count_tolerance:g}%, at most {args.count_max_runs} runs per tool, "
          f"{args.count_timeout:g} s per run) ==", flush=True)
    print(f"   start: {load_line()}", flush=True)
    h0 = start_size(shape, target)
    if h0 is None:
        print(f"   no size for {shape} in SIZES to start from; give one with --size {shape}:50k=H")
        return {"target_tets": target, "rows": [{"tool": "afmesh", "error": "no start size"}]}
    prefix_of = lambda h: f"{base}-h{h:.6g}"
    afmesh = search_count(
        lambda h: run_afmesh(args, shape, h, prefix_of(h), True, args.count_timeout),
        target, h0, args, "afmesh")
    rows = [afmesh]
    surface_h = afmesh["size"] if "error" not in afmesh else afmesh.get(
        "closest_meshed", afmesh)["size"]
    prefix = prefix_of(surface_h)
    surface = {}
    if not os.path.exists(prefix + ".mesh"):
        print("   no surface was written: nothing for the peers to mesh")
    else:
        points, triangles, _ = peers.read_medit(prefix + ".mesh")
        surface = {"prefix": prefix, "afmesh_size": surface_h, "points": len(points),
                   "triangles": len(triangles)}
        print(f"   peers mesh afmesh's surface at h = {surface_h:.5g}: {len(points):,} points, "
              f"{len(triangles):,} triangles", flush=True)
        for tool in tools:
            if tool == "afmesh":
                continue
            reason = equal_count_skip(args, tool, label, target)
            if reason:
                rows.append({"tool": tool, "skipped": reason})
                continue
            rows.append(search_count(lambda h: run_peer(args, tool, h, prefix, args.count_timeout),
                                     target, surface_h, args, tool))
    print(f"   end: {load_line()}")
    print_equal_count_table(rows, target, args.count_tolerance)
    return {"target_tets": target, "tolerance": args.count_tolerance, "surface": surface,
            "rows": rows}


# ---------------------------------------------------------------------------------------------
# Printing.

VOLUME_COLUMNS = (
    ("tool", 13, "s"), ("tets", 9, ","), ("time s", 8, ".2f"), ("cpu s", 8, ".2f"),
    ("tets/s", 9, ",.0f"), ("bytes/tet", 9, ".0f"), ("min dih", 7, ".2f"), ("%<10°", 7, ".3f"),
    ("%<20°", 7, ".3f"), ("min RR", 7, ".4f"), ("mean RR", 7, ".4f"),
    ("edge/h", 6, ".3f"), ("%e in band", 10, ".1f"),
    ("afm/peer tets/s", 15, ".2f"), ("afm/peer B/tet", 14, ".2f"))


def _cell(value, width, spec):
    text = "-" if value is None else format(value, spec)
    return text.ljust(width) if spec == "s" else text.rjust(width)


def volume_cells(row, reference):
    tets_per_s = row["tets"] / row["seconds"] if row.get("seconds") else None
    bytes_per_tet = row.get("bytes_per_tet")
    speed_ratio = memory_ratio = None
    if ("error" not in reference and reference is not row and tets_per_s
            and not row["tool"].startswith("afmesh")):
        speed_ratio = (reference["tets"] / reference["seconds"]) / tets_per_s
        if bytes_per_tet and reference.get("bytes_per_tet") is not None:
            memory_ratio = reference["bytes_per_tet"] / bytes_per_tet
    percent = lambda share: None if share is None else 100.0 * share
    return [row["tool"], row["tets"], row["seconds"], row.get("cpu_seconds"), tets_per_s,
            bytes_per_tet, row.get("min_dihedral"), percent(row.get("share_below_10")),
            percent(row.get("share_below_20")), row.get("min_radius_ratio"),
            row.get("mean_radius_ratio"), row.get("mean_edge_over_h"),
            percent(row.get("share_edges_in_band")), speed_ratio, memory_ratio]


def print_table(rows):
    print("   " + " ".join(_cell(name, w, "s") if i == 0 else name.rjust(w)
                           for i, (name, w, _) in enumerate(VOLUME_COLUMNS)))
    reference = rows[0]
    for row in rows:
        if "error" in row or "skipped" in row:
            note = f"FAILED: {row['error']}" if "error" in row else row["skipped"]
            print(f"   {row['tool']:13s} {note}")
            continue
        cells = volume_cells(row, reference)
        print("   " + " ".join(_cell(v, w, spec) for v, (_, w, spec) in zip(cells, VOLUME_COLUMNS)))
    for row in rows:
        if row["tool"].startswith("afmesh") and "error" not in row:
            stages = ", ".join(f"{k} {v:.2f} s" for k, v in row.get("stages", {}).items())
            valid = {True: "valid", False: "INVALID: " + row.get("validation", "")}.get(
                row.get("valid"), "not validated")
            print(f"   {row['tool']}: {valid}; stages {stages}")
    print(f"   (edge/h: mean interior edge length / h, the size asked of that tool; %e in band: "
          f"share of interior edges in [{peers.EDGE_BAND[0]:g} h, {peers.EDGE_BAND[1]:g} h])")
    sys.stdout.flush()


EQUAL_COUNT_COLUMNS = (
    ("tool", 13, "s"), ("asked", 24, "s"), ("runs", 4, "d"), ("tets", 9, ","),
    ("vs N", 7, "s"), ("time s", 8, ".2f"), ("tets/s", 9, ",.0f"), ("bytes/tet", 9, ".0f"),
    ("min dih", 7, ".2f"), ("%<20°", 7, ".3f"), ("edge/h", 6, ".3f"), ("%e in band", 10, ".1f"),
    ("afm/peer tets/s", 15, ".2f"), ("afm/peer B/tet", 14, ".2f"))


def print_equal_count_table(rows, target, tolerance):
    print("   " + " ".join(_cell(name, w, "s") if spec == "s" else name.rjust(w)
                           for name, w, spec in EQUAL_COUNT_COLUMNS))
    ours = rows[0]
    ours_ok = "error" not in ours and ours.get("seconds")
    notes = []
    for row in rows:
        if "skipped" in row:
            print(f"   {row['tool']:13s} {row['skipped']}")
            continue
        if "error" in row:
            what = "TIMED OUT" if row.get("timed_out") else "FAILED"
            print(f"   {row['tool']:13s} {what} at {asked_text(row)} after {row['runs']} run(s): "
                  f"{row['error'][:300]}")
            closest = row.get("closest_meshed")
            if closest:
                notes.append(f"   {row['tool']}: no figures reported; its closest count before was "
                             f"{closest['tets']:,} at {asked_text(closest)}")
            continue
        tets_per_s = row["tets"] / row["seconds"] if row.get("seconds") else None
        off = f"{100 * (row['tets'] / target - 1):+.1f}%" + (
            "" if row.get("count_status") == "within" else "!")
        speed_ratio = memory_ratio = None
        if row is not ours and ours_ok and tets_per_s:
            speed_ratio = (ours["tets"] / ours["seconds"]) / tets_per_s
            if row.get("bytes_per_tet") and ours.get("bytes_per_tet") is not None:
                memory_ratio = ours["bytes_per_tet"] / row["bytes_per_tet"]
        percent = lambda share: None if share is None else 100.0 * share
        cells = [row["tool"], asked_text(row), row["runs"], row["tets"], off, row["seconds"],
                 tets_per_s, row.get("bytes_per_tet"), row.get("min_dihedral"),
                 percent(row.get("share_below_20")), row.get("mean_edge_over_h"),
                 percent(row.get("share_edges_in_band")), speed_ratio, memory_ratio]
        print("   " + " ".join(_cell(v, w, spec) for v, (_, w, spec) in zip(cells, EQUAL_COUNT_COLUMNS)))
        if row.get("count_status") != "within":
            notes.append(f"   {row['tool']}: NOT within {100 * tolerance:g}% of {target:,} after "
                         f"{row['runs']} runs; the closest run is shown")
        if row["tool"] == "afmesh" and row.get("valid") is False:
            notes.append(f"   afmesh: INVALID: {row.get('validation', '')}")
    for row in rows:
        failures = [t for t in row.get("trail", []) if "error" in t]
        if failures and "error" not in row:
            notes.append(f"   {row['tool']}: {len(failures)} of its runs failed on the way, e.g. "
                         f"size {failures[0]['size']:.5g}: {failures[0]['error'][:200]}")
    print("\n".join(notes) if notes else "", end="\n" if notes else "")
    print(f"   (vs N: count against the target {target:,}, ! = not within {100 * tolerance:g}%; "
          f"runs: meshings to find the size; afm/peer: afmesh's tets/s (bytes/tet) over the "
          f"peer's at these counts, > 1 = afmesh faster (uses more memory per tet); edge/h: mean "
          f"interior edge / the size asked of that tool; %e in band: share of interior edges in "
          f"[{peers.EDGE_BAND[0]:g} h, {peers.EDGE_BAND[1]:g} h])")
    sys.stdout.flush()


def print_io_table(rows):
    print(f"   {'tool':8s} {'triangles':>10s} {'points':>9s} {'read s':>7s} {'write s':>7s} "
          f"{'total s':>7s} {'peak MiB':>8s} {'+MiB':>7s} {'B/tri':>6s} {'afm/peer time':>13s}")
    ours = rows[0]
    for row in rows:
        if "error" in row:
            print(f"   {row['tool']:8s} FAILED: {row['error']}")
            continue
        ratio = ours["seconds"] / row["seconds"] if row is not ours and "error" not in ours else None
        growth = (row["rss_peak_bytes"] - row["rss_before_bytes"]) / 2**20
        print(f"   {row['tool']:8s} {row['triangles']:>10,} {row['points']:>9,} "
              f"{row['read_seconds']:7.2f} {row['write_seconds']:7.2f} {row['seconds']:7.2f} "
              f"{row['rss_peak_bytes'] / 2**20:8.1f} {growth:7.1f} {row['bytes_per_triangle']:6.0f} "
              f"{_cell(ratio, 13, '.2f')}")
    print("   (afm/peer time < 1: afmesh is faster; peak MiB is the whole process's peak, +MiB "
          "its growth during the conversion)")
    sys.stdout.flush()


def print_sizing_table(rows):
    print(f"   {'sources':>8s} {'points':>8s} {'single/s':>12s} {'single/s':>12s} "
          f"{'batch/s':>12s} {'batch/s':>12s} {'pruning':>8s} {'build s':>8s}")
    print(f"   {'':>8s} {'':>8s} {'no pruning':>12s} {'pruning':>12s} {'no pruning':>12s} "
          f"{'pruning':>12s} {'speed-up':>8s} {'(cells)':>8s}")
    for row in rows:
        if "error" in row:
            print(f"   afmesh-bench-sizing FAILED: {row['error']}")
            continue
        label = f"{row['sources']}{'c' if row['clustered'] else ' '}"
        print(f"   {label:>8s} {row['points']:>8,} {row['single_no_pruning']:>12,.0f} "
              f"{row['single_pruning']:>12,.0f} {row['batch_no_pruning']:>12,.0f} "
              f"{row['batch_pruning']:>12,.0f} {row['batch_pruning'] / row['batch_no_pruning']:>7.1f}x "
              f"{row['build_seconds']:>8.3f}")
    print("   (c: 1000 sources clustered within 0.02 of the cube's centre, the hard case for "
          "pruning; single = size_at per point, batch = sizes_at over all points; speed-up = "
          "batch pruning / batch no pruning)")
    print("   peers: gmsh, netgen and tetgen have no point/line/triangle source fields to evaluate, "
          "so there is nothing to compare and no afmesh/peer ratio")
    sys.stdout.flush()


def thin_outcome(row):
    """(short outcome, full reason or None) of one row of a thin input's table."""
    if row.get("timed_out"):
        return "TIMED OUT", row["error"]
    if "error" in row:
        reason = row.get("last_line") or row["error"]
        first = row.get("first_problem")
        if first and reason.split(": ", 1)[-1].strip() not in first:
            reason += f" [first problem line: {first}]"
        if row.get("intersecting_pairs"):
            reason += f" [{row['intersecting_pairs']} distinct intersecting element pairs warned]"
        crash = re.search(r"exit status (\d+) \((SIG\w+)\)", reason)
        if crash:
            return f"CRASHED ({crash.group(2)}, exit {crash.group(1)})", reason
        if row.get("exit_status") is not None:
            return f"FAILED (exit {row['exit_status']})", reason
        return "FAILED (exception)" if "Exception" in reason or "Error" in reason else "FAILED", reason
    if row["tool"] == "tetgen-d":
        return f"found {row['intersecting_pairs']} crossing pairs", row.get("verdict")
    if row.get("tets", 0) == 0:
        return "surface only: no tets", row.get("first_problem")
    verdicts = []
    for key, label in (("stats", "afmesh stats"), ("check", "check_volume")):
        result = row.get(key)
        if result is None:
            continue
        if "error" in result:
            verdicts.append(f"{label}: {result['error']}")
        elif not result.get("valid", result.get("pass")):
            verdicts.append(f"{label} fails {', '.join(result['failed']) or '?'}")
    if verdicts:
        return "INVALID", "; ".join(verdicts)
    checked = " + ".join(label for key, label in (("stats", "stats"), ("check", "check"))
                         if key in row)
    return f"valid ({checked})", None


def thin_gap_cell(row):
    """Tets across a gap: afmesh stats / check_volume.py ('-': not run or no mesh)."""
    values = [row.get(key, {}).get("gap_tets") for key in ("stats", "check")]
    if all(v is None for v in values):
        return "-"
    return " / ".join("-" if v is None else str(v) for v in values)


def print_thin_table(rows):
    print(f"   {'tool':20s} {'outcome':30s} {'tets':>7s} {'min dih':>7s} {'%<20°':>7s} "
          f"{'gap tets':>9s} {'time s':>7s}")
    notes = []
    for row in rows:
        outcome, reason = thin_outcome(row)
        share = row.get("share_below_20")
        seconds = row.get("process_seconds")
        print(f"   {row['tool']:20s} {outcome:30s} {_cell(row.get('tets'), 7, ',')} "
              f"{_cell(row.get('min_dihedral'), 7, '.2f')} "
              f"{_cell(None if share is None else 100 * share, 7, '.3f')} "
              f"{thin_gap_cell(row):>9s} {_cell(seconds, 7, '.2f')}")
        if reason:
            notes.append(f"   {row['tool']}: {reason}")
        for warning in row.get("warnings", []):
            notes.append(f"   {row['tool']}: {warning}")
    print("\n".join(notes))
    print("   (gap tets: tets joining two different positive environments, by afmesh stats --envs "
          "tags / tools/check_volume.py --envs; time: wall seconds of the whole process, afmesh "
          "with its private server, a peer in a fresh Python process with its imports)")
    sys.stdout.flush()


def print_growth(shape, cases):
    """Time per tet of afmesh at the largest target over the smallest."""
    rows = {t: r[0] for t, r in cases.items() if "error" not in r[0]}
    present = [t for t in TARGETS if t in rows]
    if len(present) < 2:
        return
    failed = [t for t in cases if t not in rows]
    missing = f" (afmesh failed at {', '.join(failed)})" if failed else ""
    small, large = rows[present[0]], rows[present[-1]]
    per_tet = lambda r, key: r[key] / r["tets"]
    wall = per_tet(large, "seconds") / per_tet(small, "seconds")
    cpu = per_tet(large, "cpu_seconds") / per_tet(small, "cpu_seconds")
    print(f"\n   afmesh {shape}: time per tet {present[0]}→{present[-1]} growth "
          f"({small['tets']:,} → {large['tets']:,} tets): {wall:.2f}× wall "
          f"({1e6 * per_tet(small, 'seconds'):.2f} → {1e6 * per_tet(large, 'seconds'):.2f} µs/tet), "
          f"{cpu:.2f}× cpu ({1e6 * per_tet(small, 'cpu_seconds'):.2f} → "
          f"{1e6 * per_tet(large, 'cpu_seconds'):.2f} µs/tet){missing}", flush=True)


# ---------------------------------------------------------------------------------------------

def main(argv):
    args = parse_arguments(argv)
    os.makedirs(args.work_dir, exist_ok=True)
    tools = args.tools.split(",")
    print(f"afmesh benchmark, {datetime.datetime.now():%Y-%m-%d %H:%M}")
    print(f"   {machine_line()}\n   {source_line()}\n   {load_line()}")
    print("   every figure from a fresh process, one at a time, one thread each "
          "(OMP_NUM_THREADS=1; gmsh General.NumThreads=1, Mesh.MaxNumThreads3D=1)")
    results = {}
    only = args.io_only or args.sizing_only or args.thin_only or args.equal_count_only
    if not only:
        for shape in args.shapes.split(","):
            cases = {}
            for target in args.targets.split(","):
                cases[target] = run_case(args, tools, shape, target)
            print_growth(shape, cases)
            results[shape] = cases
    if args.equal_count_only or (args.equal_count and not only):
        results["equal_count"] = {
            shape: {label: run_equal_count(args, tools, shape, label)
                    for label in args.count_targets.split(",")}
            for shape in args.shapes.split(",")}
    if args.io_only or (args.io and not only):
        results["io"] = run_io(args)
    if args.sizing_only or (args.sizing and not only):
        results["sizing"] = run_sizing(args)
    if args.thin_only or (args.thin and not only):
        results["thin"] = {name: run_thin(args, tools, name, *rest)
                           for name, *rest in THIN_INPUTS}
        for name, generator_args, spec, title in THIN_GENERATED:
            results["thin"][name] = run_thin(args, tools, name,
                                             generate_thin(args, name, generator_args), spec,
                                             title)
    with open(os.path.join(args.work_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    print(f"\n{load_line()}\nfigures saved in {os.path.join(args.work_dir, 'results.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
