#!/usr/bin/python3
"""The surface mesher on every file of the real corpus (issue 11): one line per file, then a
summary line.

Runs `afmesh-bench-surface --input F --json` (default size: the file's mean edge length) on each
file of ../shared/corpus/ (beside the checkout; --corpus DIR), one after the other, each a fresh
process with a timeout. Columns: outcome (valid = the bench's checks pass, open = the input is open
per the corpus README's 'closed' column and the only checks that fail are closed and manifold_edges,
refused = the input was refused before meshing (INVALID_ARGUMENT), stopped = the mesher stopped
(FAILED_PRECONDITION or another error), timeout = killed after --timeout seconds), triangles, cpu s
(user + system of the child, so a loaded machine does not inflate it), wall s, min angle, % of
triangles with smallest angle >= 30 degrees, Hausdorff / bounding-box diagonal, and the first line
of the message when the run did not succeed.

  bench/surface/run_corpus.py [--bench PATH] [--corpus DIR] [--timeout SEC] [--only a,b] [--json]
"""

import argparse
import json
import os
import resource
import subprocess
import sys
import time

SURFACE_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(os.path.dirname(SURFACE_DIR))
DEFAULT_BENCH = os.path.join(REPO_DIR, "build", "release", "bench", "afmesh-bench-surface")
DEFAULT_CORPUS = os.path.join(REPO_DIR, "..", "shared", "corpus")


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
            if r.get("valid"):
                return "valid", r, ""
            failed = set(filter(None, r.get("failed_checks", "").split(",")))
            if name not in closed and failed <= {"closed", "manifold_edges"}:
                return "open", r, ""
            return "stopped", r, "checks failed: " + r.get("failed_checks", "")
    message = text.splitlines()[0] if text else "exit %d, no output" % rc
    outcome = "refused" if "INVALID_ARGUMENT" in message else "stopped"
    return outcome, {}, message


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", default=DEFAULT_BENCH)
    ap.add_argument("--corpus", default=DEFAULT_CORPUS)
    ap.add_argument("--timeout", type=float, default=90.0)
    ap.add_argument("--only", default="", help="comma-separated file stems")
    ap.add_argument("--json", action="store_true", help="one JSON object per file")
    args = ap.parse_args()

    corpus = os.path.abspath(args.corpus)
    closed = closed_files(corpus)
    names = sorted(n for n in os.listdir(corpus) if n.endswith(".stl"))
    if args.only:
        wanted = set(args.only.split(","))
        names = [n for n in names if n[:-4] in wanted]
    counts = {}
    total_cpu = 0.0
    if not args.json:
        print("%-24s %-8s %8s %7s %7s %6s %6s %9s  %s" % (
            "file", "outcome", "tris", "cpu s", "wall s", "min", "%>=30", "H/diag", "message"))
    for name in names:
        rc, out, err, cpu, wall = run_timed(
            [args.bench, "--input", os.path.join(corpus, name), "--json"], args.timeout)
        outcome, r, message = judge(name, closed, rc, out, err)
        counts[outcome] = counts.get(outcome, 0) + 1
        total_cpu += cpu
        if args.json:
            print(json.dumps({"file": name, "outcome": outcome, "cpu_seconds": cpu,
                              "wall_seconds": wall, "message": message, "bench": r}))
        else:
            def cell(key, fmt, scale=1.0):
                return fmt % (r[key] * scale) if key in r else "-"
            # The message names the file and size first; keep what follows.
            short = message.split(": ", 2)[-1] if message.startswith("/") else message
            print("%-24s %-8s %8s %7.2f %7.2f %6s %6s %9s  %s" % (
                name[:-4], outcome, cell("triangles", "%d"), cpu, wall,
                cell("min_angle", "%.1f"), cell("share_at_least_30", "%.1f", 100.0),
                cell("hausdorff_over_diagonal", "%.2e"), short[:160]))
        sys.stdout.flush()
    summary = ", ".join("%s %d" % (k, counts.get(k, 0))
                        for k in ("valid", "open", "refused", "stopped", "timeout"))
    print("summary: %d files: %s; %.1f cpu s" % (len(names), summary, total_cpu))


if __name__ == "__main__":
    main()
