#!/usr/bin/python3
"""Geometric features of the swept surfaces, joined with the sweep results, to see what the failing
solids have in common.

usage: features.py [--solids DIR] [--results FILE] [--out FILE]

Per solid (from its STL and h_s): min_edge/h_s and the number of edges shorter than h_s/4
(steps and slivers left by booleans); the smallest triangle angle; the sharpest dihedral angle
between two triangles sharing an edge (0 = a knife edge, 180 = flat); the number of reflex
(concave) edges; gap = the smallest distance from a vertex to a triangle not touching it, divided
by the mean length of the edges at that vertex (about 0.8 on a flat regular mesh, small at a thin
step, a slot or two nearly touching bodies). Writes one JSON line per solid to --out and prints,
for every feature, its median over the solids whose runs all passed and over those with a failure.
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stl_tools  # noqa: E402


def point_triangle_distance(p, a, b, c):
    """Distances from the point p to the triangles (a, b, c) (arrays N x 3), Ericson 5.1.5."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    denom = va + vb + vc
    denom = np.where(np.abs(denom) > 1e-300, denom, 1e-300)
    v = vb / denom
    w = vc / denom
    q = a + ab * v[:, None] + ac * w[:, None]  # interior
    # regions (later assignments win over earlier ones, so go from the general to the special)
    m = (vb <= 0) & (d2 - d6 >= 0) & (d6 - d5 <= 0) | False
    with np.errstate(divide="ignore", invalid="ignore"):
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
        q = np.where(m[:, None], b + (c - b) * t_bc[:, None], q)
        t_ac = d2 / (d2 - d6)
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        q = np.where(m[:, None], a + ac * t_ac[:, None], q)
        t_ab = d1 / (d1 - d3)
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        q = np.where(m[:, None], a + ab * t_ab[:, None], q)
    q = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, q)
    return np.linalg.norm(p - q, axis=1)


def features(points, tris, h):
    a, b, c = (points[tris[:, i]] for i in range(3))
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1, keepdims=True)

    def ang(x, y, z):
        u, v = y - x, z - x
        cs = np.einsum("ij,ij->i", u, v) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
        return np.degrees(np.arccos(np.clip(cs, -1, 1)))
    min_angle = float(np.minimum(np.minimum(ang(a, b, c), ang(b, c, a)), ang(c, a, b)).min())
    # edges and the dihedral angle between their two triangles
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    opp = np.concatenate([tris[:, 2], tris[:, 0], tris[:, 1]])
    owner = np.tile(np.arange(len(tris)), 3)
    key = np.sort(e, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, owner, opp, e = key[order], owner[order], opp[order], e[order]
    first = np.nonzero(np.all(key[1:] == key[:-1], axis=1))[0]
    t1, t2 = owner[first], owner[first + 1]
    cosang = np.clip(np.einsum("ij,ij->i", n[t1], n[t2]), -1, 1)
    # interior dihedral angle: 180 - angle between normals, reflex when the opposite vertex of t2
    # lies above t1's plane
    above = np.einsum("ij,ij->i", points[opp[first + 1]] - points[key[first, 0]], n[t1]) > 1e-12 * h
    turn = np.degrees(np.arccos(cosang))
    interior = np.where(above, 180 + turn, 180 - turn)
    sharp = float(interior.min())
    reflex = int(np.sum(interior > 181))
    lengths = np.linalg.norm(points[key[first, 0]] - points[key[first, 1]], axis=1)
    # gap: per vertex, distance to the nearest triangle not touching it / its mean edge length
    vsum = np.zeros(len(points))
    vcnt = np.zeros(len(points))
    for j in (0, 1):
        np.add.at(vsum, key[first, j], lengths)
        np.add.at(vcnt, key[first, j], 1)
    vmean = vsum / np.maximum(vcnt, 1)
    gap = np.inf
    lo, hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)
    for v in range(len(points)):
        p = points[v]
        r = 2.0 * vmean[v]
        cand = np.nonzero(np.all(lo <= p + r, axis=1) & np.all(hi >= p - r, axis=1) & np.all(tris != v, axis=1))[0]
        if len(cand) == 0:
            continue
        d = point_triangle_distance(p[None, :], a[cand], b[cand], c[cand]).min()
        gap = min(gap, d / vmean[v])
    return {"min_edge_over_h": float(lengths.min() / h), "short_edges": int(np.sum(lengths < 0.25 * h)),
            "min_triangle_angle": min_angle, "sharpest_dihedral": sharp, "reflex_edges": reflex,
            "gap": float(min(gap, 2.0))}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solids", default="/work/sweep-out/solids")
    ap.add_argument("--results", default="/work/sweep-out/results.jsonl")
    ap.add_argument("--out", default="/work/sweep-out/features.jsonl")
    args = ap.parse_args()
    results = {}
    if os.path.exists(args.results):
        for line in open(args.results):
            r = json.loads(line)
            if r["group"] == "solids":
                results.setdefault(r["name"], []).append(r)
    rows = []
    with open(args.out, "w") as f:
        for line in open(os.path.join(args.solids, "solids.jsonl")):
            s = json.loads(line)
            if s["name"] not in results:
                continue
            p, t = stl_tools.read_stl(s["stl"])
            row = {"name": s["name"], "family": s["family"], **features(p, t, s["h_s"])}
            rs = results[s["name"]]
            row["runs"], row["valid"] = len(rs), sum(r["valid"] for r in rs)
            row["causes"] = sorted({r["cause"] for r in rs if not r["valid"]})
            rows.append(row)
            f.write(json.dumps(row) + "\n")
    keys = ["min_edge_over_h", "short_edges", "min_triangle_angle", "sharpest_dihedral", "reflex_edges", "gap"]
    good = [r for r in rows if r["valid"] == r["runs"]]
    bad = [r for r in rows if r["valid"] < r["runs"]]
    print(f"{len(good)} solids with every run valid, {len(bad)} with a failure")
    for k in keys:
        g = np.median([r[k] for r in good]) if good else float("nan")
        b = np.median([r[k] for r in bad]) if bad else float("nan")
        print(f"  {k:20s} median all-valid {g:9.3f}   median failing {b:9.3f}")
    for r in sorted(bad, key=lambda r: r["gap"]):
        print(f"  {r['name']:22s} {r['valid']}/{r['runs']} gap={r['gap']:.3f} min_edge/h={r['min_edge_over_h']:.3f} "
              f"short={r['short_edges']} minang={r['min_triangle_angle']:.1f} sharp={r['sharpest_dihedral']:.1f} "
              f"reflex={r['reflex_edges']} {'; '.join(c[:40] for c in r['causes'])}")


if __name__ == "__main__":
    main()
