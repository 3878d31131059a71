#!/usr/bin/python3
"""Debian's libcgal-demo meshes as binary STL files, for run_corpus.py --corpus DIR.

libcgal-demo (Debian 12: 5.5.1-2, 24 MB) ships CGAL's example and demo data: about 150 surface
meshes made by other people (scans, CAD parts, animals, noisy and self-intersecting models), of
which the corpus (../shared/corpus) holds 13. This script fetches the package with
`apt-get download` (no installation, no root), unpacks its data, examples and demo archives, and
writes every OFF, OBJ, PLY and STL mesh with at least --min-triangles triangles to
OUT/<path with / as _>.stl (polygons split into fans; point clouds and unreadable files are
listed and skipped). Then:

    bench/surface/cgal_data.py --out /tmp/cgal-data
    bench/surface/run_corpus.py --corpus /tmp/cgal-data --timeout 120

Run with Debian's /usr/bin/python3 (meshio, numpy).
"""
import argparse
import glob
import os
import subprocess
import sys
import tarfile
import tempfile

import meshio
import numpy as np


def read_off(path):
    """Points (N x 3) and triangles (fans of the polygons) of an OFF file: comments, COFF/NOFF
    headers and polygons of any size; colours after a face's indices are ignored."""
    lines = []
    with open(path, "rb") as f:
        for line in f:
            line = line.split(b"#")[0].strip()
            if line:
                lines.append(line.split())
    head = lines[0][0].decode(errors="replace")
    if not head.endswith("OFF"):
        raise ValueError("not an OFF header: " + head)
    rest = lines[0][1:] if len(lines[0]) > 1 else None
    counts = rest if rest else lines[1]
    first = 1 if rest else 2
    nv, nf = int(counts[0]), int(counts[1])
    points = np.array([[float(x) for x in lines[first + i][:3]] for i in range(nv)])
    triangles = []
    for i in range(nf):
        row = lines[first + nv + i]
        k = int(row[0])
        idx = [int(x) for x in row[1:1 + k]]
        for j in range(1, k - 1):
            triangles.append((idx[0], idx[j], idx[j + 1]))
    return points, np.array(triangles, dtype=np.int64).reshape(-1, 3)


def read_any(path):
    if path.lower().endswith(".off"):
        return read_off(path)
    m = meshio.read(path)
    blocks = [c.data for c in m.cells if c.type == "triangle"]
    if not blocks:
        raise ValueError("no triangles")
    return m.points[:, :3].astype(float), np.vstack(blocks)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True, help="folder for the STL files")
    ap.add_argument("--deb", help="a libcgal-demo .deb already downloaded")
    ap.add_argument("--min-triangles", type=int, default=50)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        deb = args.deb
        if not deb:
            subprocess.run(["apt-get", "download", "libcgal-demo"], cwd=work, check=True)
            deb = glob.glob(os.path.join(work, "libcgal-demo_*.deb"))[0]
        unpacked = os.path.join(work, "deb")
        subprocess.run(["dpkg-deb", "-x", deb, unpacked], check=True)
        data = os.path.join(work, "data")
        os.makedirs(data)
        for archive in glob.glob(os.path.join(unpacked, "usr/share/doc/libcgal-dev/*.tar.gz")):
            with tarfile.open(archive) as tar:
                tar.extractall(data)
        written, skipped = 0, []
        for path in sorted(glob.glob(os.path.join(data, "**", "*"), recursive=True)):
            if not os.path.isfile(path) or not path.lower().endswith((".off", ".obj", ".ply", ".stl")):
                continue
            rel = os.path.relpath(path, data)
            try:
                points, triangles = read_any(path)
                if len(triangles) < args.min_triangles:
                    continue
                if triangles.min() < 0 or triangles.max() >= len(points):
                    raise ValueError("a triangle's index is out of range")
                name = rel.replace("/", "_").rsplit(".", 1)[0] + ".stl"
                meshio.write(os.path.join(args.out, name),
                             meshio.Mesh(points, [("triangle", triangles)]), binary=True)
                written += 1
            except BaseException as e:  # meshio exits on some malformed files
                skipped.append((rel, str(e).splitlines()[0][:80] if str(e) else type(e).__name__))
    for rel, why in skipped:
        print("skipped %s: %s" % (rel, why))
    print("%d meshes written to %s, %d skipped" % (written, args.out, len(skipped)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
