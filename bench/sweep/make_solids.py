#!/usr/bin/python3
"""Deterministic generator of varied closed solids for the robustness sweep (issue 10, part 1).

usage: make_solids.py [--out DIR] [--count N] [--seed S] [--first K] [--special] [--calibration]

Every solid is built with gmsh's OpenCASCADE kernel, surface-meshed at a size h_s
(gmsh.model.mesh.generate(2), General.NumThreads=1), written by gmsh as a binary STL, read back and
checked: closed (every edge in exactly two triangles), one consistent orientation, every
component outward (outer shells enclose positive volume, cavity shells - nesting depth odd -
negative), and the enclosed volume within a few percent of the OCC volume. gmsh's STL writer keeps
each surface's own orientation: faces reversed in the OCC shell (some cut faces, every cavity)
come out the wrong way round. Those triangles are flipped (made consistent per component, then
whole components turned outward) and the file rewritten; "flipped" in the JSON line counts them.

Solid k belongs to family FAMILIES[k % len(FAMILIES)] and is drawn from random.Random(seed, k),
so the first 12*m solids cover every family m times and any prefix is reproducible on its own.

Writes DIR/NAME.stl and one JSON line per solid to DIR/solids.jsonl (name, family, h_s, bbox,
triangles, points, components, volumes, flipped, the parameters drawn). --special also writes
the named cases of the issue (torus_shell, sphere_bore_cavity; the latter kept exactly as gmsh
wrote it); --calibration writes spheres of radius 1 at several h_s (the time reference).
"""
import argparse
import json
import math
import os
import random
import sys

import gmsh
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stl_tools  # noqa: E402

occ = None  # gmsh.model.occ, set per model


def U(rng, a, b):
    return round(rng.uniform(a, b), 4)


def volume_h(rng, volume, lo=300.0, hi=1200.0):
    """An h_s giving volume/h_s^3 in [lo, hi] (about 2500-10000 tets at H = h_s)."""
    n = math.exp(rng.uniform(math.log(lo), math.log(hi)))
    return round((volume / n) ** (1.0 / 3.0), 4)


def total_volume():
    return sum(occ.getMass(3, t) for _, t in occ.getEntities(3))


def fuse_all(dimtags):
    if len(dimtags) < 2:
        return dimtags
    out, _ = occ.fuse(dimtags[:1], dimtags[1:])
    return out


def rand_box(rng, c=(0, 0, 0), lo=0.4, hi=1.2):
    dx, dy, dz = U(rng, lo, hi), U(rng, lo, hi), U(rng, lo, hi)
    x, y, z = c[0] + U(rng, -0.3, 0.3), c[1] + U(rng, -0.3, 0.3), c[2] + U(rng, -0.3, 0.3)
    return (3, occ.addBox(x - dx / 2, y - dy / 2, z - dz / 2, dx, dy, dz)), [x, y, z, dx, dy, dz]


# ---------------------------------------------------------------------------------------------
# families: each builds the OCC model and returns (h_s, params)

def f_box_fuse(rng):
    n = rng.randint(2, 4)
    boxes, ps = [], []
    for _ in range(n):
        b, p = rand_box(rng)
        boxes.append(b)
        ps.append(p)
    fuse_all(boxes)
    occ.synchronize()
    return volume_h(rng, total_volume()), {"boxes": ps}


def f_box_cut(rng):
    base = (3, occ.addBox(0, 0, 0, 1.5, 1.0, 0.8))
    tools, ps = [], []
    for _ in range(rng.randint(1, 3)):
        # a box touching the outside: a corner notch, a slot or a pocket from one face
        dx, dy, dz = U(rng, 0.3, 0.8), U(rng, 0.3, 0.8), U(rng, 0.2, 0.6)
        x = rng.choice([-0.1, 1.5 - dx + 0.1, U(rng, 0.2, 1.5 - dx - 0.2)])
        y = rng.choice([-0.1, 1.0 - dy + 0.1, U(rng, 0.1, max(0.11, 1.0 - dy - 0.1))])
        z = rng.choice([0.8 - dz + 0.01, 0.8 - dz, -0.01, U(rng, 0.0, 0.8 - dz)])
        if z == 0.8 - dz:
            dz += 0.2  # open to the top
        tools.append((3, occ.addBox(x, y, z, dx, dy, dz)))
        ps.append([x, y, z, dx, dy, dz])
    out, _ = occ.cut([base], tools)
    occ.synchronize()
    return volume_h(rng, total_volume()), {"base": [1.5, 1.0, 0.8], "cuts": ps}


def f_cylinder(rng):
    r, h = U(rng, 0.2, 0.7), U(rng, 0.3, 2.0)
    parts = [(3, occ.addCylinder(0, 0, 0, 0, 0, h, r))]
    p = {"r": r, "h": h}
    if rng.random() < 0.5:  # a flange or a base plate
        w = U(rng, 2.2 * r, 3.5 * r)
        t = U(rng, 0.15, 0.4)
        parts.append((3, occ.addBox(-w / 2, -w / 2, -t, w, w, t + 0.05)))
        p["plate"] = [w, t]
    fuse_all(parts)
    occ.synchronize()
    return volume_h(rng, total_volume()), p


def f_cone(rng):
    r1, h = U(rng, 0.3, 0.8), U(rng, 0.5, 1.8)
    r2 = rng.choice([0.0, U(rng, 0.05, 0.6 * r1)])
    parts = [(3, occ.addCone(0, 0, 0, 0, 0, h, r1, r2))]
    p = {"r1": r1, "r2": r2, "h": h}
    if rng.random() < 0.5:  # on a cylinder
        hc = U(rng, 0.2, 0.8)
        parts.append((3, occ.addCylinder(0, 0, -hc, 0, 0, hc + 0.01, r1)))
        p["base_cyl"] = hc
    fuse_all(parts)
    occ.synchronize()
    return volume_h(rng, total_volume()), p


def f_sphere(rng):
    r = U(rng, 0.4, 1.0)
    s = (3, occ.addSphere(0, 0, 0, r))
    kind = rng.choice(["plain", "ellipsoid", "fuse_box", "cut_box", "fuse_sphere"])
    p = {"r": r, "kind": kind}
    if kind == "ellipsoid":
        a, b = U(rng, 0.5, 1.8), U(rng, 0.5, 1.8)
        occ.dilate([s], 0, 0, 0, a, b, 1.0)
        p["scale"] = [a, b]
    elif kind == "fuse_box":
        b, pb = rand_box(rng, c=(r * 0.7, 0, 0), lo=0.3, hi=0.9)
        fuse_all([s, b])
        p["box"] = pb
    elif kind == "cut_box":
        d = U(rng, 0.2, 0.8) * r
        b = (3, occ.addBox(r - d, -r - 1, -r - 1, 2 * r + 2, 2 * r + 2, 2 * r + 2))
        occ.cut([s], [b])
        p["cut_depth"] = d
    elif kind == "fuse_sphere":
        r2 = U(rng, 0.3, 1.0) * r
        dist = U(rng, 0.5, 1.0) * (r + r2)
        fuse_all([s, (3, occ.addSphere(dist, 0, 0, r2))])
        p["second"] = [r2, dist]
    occ.synchronize()
    return volume_h(rng, total_volume()), p


def f_torus(rng):
    R = U(rng, 0.6, 1.2)
    r = U(rng, 0.12, 0.5) * R
    t = (3, occ.addTorus(0, 0, 0, R, r))
    p = {"R": R, "r": r}
    if rng.random() < 0.3:  # two linked or fused tori
        t2 = occ.addTorus(R, 0, 0, R, r)
        occ.rotate([(3, t2)], R, 0, 0, 1, 0, 0, math.pi / 2)
        fuse_all([t, (3, t2)])
        p["linked"] = True
    occ.synchronize()
    h = volume_h(rng, total_volume())
    return min(h, round(0.8 * r, 4)), p


def f_cavity(rng):
    """A solid with a box or sphere cavity: the cavity is a second shell, oriented inward."""
    outer = rng.choice(["box", "sphere", "cylinder"])
    inner = rng.choice(["box", "sphere"])
    p = {"outer": outer, "inner": inner}
    if outer == "box":
        L = [U(rng, 1.0, 1.8), U(rng, 1.0, 1.8), U(rng, 1.0, 1.8)]
        o = (3, occ.addBox(-L[0] / 2, -L[1] / 2, -L[2] / 2, *L))
        half = min(L) / 2
    elif outer == "sphere":
        half = U(rng, 0.6, 1.0)
        o = (3, occ.addSphere(0, 0, 0, half))
        half /= math.sqrt(3) if inner == "box" else 1.0
    else:
        rr, hh = U(rng, 0.6, 1.0), U(rng, 1.2, 2.0)
        o = (3, occ.addCylinder(0, 0, -hh / 2, 0, 0, hh, rr))
        half = min(rr / (math.sqrt(2) if inner == "box" else 1.0), hh / 2)
    frac = U(rng, 0.3, 0.75)
    a = frac * half
    if inner == "box":
        i = (3, occ.addBox(-a, -a * 0.8, -a * 0.9, 2 * a, 1.6 * a, 1.8 * a))
    else:
        i = (3, occ.addSphere(0, 0, 0, a))
    occ.cut([o], [i])
    occ.synchronize()
    wall = (1 - frac) * half
    h = volume_h(rng, total_volume())
    h = min(h, round(wall / 2.0, 4))
    p.update({"inner_half": round(a, 4), "wall": round(wall, 4)})
    return h, p


def f_thin_wall(rng):
    """Walls of about 2-3 elements: a cup, a tube, a plate, a spherical or box shell."""
    kind = rng.choice(["cup", "tube", "plate", "sphere_shell", "box_shell"])
    h = U(rng, 0.04, 0.08)
    k = U(rng, 2.0, 3.0)
    t = round(k * h, 4)
    p = {"kind": kind, "t": t, "t_over_h": k}
    if kind == "cup":
        L, H = U(rng, 0.6, 1.0), U(rng, 0.4, 0.8)
        o = (3, occ.addBox(0, 0, 0, L, L, H))
        i = (3, occ.addBox(t, t, t, L - 2 * t, L - 2 * t, H))
        occ.cut([o], [i])
        p.update({"L": L, "H": H})
    elif kind == "tube":
        r, H = U(rng, 0.3, 0.6), U(rng, 0.4, 1.0)
        o = (3, occ.addCylinder(0, 0, 0, 0, 0, H, r))
        i = (3, occ.addCylinder(0, 0, -0.1, 0, 0, H + 0.2, r - t))
        occ.cut([o], [i])
        p.update({"r": r, "H": H})
    elif kind == "plate":
        L, W = U(rng, 0.8, 1.5), U(rng, 0.5, 1.0)
        occ.addBox(0, 0, 0, L, W, t)
        p.update({"L": L, "W": W})
    elif kind == "sphere_shell":
        r = U(rng, 0.35, 0.6)
        o = (3, occ.addSphere(0, 0, 0, r))
        i = (3, occ.addSphere(0, 0, 0, r - t))
        occ.cut([o], [i])
        p.update({"r": r})
    else:
        L = U(rng, 0.5, 0.8)
        o = (3, occ.addBox(0, 0, 0, L, L, L))
        i = (3, occ.addBox(t, t, t, L - 2 * t, L - 2 * t, L - 2 * t))
        occ.cut([o], [i])
        p.update({"L": L})
    occ.synchronize()
    return h, p


def f_curvature(rng):
    """Features only 1-2 elements across: pins, thin tori, small fillets, sharp cone tips."""
    kind = rng.choice(["pin", "thin_torus", "fillet", "needle", "ring_groove"])
    p = {"kind": kind}
    h = U(rng, 0.05, 0.1)
    if kind == "pin":
        r = U(rng, 0.8, 2.0) * h
        b = (3, occ.addBox(-0.5, -0.5, -0.3, 1.0, 1.0, 0.3))
        pins = [(3, occ.addCylinder(U(rng, -0.3, 0.3), U(rng, -0.3, 0.3), -0.01, 0, 0, U(rng, 0.3, 0.7), r))
                for _ in range(rng.randint(1, 3))]
        fuse_all([b] + pins)
        p["r_over_h"] = round(r / h, 3)
    elif kind == "thin_torus":
        r = U(rng, 1.0, 2.0) * h
        occ.addTorus(0, 0, 0, U(rng, 0.4, 0.8), r)
        p["r_over_h"] = round(r / h, 3)
    elif kind == "fillet":
        L = [U(rng, 0.6, 1.2), U(rng, 0.6, 1.2), U(rng, 0.4, 0.8)]
        b = occ.addBox(0, 0, 0, *L)
        occ.synchronize()
        rf = U(rng, 0.5, 1.5) * h
        occ.fillet([b], [c for _, c in occ.getEntities(1)], [rf])
        p["fillet_over_h"] = round(rf / h, 3)
    elif kind == "needle":
        r1, hh = U(rng, 0.15, 0.3), U(rng, 0.8, 1.5)
        c = (3, occ.addCone(0, 0, 0, 0, 0, hh, r1, 0.0))
        s = (3, occ.addCylinder(0, 0, -0.3, 0, 0, 0.31, r1))
        fuse_all([c, s])
        p.update({"r1": r1, "h": hh})
    else:  # a shaft with a narrow groove
        r, H = U(rng, 0.3, 0.5), U(rng, 0.8, 1.4)
        s = (3, occ.addCylinder(0, 0, 0, 0, 0, H, r))
        g = U(rng, 1.0, 2.0) * h
        ring = (3, occ.addTorus(0, 0, H / 2, r, g))
        occ.cut([s], [ring])
        p["groove_over_h"] = round(g / h, 3)
    occ.synchronize()
    return h, p


def f_through_hole(rng):
    kind = rng.choice(["plate_holes", "block_bore", "block_square_hole", "cross_bores"])
    p = {"kind": kind}
    if kind == "plate_holes":
        L, W, T = U(rng, 1.0, 2.0), U(rng, 0.6, 1.2), U(rng, 0.2, 0.5)
        b = (3, occ.addBox(0, 0, 0, L, W, T))
        holes = []
        for j in range(rng.randint(1, 4)):
            r = U(rng, 0.06, 0.2)
            x = (j + 0.5) * L / 4.2 + 0.05
            holes.append((3, occ.addCylinder(x, W / 2 + U(rng, -0.1, 0.1), -0.1, 0, 0, T + 0.2, r)))
        occ.cut([b], holes)
        p.update({"L": L, "W": W, "T": T, "holes": len(holes)})
    elif kind == "block_bore":
        L = U(rng, 0.8, 1.5)
        r = U(rng, 0.1, 0.35) * L
        b = (3, occ.addBox(-L / 2, -L / 2, -L / 2, L, L, L))
        c = (3, occ.addCylinder(0, 0, -L, 0, 0, 2 * L, r))
        occ.cut([b], [c])
        p.update({"L": L, "r": r})
    elif kind == "block_square_hole":
        L = U(rng, 0.8, 1.5)
        a = U(rng, 0.2, 0.5) * L
        b = (3, occ.addBox(-L / 2, -L / 2, -L / 2, L, L, L))
        c = (3, occ.addBox(-a / 2, -a / 2, -L, a, a, 2 * L))
        occ.cut([b], [c])
        p.update({"L": L, "a": a})
    else:
        L = U(rng, 0.8, 1.5)
        r = U(rng, 0.1, 0.25) * L
        b = (3, occ.addBox(-L / 2, -L / 2, -L / 2, L, L, L))
        c1 = (3, occ.addCylinder(0, 0, -L, 0, 0, 2 * L, r))
        c2 = (3, occ.addCylinder(-L, 0, 0, 2 * L, 0, 0, r * U(rng, 0.6, 1.0)))
        occ.cut([b], [c1, c2])
        p.update({"L": L, "r": r})
    occ.synchronize()
    return volume_h(rng, total_volume()), p


def f_disjoint(rng):
    n = rng.randint(2, 4)
    x = 0.0
    kinds = []
    h = U(rng, 0.035, 0.06)
    gap_over_h = U(rng, 1.5, 5.0)
    for _ in range(n):
        kind = rng.choice(["box", "sphere", "cylinder", "torus"])
        s = U(rng, 0.3, 0.6)
        if kind == "box":
            occ.addBox(x, -s / 2, -s / 2, s, s, s)
            w = s
        elif kind == "sphere":
            occ.addSphere(x + s / 2, 0, 0, s / 2)
            w = s
        elif kind == "cylinder":
            occ.addCylinder(x, 0, 0, s, 0, 0, s / 3)
            w = s
        else:
            occ.addTorus(x + s / 2, 0, 0, s / 2 - s / 6, s / 6)
            w = s
        kinds.append(kind)
        x += w + gap_over_h * h
    occ.synchronize()
    return h, {"bodies": kinds, "gap_over_h": gap_over_h}


def f_mixed(rng):
    """Random CSG: a base primitive, 2-4 more fused or cut."""
    def prim():
        k = rng.choice(["box", "sphere", "cylinder", "cone", "torus"])
        c = [U(rng, -0.4, 0.4) for _ in range(3)]
        if k == "box":
            d = [U(rng, 0.3, 0.9) for _ in range(3)]
            return k, (3, occ.addBox(c[0] - d[0] / 2, c[1] - d[1] / 2, c[2] - d[2] / 2, *d))
        if k == "sphere":
            return k, (3, occ.addSphere(*c, U(rng, 0.2, 0.5)))
        ax = [0, 0, 0]
        ax[rng.randint(0, 2)] = U(rng, 0.5, 1.2)
        if k == "cylinder":
            return k, (3, occ.addCylinder(*c, *ax, U(rng, 0.1, 0.35)))
        if k == "cone":
            return k, (3, occ.addCone(*c, *ax, U(rng, 0.2, 0.4), U(rng, 0.0, 0.15)))
        return k, (3, occ.addTorus(*c, U(rng, 0.3, 0.5), U(rng, 0.08, 0.15)))
    k0, cur = prim()
    ops = [k0]
    cur = [cur]
    for _ in range(rng.randint(2, 4)):
        k, t = prim()
        if rng.random() < 0.6:
            out, _ = occ.fuse(cur, [t])
            ops.append("+" + k)
        else:
            out, _ = occ.cut(cur, [t])
            ops.append("-" + k)
        cur = out if out else cur
        if not out:
            break
    occ.synchronize()
    return volume_h(rng, max(total_volume(), 1e-6)), {"ops": ops}


FAMILIES = [
    ("box_fuse", f_box_fuse), ("box_cut", f_box_cut), ("cylinder", f_cylinder), ("cone", f_cone),
    ("sphere", f_sphere), ("torus", f_torus), ("cavity", f_cavity), ("thin_wall", f_thin_wall),
    ("curvature", f_curvature), ("through_hole", f_through_hole), ("disjoint", f_disjoint),
    ("mixed", f_mixed),
]


# ---------------------------------------------------------------------------------------------
# named cases of the issue

def s_torus_shell(rng):
    o = (3, occ.addTorus(0, 0, 0, 1.0, 0.35))
    i = (3, occ.addTorus(0, 0, 0, 1.0, 0.15))
    occ.cut([o], [i])
    occ.synchronize()
    return 0.05, {"R": 1.0, "r_outer": 0.35, "r_inner": 0.15}


def s_sphere_bore_cavity(rng):
    s = (3, occ.addSphere(0, 0, 0, 1.0))
    bore = (3, occ.addCylinder(0, 0, -1.5, 0, 0, 3.0, 0.25))
    cav = (3, occ.addBox(0.45, -0.2, -0.2, 0.3, 0.4, 0.4))
    occ.cut([s], [bore, cav])
    occ.synchronize()
    return 0.1, {"r": 1.0, "bore_r": 0.25, "cavity_box": [0.45, -0.2, -0.2, 0.3, 0.4, 0.4]}


SPECIAL = [("torus_shell", s_torus_shell, False), ("sphere_bore_cavity", s_sphere_bore_cavity, True)]


def make(name, family, builder, rng, out_dir, keep_raw=False, h_override=None):
    """Builds, meshes, writes and checks one solid; returns its JSON record."""
    global occ
    gmsh.model.add(name)
    occ = gmsh.model.occ
    h, params = builder(rng)
    if h_override:
        h = h_override
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    occ_volume = total_volume()
    gmsh.model.mesh.generate(2)
    path = os.path.join(out_dir, name + ".stl")
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(path)
    gmsh.model.remove()
    points, tris = stl_tools.read_stl(path)
    facts = stl_tools.check_surface(points, tris)
    flipped, comps_flipped = 0, 0
    gmsh_consistent, gmsh_outward = facts["consistently_oriented"], facts["outward"]
    if not (gmsh_consistent and gmsh_outward) and not keep_raw:
        raw = tris
        tris, _, comps_flipped = stl_tools.orient(points, tris, facts)
        flipped = int(np.sum(np.any(tris != raw, axis=1)))  # triangles written the other way round
        stl_tools.write_stl(path, points, tris, header=b"gmsh OCC, components reoriented by make_solids.py")
        facts = stl_tools.check_surface(points, tris)
    lo, hi = points.min(axis=0), points.max(axis=0)
    rec = {
        "name": name, "family": family, "stl": path, "h_s": h,
        "bbox": [round(float(v), 6) for v in list(lo) + list(hi)],
        "diag": round(float(math.dist(lo, hi)), 6),
        "points": int(len(points)), "triangles": int(len(tris)),
        "components": len(facts["components"]),
        "cavities": sum(1 for c in facts["components"] if c["depth"] % 2 == 1),
        "closed": facts["closed"], "oriented": facts["consistently_oriented"], "outward": facts["outward"],
        "flipped": flipped, "components_flipped": comps_flipped, "gmsh_consistent": gmsh_consistent,
        "gmsh_outward": gmsh_outward, "volume": round(facts["volume"], 6), "occ_volume": round(occ_volume, 6),
        "volume_error": round(abs(facts["volume"] - occ_volume) / max(occ_volume, 1e-12), 5),
        "mean_edge": round(facts["mean_edge"], 6), "min_edge": round(facts["min_edge"], 6),
        "v_over_h3": round(occ_volume / h ** 3, 1), "params": params,
    }
    return rec


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="/work/sweep-out/solids")
    ap.add_argument("--count", type=int, default=216)
    ap.add_argument("--first", type=int, default=0, help="index of the first solid")
    ap.add_argument("--seed", type=int, default=10)
    ap.add_argument("--special", action="store_true", help="only the named cases of the issue")
    ap.add_argument("--calibration", action="store_true", help="only the reference spheres")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    jobs = []
    if args.special:
        jobs = [(n, "special", b, random.Random(0), raw, None) for n, b, raw in SPECIAL]
        index = "special.jsonl"
    elif args.calibration:
        def sphere(rng):
            occ.addSphere(0, 0, 0, 1.0)
            occ.synchronize()
            return 0.1, {"r": 1.0}
        for h in (0.25, 0.18, 0.13, 0.1, 0.08, 0.065, 0.05, 0.04):
            jobs.append((f"ref_sphere_h{h:g}", "reference", sphere, random.Random(0), False, h))
        index = "calibration.jsonl"
    else:
        for k in range(args.first, args.first + args.count):
            fam, builder = FAMILIES[k % len(FAMILIES)]
            jobs.append((f"s{k:03d}_{fam}", fam, builder, random.Random(args.seed * 1_000_003 + k), False, None))
        index = "solids.jsonl"
    mode = "a" if (args.first > 0 and not args.special and not args.calibration) else "w"
    bad = 0
    with open(os.path.join(args.out, index), mode) as f:
        for name, fam, builder, rng, raw, hov in jobs:
            rec = None
            for attempt in range(3):  # an OCC boolean that throws: redraw (deterministically)
                try:
                    rec = make(name, fam, builder, rng, args.out, keep_raw=raw, h_override=hov)
                    rec["attempt"] = attempt
                    break
                except Exception as e:
                    gmsh.model.remove()
                    print(f"{name}: attempt {attempt} failed to build: {e}", file=sys.stderr)
                    rng = random.Random(rng.random())
            if rec is None:
                bad += 1
                continue
            ok = rec["closed"] and rec["oriented"] and rec["outward"] and rec["volume_error"] < 0.06
            if not ok:
                bad += 1
            f.write(json.dumps(rec) + "\n")
            f.flush()
            print(f"{name:28s} h_s={rec['h_s']:<7g} tris={rec['triangles']:<6d} comps={rec['components']} "
                  f"cav={rec['cavities']} flipped={rec['flipped']}/{rec['components_flipped']}c V/h^3={rec['v_over_h3']:<7g} "
                  f"dV={rec['volume_error']:.4f} {'ok' if ok else 'CHECK'}")
    gmsh.finalize()
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
