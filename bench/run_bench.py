#!/usr/bin/python3
"""The benchmark tables: afmesh's volume mesher against gmsh (Delaunay, HXT), netgen and tetgen on
the same surfaces, core/io converting a ~1M-triangle STL against gmsh, and the size field's
evaluations per second with 1 to 1000 sources (afmesh alone: the peers have no source fields).
Run by scripts/bench.sh.

Every measurement is a fresh process, run one after the other (never in parallel): afmesh by
afmesh-bench-volume / afmesh-bench-io, the peers by bench/peers.py. Each case first runs afmesh,
which writes the surface the peers then mesh.

Columns: tets; time = wall seconds of the volume phase (cpu = its CPU seconds: on a loaded
machine wall > cpu); tets/s = tets / wall seconds; bytes/tet = (peak resident memory during the
phase - resident before) / tets; min dihedral (degrees), shares of tets with min dihedral under 10
and 20 degrees, min and mean radius ratio (3 r_in / r_circ); afmesh/peer = afmesh's tets/s (or
bytes/tet) over the peer's, so > 1 means afmesh is faster (or uses more memory per tet).
"""

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys

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
SHAPE_TITLES = {"sphere": "sphere, radius 1", "torus": "torus, R = 1, r = 0.35",
                "box": "unit cube", "lblock": "L-block with a square hole, voxels 0.5"}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
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
    parser.add_argument("--io", dest="io", action="store_true", default=True)
    parser.add_argument("--no-io", dest="io", action="store_false", help="skip the io benchmark")
    parser.add_argument("--io-only", action="store_true", help="only the io benchmark")
    parser.add_argument("--sizing", dest="sizing", action="store_true", default=True)
    parser.add_argument("--no-sizing", dest="sizing", action="store_false",
                        help="skip the size-field throughput benchmark")
    parser.add_argument("--sizing-only", action="store_true",
                        help="only the size-field throughput benchmark")
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
        return [{"error": f"timed out after {timeout:.0f} s (killed)"}]
    results = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    if not results:
        tail = " | ".join((done.stderr or done.stdout).strip().splitlines()[-3:])
        return [{"error": f"exit status {done.returncode}: {tail}"}]
    return results


def run_afmesh(args, shape, h, prefix, optimise):
    command = [os.path.join(args.build_dir, "bench", "afmesh-bench-volume"), "--shape", shape,
               "--size", repr(h), "--json"]
    if optimise:
        command += ["--surface", prefix]
    else:
        command += ["--no-optimise"]
    figures = run_json_lines(command)[0]
    figures["tool"] = "afmesh" if optimise else "afmesh no-opt"
    return figures


def run_peer(args, tool, h, prefix):
    command = ["/usr/bin/python3", os.path.join(BENCH_DIR, "peers.py"), "volume", "--surface",
               prefix, "--size", repr(h), "--tools", tool, "--timeout", repr(args.peer_timeout),
               "--json"]
    figures = run_json_lines(command)[0]
    figures["tool"] = tool
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
# Printing.

VOLUME_COLUMNS = (
    ("tool", 13, "s"), ("tets", 9, ","), ("time s", 8, ".2f"), ("cpu s", 8, ".2f"),
    ("tets/s", 9, ",.0f"), ("bytes/tet", 9, ".0f"), ("min dih", 7, ".2f"), ("%<10°", 7, ".3f"),
    ("%<20°", 7, ".3f"), ("min RR", 7, ".4f"), ("mean RR", 7, ".4f"),
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
            row.get("mean_radius_ratio"), speed_ratio, memory_ratio]


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
    if not (args.io_only or args.sizing_only):
        for shape in args.shapes.split(","):
            cases = {}
            for target in args.targets.split(","):
                cases[target] = run_case(args, tools, shape, target)
            print_growth(shape, cases)
            results[shape] = cases
    if args.io_only or (args.io and not args.sizing_only):
        results["io"] = run_io(args)
    if args.sizing_only or (args.sizing and not args.io_only):
        results["sizing"] = run_sizing(args)
    with open(os.path.join(args.work_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    print(f"\n{load_line()}\nfigures saved in {os.path.join(args.work_dir, 'results.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
