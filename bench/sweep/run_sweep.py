#!/usr/bin/python3
"""Robustness sweep of `afmesh volume` (issue 10, part 1): runs, judges and tabulates.

usage: run_sweep.py [--afmesh BIN] [--out DIR]
                    [--groups calibration,solids,corpus,special,occt,thin,exporters]
                    [--limit N] [--sizes 0.5,1,2,none] [--timeout SEC] [--fresh] [--report-only]
                    [--corpus DIR]

Groups (each run appended as one JSON line to DIR/results.jsonl; a run already there is skipped,
so a sweep can be extended with a larger --limit; --fresh starts over):
  calibration  reference spheres of radius 1 (make_solids.py --calibration), no --size: the
               time a plain solid takes for a given tet count
  solids       the first --limit solids of make_solids.py, at --size f*h_s for every factor f of
               --sizes and once without --size (the CLI default: the mean edge of the input)
  corpus       every file of /work/shared/corpus, no --size and --size diag/25
               (--corpus DIR: every .stl of DIR instead)
  special      the named cases of the issue: the torus shell at 0.06/0.05/0.045 (timeout 120 s)
               and the gmsh-written sphere with a bore and a box cavity, no --size and 0.1
  occt         /usr/share/opencascade/data/stl/{shape,sh1,sh2,TR12J_OCC}.stl at 1x and 0.5x
               their mean edge and with no --size
  exporters    the primitives of make_exporter_shapes.py (exporters.jsonl beside the solids):
               spheres, cylinders, cones and tori as STL exporters tessellate them, with no
               --size and at 0.5x their mean edge
  thin         the thin fronts of `make-thin-examples --variants DIR` (--thin DIR): domes, sails
               and crossing X's of other shapes, each with its family's spec file, with
               --envs tags and --envs auto; judged with `stats --envs tags` and the checker's
               --envs (no tet across a thin gap)

Each run: `nice -n 10 afmesh volume IN -o OUT.msh [--size H] --json --timeout T`, one at a time.
A successful run is followed by `afmesh stats OUT.msh --json` and the independent checker
`check_volume.py OUT.msh IN --json` (on a .mesh made by `afmesh convert` if meshio cannot read
the .msh). A run is valid when the mesher exits 0, stats exits 0 and every check passes.
"""
import argparse
import json
import math
import os
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stl_tools  # noqa: E402

# ../shared beside the checkout (as CI lays it out).
SHARED = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared"))
CHECKER = os.path.join(SHARED, "tools", "check_volume.py")
CORPUS = os.path.join(SHARED, "corpus")
OCCT = "/usr/share/opencascade/data/stl"
PY = "/usr/bin/python3"


def run(cmd, timeout):
    """(rc, stdout, stderr, wall seconds, timed_out); the child runs in its own process group,
    which is killed (by its id) if it outlives timeout."""
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
        timed_out = False
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGTERM)
        try:
            out, err = p.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            out, err = p.communicate()
        timed_out = True
    return p.returncode, out, err, time.monotonic() - t0, timed_out


def error_message(stderr):
    """The error line of the CLI (its last line that is not a warning or a progress line)."""
    lines = [l.strip() for l in re.split(r"[\r\n]+", stderr) if l.strip()]
    errs = [l for l in lines if "warning:" not in l and "note:" not in l]
    msg = errs[-1] if errs else (lines[-1] if lines else "")
    return re.sub(r"^afmesh( volume)?:\s*(error:\s*)?", "", msg)


def cause_of(msg, timed_out):
    """A failure's cause: the message's first words with numbers and paths masked."""
    if timed_out or "did not finish within --timeout" in msg:
        return "timeout"
    m = re.sub(r"/\S+", "PATH", msg)
    m = re.sub(r"[-+]?\d[\d.eE+-]*", "N", m)
    words = re.split(r"\s+", m.split(";")[0].strip())
    return " ".join(words[:9])


def judge(args, group, name, stl, label, size, timeout, extra=None):
    out = os.path.join(args.out, "meshes", f"{group}__{name}__{label}.msh".replace("/", "_"))
    cmd = ["nice", "-n", "10", args.afmesh, "volume", stl, "-o", out, "--json", "--timeout", f"{timeout:g}"]
    if size is not None:
        cmd += ["--size", f"{size:.6g}"]
    cmd += (extra or {}).get("cli_args", [])
    envs = (extra or {}).get("envs_check", False)
    rc, so, se, wall, to = run(cmd, timeout + 20)
    rec = {"group": group, "name": name, "stl": stl, "label": label, "size": size, "rc": rc,
           "wall": round(wall, 3), "timeout": to or (rc == 6 and "did not finish within" in se),
           "cmd": " ".join(cmd[3:])}
    rec.update(extra or {})
    warnings = [l.split("warning:", 1)[1].strip() for l in se.splitlines() if "warning:" in l]
    rec["warnings"] = warnings[:5]
    # The front could not close and the volume was filled from its points instead
    # (core/delaunay/conforming_fill.h): valid, but not the front's mesh.
    rec["filled"] = any("filled by the Delaunay tetrahedralisation" in w for w in warnings)
    if rc == 0:
        try:
            s = json.loads(so)
        except ValueError:
            s = {}
        q = s.get("quality", {})
        val = s.get("validation", {})
        rec.update({"tets": int(s.get("tetCount", 0)), "points": int(s.get("pointCount", 0)),
                    "min_dihedral": q.get("minDihedralDeg"), "server_valid": val.get("passed"),
                    # Away from the boundary's slivers (QualityFigures): what the mesher made
                    # where the input leaves it free; unset fields are 0 in protobuf's JSON.
                    "boundary_slivers": int(q.get("boundarySliverCount", 0)),
                    "tets_away": int(q.get("tetsAwayFromSlivers", 0)),
                    "away_min_dihedral": q.get("minDihedralAwayFromSliversDeg", 0.0),
                    "server_messages": val.get("messages", [])[:3],
                    "repair": s.get("repair", {}),
                    "timings": {t.get("stage"): t.get("seconds") for t in s.get("timings", [])}})
        src, sso, sse, _, _ = run(["nice", "-n", "10", args.afmesh, "stats", out, "--json"]
                                  + (["--envs", "tags"] if envs else []), 120)
        rec["stats_rc"] = src
        try:
            st = json.loads(sso)
            rec["stats_valid"] = st.get("validation", {}).get("valid")
            rec["stats_failed"] = [c["name"] + ": " + c.get("summary", "")[:160] for c in
                                   st.get("validation", {}).get("checks", []) if c.get("outcome") == "failed"]
        except ValueError:
            rec["stats_error"] = (sse or sso).strip()[-300:]
        crc, cso, cse, _, cto = run(["nice", "-n", "10", PY, CHECKER, out, stl, "--json"]
                                    + (["--envs"] if envs else []), 300)
        if crc not in (0, 1) or not cso.strip():
            mesh = out[:-4] + ".mesh"
            run(["nice", "-n", "10", args.afmesh, "convert", out, mesh], 120)
            crc, cso, cse, _, cto = run(["nice", "-n", "10", PY, CHECKER, mesh, stl, "--json"]
                                        + (["--envs"] if envs else []), 300)
            rec["checked_on"] = "mesh"
        repaired = any(int(rec["repair"].get(k, 0)) > 0 for k in ("trianglesReoriented", "trianglesDropped"))
        if repaired:
            # The server re-oriented or dropped input triangles (its warnings say which): the
            # input as given encloses another volume (a cavity facing out counts as solid), so
            # the volume is checked against the repaired front the mesh carries, after the
            # boundary was checked against the input (the checker's boundary test ignores
            # orientation). Its other checks do not depend on the reference surface.
            try:
                c0 = json.loads(cso)
            except ValueError:
                c0 = {}
            ref = out[:-4] + "-front.mesh"
            run([PY, "-c", "import meshio, sys; m = meshio.read(sys.argv[1]); "
                 "meshio.write(sys.argv[2], meshio.Mesh(m.points, [('triangle', m.cells_dict['triangle'])]))",
                 rec.get("checked_on") == "mesh" and out[:-4] + ".mesh" or out, ref], 120)
            crc, cso, cse, _, cto = run(["nice", "-n", "10", PY, CHECKER,
                                         rec.get("checked_on") == "mesh" and out[:-4] + ".mesh" or out, ref, "--json"], 300)
            rec["volume_checked_against"] = "repaired front"
            if os.path.exists(ref):
                os.remove(ref)
            try:
                c1 = json.loads(cso)
                c1["boundary"] = c0.get("boundary", {"pass": False})
                c1["pass"] = all(c1.get(k, {}).get("pass", False) for k in ("positive", "conform", "boundary", "volume"))
                cso = json.dumps(c1)
            except ValueError:
                pass
        try:
            c = json.loads(cso)
            rec["check_pass"] = bool(c.get("pass"))
            rec["check_fail"] = [k for k in ("positive", "conform", "boundary", "volume", "envs") if
                                 not c.get(k, {}).get("pass", True)]
            rec["check"] = {k: c[k] for k in ("positive", "conform", "boundary", "volume") if k in c}
            rec["check_min_dihedral"] = c.get("quality", {}).get("min_dihedral_deg")
        except ValueError:
            rec["check_pass"] = False
            rec["check_fail"] = ["checker: " + (cse.strip().splitlines() or ["no output"])[-1][:200]]
        rec["valid"] = bool(rec["check_pass"] and src == 0)
        if not rec["valid"]:
            rec["cause"] = "invalid mesh: " + ",".join(rec["check_fail"] or [f"stats exit {src}"] + rec.get("stats_failed", [])[:1])
        if not args.keep_meshes:
            for f in (out, out[:-4] + ".mesh"):
                if os.path.exists(f):
                    os.remove(f)
    else:
        rec["message"] = error_message(se) if se.strip() else f"(no stderr; rc={rc})"
        rec["valid"] = False
        rec["cause"] = cause_of(rec["message"], rec["timeout"])
    return rec


def line_of(r):
    if r["rc"] == 0:
        md = r.get("check_min_dihedral")
        rel = r.get("rel_time")
        return (f"{r['group']:11s} {r['name']:28s} {r['label']:>7s} H={r['size'] or 0:<8.4g} rc=0 "
                f"{r['wall']:7.2f}s tets={r.get('tets', 0):<7d} mindih={md if md is None else round(md, 2)} "
                + (f"away={round(r['away_min_dihedral'], 2)}/{r['tets_away']} "
                   if r.get("boundary_slivers") and r.get("tets_away") else "")
                + f"{'VALID' if r['valid'] else 'INVALID ' + ','.join(r.get('check_fail', []))}"
                + (" FILLED" if r.get("filled") else "")
                + (f" t/sphere={rel:.2f}" if rel else ""))
    return (f"{r['group']:11s} {r['name']:28s} {r['label']:>7s} H={r['size'] or 0:<8.4g} rc={r['rc']} "
            f"{r['wall']:7.2f}s {'TIMEOUT ' if r['timeout'] else ''}{r.get('message', '')[:160]}")


def load_jsonl(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [json.loads(l) for l in f if l.strip()]


def plan(args):
    """The runs to do: (group, name, stl, label, size, timeout, extra)."""
    jobs = []
    groups = args.groups.split(",")
    sdir = args.solids
    if "calibration" in groups:
        for s in load_jsonl(os.path.join(sdir, "calibration.jsonl")):
            jobs.append(("calibration", s["name"], s["stl"], "none", None, args.timeout,
                         {"h_s": s["h_s"], "volume": s["occ_volume"]}))
    if "solids" in groups:
        solids = load_jsonl(os.path.join(sdir, "solids.jsonl"))[:args.limit]
        factors = args.sizes.split(",")
        for s in solids:
            for f in factors:
                size = None if f == "none" else float(f) * s["h_s"]
                label = "none" if f == "none" else f"{f}h"
                jobs.append(("solids", s["name"], s["stl"], label, size, args.timeout,
                             {"family": s["family"], "h_s": s["h_s"], "volume": s["occ_volume"],
                              "triangles": s["triangles"], "components": s["components"],
                              "cavities": s["cavities"], "params": s["params"]}))
    if "corpus" in groups:
        for fn in sorted(os.listdir(args.corpus)):
            if not fn.endswith(".stl"):
                continue
            path = os.path.join(args.corpus, fn)
            pts, tris = stl_tools.read_stl(path)
            diag = float(math.dist(pts.min(0), pts.max(0)))
            for label, size in (("none", None), ("diag/25", diag / 25)):
                jobs.append(("corpus", fn[:-4], path, label, size, args.timeout, {"diag": diag}))
    if "special" in groups:
        for s in load_jsonl(os.path.join(sdir, "special.jsonl")):
            if s["name"] == "torus_shell":
                for h in (0.06, 0.05, 0.045):
                    jobs.append(("special", s["name"], s["stl"], f"{h:g}", h, 120, {"h_s": s["h_s"]}))
            else:
                for label, h in (("none", None), ("0.1", 0.1)):
                    jobs.append(("special", s["name"], s["stl"], label, h, args.timeout,
                                 {"h_s": s["h_s"], "outward": s["outward"], "flipped": s["flipped"]}))
    if "thin" in groups:
        # make-thin-examples --variants DIR (tests/environments): the dome, sails and crossing X
        # with other thicknesses, triangulations, boxes, heels and cambers (issue 10, part 6),
        # each with its family's shipped spec and with --envs tags and --envs auto.
        root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
        for v in load_jsonl(os.path.join(args.thin, "thin.jsonl")):
            spec = os.path.join(root, "examples", v["family"], v["family"] + "-sizes.json")
            for envs in ("tags", "auto"):
                jobs.append(("thin", v["name"], v["file"], envs, None, args.timeout,
                             {"cli_args": ["--spec", spec, "--envs", envs], "envs_check": True,
                              "family": v["family"], "parameters": v["parameters"]}))
    if "exporters" in groups:
        # make_exporter_shapes.py: spheres, cylinders, cones and tori as STL exporters tessellate
        # them (fans of needles, bands of coplanar quads), at their mean edge and half of it.
        for s in load_jsonl(os.path.join(sdir, "exporters.jsonl")):
            pts, tris = stl_tools.read_stl(s["stl"])
            me = stl_tools.check_surface(pts, tris)["mean_edge"]
            for label, size in (("none", None), ("0.5me", 0.5 * me)):
                jobs.append(("exporters", s["name"], s["stl"], label, size, args.timeout,
                             {"family": s["family"], "mean_edge": me, "parameters": s["parameters"]}))
    if "occt" in groups:
        for n in ("shape", "sh1", "sh2", "TR12J_OCC"):
            path = os.path.join(OCCT, n + ".stl")
            if not os.path.exists(path):
                continue
            pts, tris = stl_tools.read_stl(path)
            facts = stl_tools.check_surface(pts, tris)
            me = facts["mean_edge"]
            extra = {"mean_edge": me, "closed": facts["closed"], "nonmanifold": facts["nonmanifold_edges"],
                     "boundary_edges": facts["boundary_edges"], "input_triangles": int(len(tris))}
            for label, size in (("none", None), ("1.0me", me), ("0.5me", 0.5 * me)):
                jobs.append(("occt", n, path, label, size, args.timeout, extra))
    return jobs


def refused_as_dirty(r):
    """True for a run the server refused as a bad front (exit 3, the message names the problem)."""
    return r["rc"] == 3 and r.get("message", "").startswith("invalid front")


def reference(results):
    """log-log interpolation of the reference spheres' wall time against their tet count."""
    pts = sorted((r["tets"], r["wall"]) for r in results if r["group"] == "calibration" and r["rc"] == 0)
    if len(pts) < 2:
        return None

    def t_of(n):
        x = math.log(max(n, 1))
        xs = [math.log(a) for a, _ in pts]
        ys = [math.log(b) for _, b in pts]
        i = 0 if x <= xs[0] else (len(xs) - 2 if x >= xs[-1] else max(j for j in range(len(xs) - 1) if xs[j] <= x))
        k = (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i])
        return math.exp(ys[i] + k * (x - xs[i]))
    return t_of


def summarise(results, t_of):
    lines = []
    # tets per unit of volume/H^3 on the valid solids, to estimate the tet count of failed runs
    ks = sorted(r["tets"] / (r["volume"] / r["size"] ** 3) for r in results
                if r["group"] in ("solids", "calibration") and r["rc"] == 0 and r.get("size") and r.get("volume"))
    kmed = ks[len(ks) // 2] if ks else 7.0
    for r in results:
        if r["rc"] == 0 and t_of and r.get("tets"):
            r["rel_time"] = r["wall"] / t_of(r["tets"])
        elif r.get("timeout") and t_of and r.get("size") and r.get("volume"):
            r["est_tets"] = int(kmed * r["volume"] / r["size"] ** 3)
            r["rel_time_lower_bound"] = r["wall"] / t_of(r["est_tets"])
    for group in ("calibration", "solids", "special", "occt", "corpus", "exporters", "thin"):
        rs = [r for r in results if r["group"] == group]
        if not rs:
            continue
        valid = sum(r["valid"] for r in rs)
        to = sum(bool(r["timeout"]) for r in rs)
        # A dirty input (open, non-manifold, self-intersecting) must be refused, naming the
        # problem (issue 10, part 1): exit 3 with "invalid front: ..." is that answer.
        refused = [r for r in rs if refused_as_dirty(r)]
        filled = sum(bool(r.get("filled")) and r["valid"] for r in rs)
        lines.append(f"\n== {group}: {len(rs)} runs, {valid} valid"
                     + (f" ({filled} filled from their points, the front having failed)" if filled else "")
                     + f", {len(rs) - valid} not valid, {to} timeouts"
                     + (f"; of the not valid, {len(refused)} refused as dirty input (exit 3, 'invalid front', "
                        f"at most {max(r['wall'] for r in refused):.1f} s)" if refused else ""))
        causes = {}
        for r in rs:
            if not r["valid"]:
                causes.setdefault(r["cause"], []).append(r)
        for c, lst in sorted(causes.items(), key=lambda kv: -len(kv[1])):
            ex = ", ".join(sorted({f"{x['name']}@{x['label']}" for x in lst})[:4])
            lines.append(f"  {len(lst):4d}  {c[:90]:90s}  e.g. {ex}")
        if group == "solids":
            lines.append("  by size label:   " + "  ".join(
                f"{lab}: {sum(r['valid'] for r in rs if r['label'] == lab)}/{sum(1 for r in rs if r['label'] == lab)}"
                for lab in sorted({r['label'] for r in rs})))
            fams = sorted({r["family"] for r in rs})
            lines.append("  by family:       " + "  ".join(
                f"{f}: {sum(r['valid'] for r in rs if r['family'] == f)}/{sum(1 for r in rs if r['family'] == f)}"
                for f in fams))
        rel = [r for r in rs if r.get("rel_time")]
        if rel:
            worst = max(rel, key=lambda r: r["rel_time"])
            lines.append(f"  longest relative time: {worst['rel_time']:.2f}x a sphere of {worst['tets']} tets "
                         f"({worst['name']}@{worst['label']}, {worst['wall']:.1f} s)")
        ok = [r for r in rs if r["rc"] == 0]
        if ok:
            md = [r["check_min_dihedral"] for r in ok if r.get("check_min_dihedral") is not None]
            lines.append(f"  wall: max {max(r['wall'] for r in rs):.1f} s, sum {sum(r['wall'] for r in rs):.0f} s; "
                         f"min dihedral over valid runs: min {min(md):.2f}°, median {sorted(md)[len(md) // 2]:.2f}°"
                         if md else "")
            # The same away from the boundary's slivers (the server's figures; a run without any
            # counts every tet).
            away = [r["away_min_dihedral"] for r in ok if r.get("valid") and r.get("tets_away")]
            if away:
                lines.append(f"  away from the input's slivers (angle < 20°): min dihedral min {min(away):.2f}°, "
                             f"median {sorted(away)[len(away) // 2]:.2f}°, {sum(a < 18 for a in away)} of "
                             f"{len(away)} runs under 18°")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--afmesh", default="/work/sweep-bin/afmesh")
    ap.add_argument("--solids", default="/work/sweep-out/solids")
    ap.add_argument("--out", default="/work/sweep-out")
    ap.add_argument("--groups", default="calibration,solids,special,occt,corpus")
    ap.add_argument("--limit", type=int, default=60)
    ap.add_argument("--sizes", default="0.5,1,2,none")
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--fresh", action="store_true")
    ap.add_argument("--keep-meshes", action="store_true")
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--thin", default="/work/sweep-out/thin",
                    help="folder of make-thin-examples --variants (thin.jsonl and the fronts)")
    ap.add_argument("--corpus", default=CORPUS,
                    help="folder of the corpus group's .stl files (default: ../shared/corpus beside the checkout)")
    ap.add_argument("--fail-on-invalid", action="store_true",
                    help="exit 1 when a run of this invocation is not valid (for CI)")
    args = ap.parse_args()
    os.makedirs(os.path.join(args.out, "meshes"), exist_ok=True)
    res_path = os.path.join(args.out, "results.jsonl")
    if args.fresh and os.path.exists(res_path):
        os.remove(res_path)
    results = load_jsonl(res_path)
    done = {(r["group"], r["name"], r["label"]) for r in results}
    invalid = 0
    if not args.report_only:
        with open(res_path, "a") as f:
            for group, name, stl, label, size, timeout, extra in plan(args):
                if (group, name, label) in done:
                    continue
                r = judge(args, group, name, stl, label, size, timeout, extra)
                invalid += 0 if r["valid"] else 1
                results.append(r)
                f.write(json.dumps(r) + "\n")
                f.flush()
                print(line_of(r), flush=True)
    t_of = reference(results)
    text = summarise(results, t_of)
    print(text)
    with open(os.path.join(args.out, "summary.txt"), "w") as f:
        f.write("\n".join(line_of(r) for r in results) + "\n" + text + "\n")
    with open(res_path, "w") as f:
        for r in results:
            f.write(json.dumps(r) + "\n")
    if args.fail_on_invalid and invalid:
        print(f"{invalid} run(s) not valid", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
