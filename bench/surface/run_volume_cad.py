#!/usr/bin/python3
"""The volume mesher on raw CAD tessellations, with and without --remesh-surface (issue 11):
one line per file and mode.

Runs `afmesh volume F -o OUT.msh --json --quiet` (its private server; default size: the file's
mean edge length) on each closed CAD file of ../shared/corpus/, once as it is and once with
--remesh-surface (the surface re-triangulated at the size first, in the same job), each a fresh
process with a timeout. Columns: outcome (ok, or the exit code and the first line of the
message, or timeout), tets, min dihedral angle, % of tets under 20 degrees, boundary triangles,
cpu s (user + system of the CLI and its server) and wall s.

With --occt, the four raw CAD tessellations of Debian's occt-misc that issue 10 names (shape,
sh1, sh2 and TR12J_OCC in /usr/share/opencascade/data/stl, or --occt-dir: closed, manifold,
oriented, with sliver triangles down to 0.002 degrees and edge ratios up to 800) follow the
corpus's files, or replace them with --only-occt.

  bench/surface/run_volume_cad.py [--cli PATH] [--corpus DIR] [--timeout SEC] [--only a,b]
                                  [--occt | --only-occt] [--occt-dir DIR]
"""

import argparse
import os
import sys
import tempfile

from run_corpus import DEFAULT_CLI, DEFAULT_CORPUS, closed_files, run_cli_volume

# The corpus's CAD tessellations (corpus README: CAD parts, not scans or terrain).
# Debian's occt-misc raw CAD tessellations (issue 10 part 3).
OCCT_DIR = "/usr/share/opencascade/data/stl"
OCCT = ["shape", "sh1", "sh2", "TR12J_OCC"]
CAD = ["cgal_pinion", "cgal_rotor", "cgal_couplingdown", "gmsh_lever", "netgen_hinge",
       "netgen_part1", "simbody_UR10_Wrist2", "of_simpleCar", "plb_obstacle"]


def row(cli, path, remesh, timeout):
    with tempfile.TemporaryDirectory() as tmp:
        return run_cli_volume(cli, path, os.path.join(tmp, "out.msh"), timeout,
                              ["--remesh-surface"] if remesh else [])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default=DEFAULT_CLI)
    ap.add_argument("--corpus", default=DEFAULT_CORPUS)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--only", default="", help="comma-separated file stems")
    ap.add_argument("--occt", action="store_true", help="also occt-misc's raw CAD files")
    ap.add_argument("--only-occt", action="store_true", help="occt-misc's raw CAD files only")
    ap.add_argument("--occt-dir", default=OCCT_DIR)
    args = ap.parse_args()
    corpus = os.path.abspath(args.corpus)
    closed = closed_files(corpus)
    files = [] if args.only_occt else [
        (n, os.path.join(corpus, f"{n}.stl"))
        for n in (args.only.split(",") if args.only else CAD) if f"{n}.stl" in closed or args.only]
    if args.occt or args.only_occt:
        for n in OCCT:
            path = os.path.join(args.occt_dir, f"{n}.stl")
            if not os.path.exists(path):
                sys.exit(f"run_volume_cad.py: {path} not found (apt install occt-misc)")
            files.append((n, path))
    print(f"{'file':22} {'mode':8} {'outcome':8} {'tets':>9} {'min dih':>8} {'% <20':>6} "
          f"{'bnd tris':>9} {'cpu s':>7} {'wall s':>7}  message")
    for name, path in files:
        for remesh in (False, True):
            r = row(args.cli, path, remesh, args.timeout)
            mode = "remesh" if remesh else "raw"
            if r["outcome"] == "ok":
                print(f"{name:22} {mode:8} {'ok':8} {r['tets']:9d} {r['min_dihedral']:8.2f} "
                      f"{r['below_20']:6.2f} {r['triangles']:9d} {r['cpu']:7.2f} {r['wall']:7.2f}")
            else:
                print(f"{name:22} {mode:8} {r['outcome']:8} {'-':>9} {'-':>8} {'-':>6} {'-':>9} "
                      f"{r['cpu']:7.2f} {r['wall']:7.2f}  {r.get('message', '')[:160]}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
