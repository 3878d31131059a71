"""Small STL helpers shared by make_solids.py and run_sweep.py (numpy only).

read_stl      ascii or binary STL -> (points, triangles) with exactly equal vertices merged
write_stl     binary STL
check_surface closedness, manifoldness, components, per-component signed volume and nesting depth,
              and whether the orientation is outward (outer shells positive, cavities negative)
orient        flips whole components so that the surface is outward-oriented
"""
import struct

import numpy as np


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    tris = None
    if len(data) >= 84:
        n = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * n == len(data):
            rec = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                                count=n, offset=84)
            tris = rec["v"].astype(np.float64)
    if tris is None:
        vals = []
        for line in data.decode("ascii", "replace").splitlines():
            w = line.split()
            if len(w) == 4 and w[0] == "vertex":
                vals.append([float(w[1]), float(w[2]), float(w[3])])
        tris = np.asarray(vals, dtype=np.float64).reshape(-1, 3, 3)
    flat = tris.reshape(-1, 3)
    points, inverse = np.unique(flat, axis=0, return_inverse=True)
    return points, inverse.reshape(-1, 3).astype(np.int64)


def write_stl(path, points, tris, header=b"afmesh sweep"):
    tris = np.asarray(tris, dtype=np.int64)
    a, b, c = (points[tris[:, i]] for i in range(3))
    n = np.cross(b - a, c - a)
    ln = np.linalg.norm(n, axis=1, keepdims=True)
    n = n / np.where(ln > 0, ln, 1.0)
    rec = np.zeros(len(tris), dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["n"] = n
    rec["v"] = np.stack([a, b, c], axis=1)
    with open(path, "wb") as f:
        f.write(header.ljust(80, b" ")[:80])
        f.write(struct.pack("<I", len(tris)))
        f.write(rec.tobytes())


def signed_volume(points, tris):
    a, b, c = (points[tris[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def components(tris):
    """Connected components of triangles through shared edges (a label per triangle)."""
    n = len(tris)
    parent = np.arange(n)

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(n), 3)
    order = np.lexsort((e[:, 1], e[:, 0]))
    e, owner = e[order], owner[order]
    same = np.all(e[1:] == e[:-1], axis=1)
    for i in np.nonzero(same)[0]:
        ra, rb = find(owner[i]), find(owner[i + 1])
        if ra != rb:
            parent[ra] = rb
    roots = np.array([find(i) for i in range(n)])
    _, label = np.unique(roots, return_inverse=True)
    return label


def winding_number(points, tris, q):
    """Generalised winding number of the closed surface (points, tris) at the query point q."""
    a, b, c = (points[tris[:, i]] - q for i in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    num = np.einsum("ij,ij->i", a, np.cross(b, c))
    den = la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la + \
        np.einsum("ij,ij->i", c, a) * lb
    return float(2.0 * np.arctan2(num, den).sum() / (4.0 * np.pi))


def check_surface(points, tris):
    """Facts about a triangulated surface: dict with closed, nonmanifold_edges, components, and per
    component its signed volume, nesting depth and whether its orientation is outward."""
    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    # directed edges: in a consistently oriented closed manifold each directed edge occurs once
    d = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    _, dcounts = np.unique(d, axis=0, return_counts=True)
    label = components(tris)
    ncomp = int(label.max()) + 1 if len(label) else 0
    comps = []
    for k in range(ncomp):
        t = tris[label == k]
        comps.append({"triangles": int(len(t)), "volume": signed_volume(points, t)})
    for k in range(ncomp):
        probe = points[tris[label == k][0]].mean(axis=0)
        depth = 0
        for j in range(ncomp):
            if j != k and abs(winding_number(points, tris[label == j], probe)) > 0.5:
                depth += 1
        comps[k]["depth"] = depth
        want_positive = depth % 2 == 0
        comps[k]["outward"] = (comps[k]["volume"] > 0) == want_positive
    edges = np.linalg.norm(points[e[:, 0]] - points[e[:, 1]], axis=1)
    return {
        "closed": bool(np.all(counts == 2)),
        "nonmanifold_edges": int(np.sum(counts > 2)),
        "boundary_edges": int(np.sum(counts == 1)),
        "consistently_oriented": bool(np.all(dcounts == 1)),
        "components": comps,
        "outward": all(c["outward"] for c in comps),
        "volume": signed_volume(points, tris),
        "mean_edge": float(edges.mean()) if len(edges) else 0.0,
        "min_edge": float(edges.min()) if len(edges) else 0.0,
    }


def make_consistent(tris):
    """Flips triangles so that each edge-connected component of a closed manifold surface is
    consistently oriented (breadth-first from its first triangle); (tris, flipped count)."""
    tris = tris.copy()
    n = len(tris)
    edge_owners = {}
    for i, (a, b, c) in enumerate(tris.tolist()):
        for u, v in ((a, b), (b, c), (c, a)):
            edge_owners.setdefault((min(u, v), max(u, v)), []).append(i)
    seen = np.zeros(n, dtype=bool)
    flipped = 0
    for start in range(n):
        if seen[start]:
            continue
        seen[start] = True
        queue = [start]
        while queue:
            i = queue.pop()
            a, b, c = tris[i].tolist()
            for u, v in ((a, b), (b, c), (c, a)):
                for j in edge_owners[(min(u, v), max(u, v))]:
                    if j == i or seen[j]:
                        continue
                    x, y, z = tris[j].tolist()
                    if (u, v) in ((x, y), (y, z), (z, x)):  # same direction: j is the wrong way round
                        tris[j] = [x, z, y]
                        flipped += 1
                    seen[j] = True
                    queue.append(j)
    return tris, flipped


def orient(points, tris, facts=None):
    """The triangles made consistent within each component and every wrongly oriented component
    flipped, so that the surface is outward; (tris, triangles flipped, components flipped)."""
    tris, flipped = make_consistent(tris)
    facts = check_surface(points, tris)
    label = components(tris)
    comps = 0
    for k, c in enumerate(facts["components"]):
        if not c["outward"]:
            sel = label == k
            tris[sel] = tris[sel][:, [0, 2, 1]]
            flipped += int(sel.sum())
            comps += 1
    return tris, flipped, comps
