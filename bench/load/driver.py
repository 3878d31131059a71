"""The load loop shared by the load/fault test and the scale-out runs: N client threads send
requests from a mix for a fixed time (or count), while timed events (a replica killed, a drain
started) happen; then the tables of what came back."""
import collections
import random
import threading
import time


class Schedule:
    """The order requests are sent in, shared by every client thread: `once` kinds first, then
    the weighted mix shuffled and repeated, so that every kind comes up early and in proportion
    however short the run."""

    def __init__(self, mix, once, seed):
        cycle = [kind for kind, weight in mix for _ in range(weight)]
        random.Random(seed).shuffle(cycle)
        self._cycle = cycle
        self._pending = list(once)
        self._next = 0
        self._lock = threading.Lock()

    def next(self):
        with self._lock:
            if self._pending:
                return self._pending.pop(0)
            kind = self._cycle[self._next % len(self._cycle)]
            self._next += 1
            return kind


def drive(target, mix, clients, seconds, max_requests, seed, once=(), events=()):
    """Runs `clients` threads sending requests of `mix` (kind, weight) to `target` until
    `seconds` have passed or `max_requests` were started; `events` are (at_seconds, callable)
    run at those times from the start. Returns the Results in the order they ended, and the
    seconds the whole run took (requests started before the end are waited for)."""
    schedule = Schedule(mix, once, seed)
    results = []
    lock = threading.Lock()
    started = [0]
    start = time.monotonic()
    end = start + seconds

    def client(index):
        rng = random.Random(seed * 1000 + index)
        while time.monotonic() < end:
            with lock:
                if started[0] >= max_requests:
                    return
                started[0] += 1
            result = schedule.next().run(target, rng)
            with lock:
                results.append(result)

    def timed(at, action):
        time.sleep(max(0.0, start + at - time.monotonic()))
        action()

    threads = [threading.Thread(target=client, args=(i,)) for i in range(clients)]
    threads += [threading.Thread(target=timed, args=event) for event in events]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return results, time.monotonic() - start


def percentile(values, share):
    """Nearest-rank percentile of `values` (share in [0, 1]); None when empty."""
    if not values:
        return None
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, int(round(share * len(ordered) + 0.5)) - 1))]


def format_counts(counter):
    return ", ".join(f"{code} {n}" for code, n in counter.most_common()) or "-"


def table(header, rows):
    """Plain-text columns, the widths those of the widest cell."""
    widths = [max(len(str(row[i])) for row in [header] + rows) for i in range(len(header))]
    lines = ["  ".join(str(cell).ljust(width) for cell, width in zip(row, widths)).rstrip()
             for row in [header] + rows]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def seconds_cell(value):
    return "-" if value is None else f"{value:.2f}"


def kind_table(results):
    """One row per kind: requests, how many got the expected answer, the codes of every attempt
    (retried ones included), and p50/p99 of the request's whole time (its retries included)."""
    by_kind = collections.OrderedDict()
    for result in sorted(results, key=lambda r: r.kind):
        by_kind.setdefault(result.kind, []).append(result)
    rows = []
    for kind, group in by_kind.items():
        codes = collections.Counter(code for r in group for code in r.codes)
        times = [r.seconds for r in group]
        rows.append([kind, group[0].expected, len(group), sum(r.problem is None for r in group),
                     format_counts(codes), seconds_cell(percentile(times, 0.5)),
                     seconds_cell(percentile(times, 0.99))])
    total = [r.seconds for r in results]
    rows.append(["all", "", len(results), sum(r.problem is None for r in results),
                 format_counts(collections.Counter(c for r in results for c in r.codes)),
                 seconds_cell(percentile(total, 0.5)), seconds_cell(percentile(total, 0.99))])
    return table(["kind", "expected", "requests", "as expected", "codes (every attempt)",
                  "p50 s", "p99 s"], rows)


def mesh_counts(results):
    """Valid requests, and of them how many got the same mesh, none (lost) or another."""
    meshes = collections.Counter(r.mesh for r in results if r.mesh is not None)
    return sum(meshes.values()), meshes["same"], meshes["none"], meshes["different"]


def problems(results, limit=12):
    """The first `limit` unexpected answers, one line each."""
    wrong = [r for r in results if r.problem is not None]
    lines = [f"  {r.kind}: {r.problem}" for r in wrong[:limit]]
    if len(wrong) > limit:
        lines.append(f"  ... and {len(wrong) - limit} more")
    return lines


def load_average():
    with open("/proc/loadavg") as loadavg:
        return " ".join(loadavg.read().split()[:3])


class Checks:
    """Named pass/fail checks; the driver's exit code is 1 when any failed."""

    def __init__(self):
        self.items = []

    def add(self, name, passed, detail=""):
        self.items.append((name, bool(passed), detail))

    def note(self, name, detail):
        """A finding reported beside the checks, passing or failing none."""
        self.items.append((name, None, detail))

    def failed(self):
        return [item for item in self.items if item[1] is False]

    def report(self):
        mark = {True: "PASS", False: "FAIL", None: "NOTE"}
        return "\n".join(f"  [{mark[ok]}] {name}" + (f": {detail}" if detail else "")
                         for name, ok, detail in self.items)

