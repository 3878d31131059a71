#!/usr/bin/python3
"""The fanned-cylinder family of issue 10 through the CLI: valid, filled, min dihedral.

usage: run_cylinder_family.py --afmesh BIN/afmesh [--out DIR] [--jobs 2] [--precision float|double]

Writes the 36 cylinders of make_exporter_shapes.py's `cylinder` (radius 1, heights 1 and 0.5,
40, 64, 80, 96, 112, 128 round, 2, 4, 6 layers, caps fanned to their centres) as binary STL
(float: every side quad exactly planar) or as OBJ in double precision (planar but for rounding),
meshes each with no size and at 0.5 and 0.7 of its mean edge (`afmesh volume`, reruns allowed),
checks each mesh with ../shared/tools/check_volume.py, and prints one line per run (VALID,
FILLED when the front failed and the volume was filled from its points, min dihedral, wall) and
a summary. Deterministic inputs; needs numpy and meshio (Debian's python3).
"""

import argparse
import concurrent.futures
import json
import os
import subprocess
import time

import numpy as np

import make_exporter_shapes
import stl_tools

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "tools", "check_volume.py"))


def write_family(out, precision):
    runs = []
    for around in (40, 64, 80, 96, 112, 128):
        for layers in (2, 4, 6):
            for height in (1.0, 0.5):
                pts, tris = make_exporter_shapes.cylinder(around, layers, height)
                p, t = np.array(pts), np.array(tris)
                edges = np.concatenate([np.linalg.norm(p[t[:, i]] - p[t[:, (i + 1) % 3]], axis=1)
                                        for i in range(3)])
                name = f"cylinder_{around}_{layers}_h{height}"
                if precision == "float":
                    path = os.path.join(out, name + ".stl")
                    stl_tools.write_stl(path, p, t)
                else:
                    path = os.path.join(out, name + ".obj")
                    with open(path, "w") as f:
                        f.writelines("v %.17g %.17g %.17g\n" % tuple(x) for x in pts)
                        f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in tris)
                mean = float(edges.mean())
                runs += [(name, path, "none", None), (name, path, "0.5me", 0.5 * mean),
                         (name, path, "0.7me", 0.7 * mean)]
    return runs


def run_one(afmesh, out, run):
    name, path, label, size = run
    mesh = os.path.join(out, f"{name}__{label}.msh")
    cmd = [afmesh, "volume", path, "-o", mesh]
    if size is not None:
        cmd += ["--size", f"{size:.6g}"]
    start = time.monotonic()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    rec = {"name": name, "label": label, "rc": done.returncode, "wall": round(wall, 2),
           "filled": "filled by the Delaunay tetrahedralisation" in done.stderr}
    if done.returncode == 0 and os.path.exists(mesh):
        check = subprocess.run(["/usr/bin/python3", CHECK, mesh, path], capture_output=True,
                               text=True)
        rec["valid"] = "pass: True" in check.stdout
        for line in check.stdout.splitlines():
            if line.startswith("quality:"):
                rec["min_dihedral"] = round(
                    float(line.split("'min_dihedral_deg':")[1].split(",")[0]), 2)
        os.remove(mesh)
    else:
        rec["valid"] = False
        rec["message"] = done.stderr.strip().splitlines()[-1][:200] if done.stderr.strip() else ""
    return rec


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--afmesh", required=True)
    ap.add_argument("--out", default="/tmp/afmesh-cylinder-family")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--precision", choices=("float", "double"), default="float")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    runs = write_family(args.out, args.precision)
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        recs = list(pool.map(lambda r: run_one(args.afmesh, args.out, r), runs))
    with open(os.path.join(args.out, f"results_{args.precision}.jsonl"), "w") as f:
        for r in recs:
            f.write(json.dumps(r) + "\n")
            print(f"{r['name']:24s} {r['label']:>6s} {'VALID' if r['valid'] else 'FAILED'}"
                  f"{' FILLED' if r['filled'] else ''} {r['wall']:6.2f}s "
                  f"{r.get('min_dihedral', r.get('message', ''))}")
    valid = sum(r["valid"] for r in recs)
    filled = [r for r in recs if r["valid"] and r["filled"]]
    md = sorted(r["min_dihedral"] for r in filled if "min_dihedral" in r)
    print(f"\n{args.precision}: {valid} of {len(recs)} valid, {len(filled)} of them filled"
          + (f" (min dihedral {md[0]}-{md[-1]} degrees)" if md else ""))


if __name__ == "__main__":
    main()
