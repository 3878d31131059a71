#!/usr/bin/python3
"""Primitives tessellated as STL exporters write them, for the sweep's "exporters" group.

usage: make_exporter_shapes.py [--out DIR]

Writes binary STL files and exporters.jsonl (one line per file: name, family, stl, triangles,
parameters) into DIR (default /work/sweep-out/solids, beside the generated solids):
  uv_sphere  latitude-longitude spheres of radius 10, `around` points per ring and `rings` rings
             between two poles: bands of quads whose four points are coplanar but for rounding,
             split in two, and poles that are fans of needles (under 5 degrees from 72 around);
  cylinder   radius 1, height 1 (or `height`), caps fanned to their centres, `layers` bands
             of quads on the side (in float, each side quad is exactly planar);
  cone       radius 1, height 2, a fan of needles at the tip, `rings` bands, the base fanned to
             its centre;
  uv_torus   radii 3 and `minor`, a grid of `around` x `across` quads.
libcgal-demo's sphere966.stl (44 around, 21 rings) stopped at its mean edge until c42d0f7, and
spheres of 72 or more around until 6549085; cylinders of 40-128 round, 2-6 layers, heights 1
and 0.5 stopped under their mean edge more often than not (bench/sweep/README.md).
Deterministic; needs numpy.
"""

import argparse
import json
import math
import os

import numpy as np

import stl_tools


def circle(r, z, n):
    return [(r * math.cos(2 * math.pi * j / n), r * math.sin(2 * math.pi * j / n), z)
            for j in range(n)]


def uv_sphere(around, rings, radius=10.0):
    pts = [(0.0, 0.0, radius)]
    for i in range(1, rings + 1):
        theta = math.pi * i / (rings + 1)
        pts += circle(radius * math.sin(theta), radius * math.cos(theta), around)
    south = len(pts)
    pts.append((0.0, 0.0, -radius))
    ring = lambda i, j: 1 + (i - 1) * around + j % around
    tris = [(0, ring(1, j), ring(1, j + 1)) for j in range(around)]
    for i in range(1, rings):
        for j in range(around):
            a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    tris += [(south, ring(rings, j + 1), ring(rings, j)) for j in range(around)]
    return pts, tris


def bands_with_fans(radii_z, around, top_apex, bottom_centre):
    """Circles (r, z) from top to bottom, the top closed by a fan to `top_apex` (x, y, z), the
    bottom by a fan to `bottom_centre`; outward when the circles run from high z to low."""
    pts = [top_apex]
    for r, z in radii_z:
        pts += circle(r, z, around)
    bottom = len(pts)
    pts.append(bottom_centre)
    ring = lambda i, j: 1 + i * around + j % around
    tris = [(0, ring(0, j), ring(0, j + 1)) for j in range(around)]
    for i in range(len(radii_z) - 1):
        for j in range(around):
            a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    last = len(radii_z) - 1
    tris += [(bottom, ring(last, j + 1), ring(last, j)) for j in range(around)]
    return pts, tris


def cylinder(around, layers, height=1.0):
    circles = [(1.0, height * (1 - k / layers)) for k in range(layers + 1)]
    return bands_with_fans(circles, around, (0.0, 0.0, height), (0.0, 0.0, 0.0))


def cone(around, rings, height=2.0):
    circles = [(k / rings, height * (1 - k / rings)) for k in range(1, rings + 1)]
    return bands_with_fans(circles, around, (0.0, 0.0, height), (0.0, 0.0, 0.0))


def uv_torus(around, across, minor, major=3.0):
    pts = []
    for i in range(around):
        u = 2 * math.pi * i / around
        for j in range(across):
            v = 2 * math.pi * j / across
            w = major + minor * math.cos(v)
            pts.append((w * math.cos(u), w * math.sin(u), minor * math.sin(v)))
    at = lambda i, j: (i % around) * across + j % across
    tris = []
    for i in range(around):
        for j in range(across):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    return pts, tris


SHAPES = (
    [(f"uv_sphere_{a}_{r}", "uv_sphere", uv_sphere, {"around": a, "rings": r})
     for a in (32, 44, 64, 72, 96, 128) for r in (15, 21, 31, 47)]
    + [(f"cylinder_{a}_{l}", "cylinder", cylinder, {"around": a, "layers": l})
       for a in (32, 48, 96) for l in (1, 4)]
    + [(f"cylinder_{a}_{l}_h{h}", "cylinder", cylinder, {"around": a, "layers": l, "height": h})
       for a in (40, 64, 80, 112, 128) for l in (2, 6) for h in (1.0, 0.5)]
    + [(f"cone_{a}_{r}", "cone", cone, {"around": a, "rings": r})
       for a in (32, 64, 96) for r in (1, 4)]
    + [(f"uv_torus_{a}_{c}", "uv_torus", uv_torus, {"around": a, "across": c, "minor": m})
       for a, c, m in ((48, 16, 0.5), (64, 32, 1.0), (128, 24, 1.0))]
)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="/work/sweep-out/solids")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "exporters.jsonl"), "w") as index:
        for name, family, build, params in SHAPES:
            pts, tris = build(**params)
            pts, tris = np.array(pts, dtype=float), np.array(tris, dtype=np.int64)
            assert stl_tools.signed_volume(pts, tris) > 0, name  # outward
            path = os.path.join(args.out, name + ".stl")
            stl_tools.write_stl(path, pts, tris)
            index.write(json.dumps({"name": name, "family": family, "stl": path,
                                    "triangles": int(len(tris)), "parameters": params}) + "\n")
    print(f"{len(SHAPES)} shapes in {args.out}")


if __name__ == "__main__":
    main()
