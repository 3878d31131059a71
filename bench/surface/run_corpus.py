#!/usr/bin/python3
"""The surface mesher on every file of the real corpus (issue 11): one line per file, then a
summary line.

Runs `afmesh-bench-surface --input F --json` (default size: the file's mean edge length) on each
file of ../shared/corpus/ (beside the checkout; --corpus DIR), one after the other, each a fresh
process with a timeout. Columns: outcome (valid = the bench's checks pass, open = the output fails
only checks its input fails too (afmesh-bench-surface's failed_checks_of_input: an open input, holes
touching at a vertex), or the input is open per the corpus README's 'closed' column and the only
checks that fail are closed and manifold_edges,
refused = the input was refused before meshing (INVALID_ARGUMENT), stopped = the mesher stopped
(FAILED_PRECONDITION or another error), timeout = killed after --timeout seconds), triangles, cpu s
(user + system of the child, so a loaded machine does not inflate it), wall s, min angle, % of
triangles with smallest angle >= 30 degrees, the triangles under 15 degrees and how many of them lie
on an input triangle whose own smallest angle is no larger (as "N/K": the input's slivers between
its lines, kept or spanned from line to line), Hausdorff / bounding-box diagonal, and the first
line of the message when the run did not succeed.

With --volume, every file whose surface came out valid and closed is also filled with tets: the
bench writes the surface (--out, Medit .mesh: shortest round-trip doubles), `afmesh volume` meshes
it (its private server; default size: the surface's mean edge length, about the bench's size),
and the independent checker ../shared/tools/check_volume.py (Debian's python3 with meshio and
numpy) judges the tets against that surface. Four columns go before the message: the checker's
verdict (valid, invalid, unchecked when it gave none; or the CLI's exit code, or timeout), the
checker's tets and smallest dihedral angle, and the volume run's wall seconds (CLI and server);
files not filled show "-". --keep DIR keeps the files. Without --volume the output is as before.
--surface-flags passes options to afmesh-bench-surface (e.g. "--wall-sizes 1", the sizes a
volume's front needs across thin walls, or "--curvature-deviation 0.001").

--sizes runs each file at several sizes instead of its mean edge: a comma-separated list of
meK (K times the file's mean edge, which a first run at the default size reports) and d/K (the
bounding-box diagonal over K); each line's file column then reads FILE@SIZE. With
--surface-flags "--curvature-angle 0" the sizes alone bind (the sweep of the 7 December note).

  bench/surface/run_corpus.py [--bench PATH] [--corpus DIR] [--timeout SEC] [--only a,b] [--json]
                              [--volume [--cli PATH] [--check PATH] [--keep DIR]]
                              [--surface-flags "FLAGS"] [--sizes me0.5,me2,d/20,...]
"""

import argparse
import json
import os
import resource
import struct
import subprocess
import sys
import tempfile
import time

SURFACE_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(os.path.dirname(SURFACE_DIR))
DEFAULT_BENCH = os.path.join(REPO_DIR, "build", "release", "bench", "afmesh-bench-surface")
DEFAULT_CORPUS = os.path.join(REPO_DIR, "..", "shared", "corpus")
DEFAULT_CLI = os.path.join(REPO_DIR, "build", "release", "client", "afmesh")
DEFAULT_CHECK = os.path.join(REPO_DIR, "..", "shared", "tools", "check_volume.py")


def closed_files(corpus):
    """Names the corpus README's table marks closed (column 4, 'yes')."""
    closed = set()
    readme = os.path.join(corpus, "README.md")
    if not os.path.exists(readme):
        return closed
    with open(readme) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) >= 4 and cells[0].endswith(".stl") and cells[3] == "yes":
                closed.add(cells[0])
    return closed


def stl_diagonal(path):
    """The length of the bounding box's diagonal of an STL file's vertices (binary or ASCII)."""
    with open(path, "rb") as f:
        data = f.read()
    lo = [float("inf")] * 3
    hi = [float("-inf")] * 3

    def take(x):
        for k in range(3):
            lo[k] = min(lo[k], x[k])
            hi[k] = max(hi[k], x[k])

    count = struct.unpack_from("<I", data, 80)[0] if len(data) >= 84 else 0
    if len(data) == 84 + 50 * count:
        for t in range(count):
            for v in range(3):
                take(struct.unpack_from("<3f", data, 84 + 50 * t + 12 + 12 * v))
    else:
        for line in data.decode("ascii", "replace").splitlines():
            words = line.split()
            if len(words) == 4 and words[0] == "vertex":
                take([float(w) for w in words[1:]])
    return sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5


def sizes_of(args, path):
    """[(tag, size)] for --sizes (None: the bench's default size, the file's mean edge)."""
    if not args.sizes:
        return [("", None)]
    out = []
    mean_edge = None
    for tag in args.sizes.split(","):
        if tag.startswith("me"):
            if mean_edge is None:
                rc, text, _, _, _ = run_timed([args.bench, "--input", path, "--json",
                                               "--curvature-angle", "0"], args.timeout)
                lines = [l for l in text.splitlines() if l.startswith("{")]
                if not lines:
                    continue
                mean_edge = json.loads(lines[0])["size"]
            out.append((tag, float(tag[2:]) * mean_edge))
        elif tag.startswith("d/"):
            out.append((tag, stl_diagonal(path) / float(tag[2:])))
        else:
            raise SystemExit("--sizes: %s is neither meK nor d/K" % tag)
    return out


def run_timed(argv, timeout):
    """Runs argv; returns (rc or None on timeout, stdout, stderr, cpu s of the child, wall s)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        rc = proc.returncode
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        rc = None
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return rc, out, err, cpu, wall


def judge(name, closed, rc, out, err):
    """Outcome, the bench's JSON object (or {}), and the message's first line."""
    if rc is None:
        return "timeout", {}, ""
    text = (out + "\n" + err).strip()
    for line in out.splitlines():
        if line.startswith("{"):
            r = json.loads(line)
            failed = set(filter(None, r.get("failed_checks", "").split(",")))
            if r.get("valid"):
                # The bench's valid: no check failed that the input passes.
                return ("open" if failed else "valid"), r, ""
            if name not in closed and failed <= {"closed", "manifold_edges"}:
                return "open", r, ""
            return "stopped", r, "checks failed: " + r.get("failed_checks", "")
    message = text.splitlines()[0] if text else "exit %d, no output" % rc
    outcome = "refused" if "INVALID_ARGUMENT" in message else "stopped"
    return outcome, {}, message


def run_cli_volume(cli, surface, mesh, timeout, extra=()):
    """`afmesh volume SURFACE -o MESH --json --quiet` (plus `extra` flags): a dict with outcome
    (ok, exit N, timeout), cpu and wall s, and when ok the CLI's tets, boundary triangles, min
    dihedral and % of tets under 20 degrees; otherwise the last line of its message."""
    argv = [cli, "volume", surface, "-o", mesh, "--json", "--quiet", *extra]
    rc, out, err, cpu, wall = run_timed(argv, timeout)
    if rc is None:
        return {"outcome": "timeout", "cpu": cpu, "wall": wall}
    if rc != 0:
        message = err.strip().splitlines()[-1] if err.strip() else ""
        return {"outcome": f"exit {rc}", "message": message, "cpu": cpu, "wall": wall}
    summary = json.loads(out)
    quality = summary.get("quality", {})
    return {"outcome": "ok", "tets": int(summary.get("tetCount", 0)),
            "triangles": int(summary.get("triangleCount", 0)),
            "min_dihedral": quality.get("minDihedralDeg", 0.0),
            "below_20": 100.0 * quality.get("shareBelow20Deg", 0.0), "cpu": cpu, "wall": wall}


def volume_of(args, surface, mesh):
    """--volume for one file: its surface (written by the bench) filled by the CLI into `mesh`
    and judged by the checker. A dict: outcome (valid, invalid, unchecked, exit N, timeout), cpu
    and wall s of the volume run and, when the checker ran, its tets, min dihedral and the
    checks that failed (message)."""
    v = run_cli_volume(args.cli, surface, mesh, args.timeout)
    if v["outcome"] != "ok":
        return v
    rc, out, err, _, _ = run_timed(
        ["/usr/bin/python3", args.check, mesh, surface, "--json"], args.timeout)
    try:
        c = json.loads(out)
    except ValueError:
        return {**v, "outcome": "unchecked",
                "message": (err.strip().splitlines() or ["checker exit %s" % rc])[-1]}
    failed = [k for k in ("positive", "conform", "boundary", "volume") if not c[k]["pass"]]
    return {**v, "outcome": "valid" if c["pass"] else "invalid", "tets": c["tets"],
            "min_dihedral": c["quality"]["min_dihedral_deg"],
            "message": "checks failed: " + ",".join(failed) if failed else ""}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", default=DEFAULT_BENCH)
    ap.add_argument("--corpus", default=DEFAULT_CORPUS)
    ap.add_argument("--timeout", type=float, default=90.0)
    ap.add_argument("--only", default="", help="comma-separated file stems")
    ap.add_argument("--json", action="store_true", help="one JSON object per file")
    ap.add_argument("--volume", action="store_true",
                    help="also fill each valid closed output with tets and check them")
    ap.add_argument("--cli", default=DEFAULT_CLI, help="afmesh CLI for --volume")
    ap.add_argument("--check", default=DEFAULT_CHECK, help="check_volume.py for --volume")
    ap.add_argument("--keep", default="",
                    help="with --volume: keep the surfaces and volume meshes in DIR")
    ap.add_argument("--surface-flags", default="",
                    help="more options for afmesh-bench-surface, one string (e.g. \"--wall-sizes 1\")")
    ap.add_argument("--sizes", default="",
                    help="sizes per file instead of its mean edge: meK (K x mean edge), d/K "
                         "(diagonal / K), comma-separated")
    args = ap.parse_args()
    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
    scratch = None if args.keep or not args.volume else tempfile.TemporaryDirectory()
    work = args.keep or (scratch.name if scratch else "")

    corpus = os.path.abspath(args.corpus)
    closed = closed_files(corpus)
    names = sorted(n for n in os.listdir(corpus) if n.endswith(".stl"))
    if args.only:
        wanted = set(args.only.split(","))
        names = [n for n in names if n[:-4] in wanted]
    counts = {}
    volume_counts = {}
    total_cpu = 0.0
    if not args.json:
        volume_header = "%-9s %8s %7s %7s " % ("volume", "tets", "min dih", "vol s")
        print("%-24s %-8s %8s %7s %7s %6s %6s %9s %9s %s %s" % (
            "file", "outcome", "tris", "cpu s", "wall s", "min", "%>=30", "<15/thin", "H/diag",
            volume_header if args.volume else "", "message"))
    runs = [(name, tag, size) for name in names
            for tag, size in sizes_of(args, os.path.join(corpus, name))]
    for name, tag, size in runs:
        argv = [args.bench, "--input", os.path.join(corpus, name), "--json",
                *args.surface_flags.split()]
        if size is not None:
            argv += ["--size", "%.9g" % size]
        label = name[:-4] + ("@" + tag if tag else "")
        surface = os.path.join(work, label.replace("/", "_") + ".surface.mesh")
        if args.volume:
            argv += ["--out", surface]
        rc, out, err, cpu, wall = run_timed(argv, args.timeout)
        outcome, r, message = judge(name, closed, rc, out, err)
        counts[outcome] = counts.get(outcome, 0) + 1
        total_cpu += cpu
        v = {}
        # Closed: the bench's checks all passed ("closed" is the one it lets an open output fail).
        if args.volume and outcome == "valid" and not r.get("failed_checks"):
            v = volume_of(args, surface,
                          os.path.join(work, label.replace("/", "_") + ".volume.msh"))
            volume_counts[v["outcome"]] = volume_counts.get(v["outcome"], 0) + 1
        if args.json:
            line = {"file": name, "size_tag": tag, "outcome": outcome, "cpu_seconds": cpu,
                    "wall_seconds": wall, "message": message, "bench": r}
            if args.volume:
                line["volume"] = v
            print(json.dumps(line))
        else:
            def cell(key, fmt, scale=1.0):
                return fmt % (r[key] * scale) if key in r else "-"
            # The message names the file and size first; keep what follows.
            short = message.split(": ", 2)[-1] if message.startswith("/") else message
            volume_cells = ""
            if args.volume:
                volume_cells = "%-9s %8s %7s %7s " % (
                    v.get("outcome", "-"), "%d" % v["tets"] if "tets" in v else "-",
                    "%.2f" % v["min_dihedral"] if "min_dihedral" in v else "-",
                    "%.2f" % v["wall"] if "wall" in v else "-")
                short = v.get("message") or short
            thin = ("%d/%d" % (r["under_15"], r["under_15_at_thinner_input"])
                    if "under_15_at_thinner_input" in r else "-")
            print("%-24s %-8s %8s %7.2f %7.2f %6s %6s %9s %9s %s %s" % (
                label, outcome, cell("triangles", "%d"), cpu, wall,
                cell("min_angle", "%.1f"), cell("share_at_least_30", "%.1f", 100.0), thin,
                cell("hausdorff_over_diagonal", "%.2e"), volume_cells, short[:160]))
        sys.stdout.flush()
    summary = ", ".join("%s %d" % (k, counts.get(k, 0))
                        for k in ("valid", "open", "refused", "stopped", "timeout"))
    if args.sizes:
        print("summary: %d runs of %d files: %s; %.1f cpu s" % (
            len(runs), len(names), summary, total_cpu))
    else:
        print("summary: %d files: %s; %.1f cpu s" % (len(names), summary, total_cpu))
    if args.volume:
        meshed = ", ".join("%s %d" % kv for kv in sorted(volume_counts.items()))
        print("volume: %d valid closed surfaces filled: %s" % (
            sum(volume_counts.values()), meshed or "none"))
    if scratch:
        scratch.cleanup()


if __name__ == "__main__":
    main()
