"""Issue 13 part 3: K afmesh-server replicas on loopback behind nginx (grpc_pass) and haproxy
(proto h2, active gRPC health check), M concurrent CLI clients through the balancer: requests
per replica, throughput K=1 vs K=2, one replica SIGKILLed mid-run, one drained (SIGTERM) mid-run,
every request accounted for."""
import collections
import os
import signal
import threading
import time

import driver
import kinds
import servers

# One worker per replica: a job is single-threaded, so K replicas use K cores. The queue holds
# every client's call, so that throughput is not shaped by busy refusals and their back-off.
REPLICA_FLAGS = ["--workers", "1", "--max-queue", "16", "--grace-period", "30"]


class Run:
    """One run's set-up and what it found."""

    def __init__(self, balancer, replicas, event):
        self.balancer = balancer  # a servers.Balancer subclass
        self.replicas = replicas
        self.event = event  # None, "kill" or "drain": what happens to replica r1 mid-run
        self.name = f"{balancer.name} K={replicas}" + (f" {event} r1" if event else "")
        self.notes = []


class DrainWatch:
    """After SIGTERM to `server`: when its health turned NOT_SERVING and when it exited."""

    def __init__(self, server):
        self.server = server
        self.sent = None
        self.not_serving_after = None
        self.exited_after = None

    def start(self):
        self.sent = time.monotonic()
        self.server.signal(signal.SIGTERM)
        threading.Thread(target=self._watch, daemon=True).start()

    def _watch(self):
        while self.server.alive() and time.monotonic() - self.sent < 60:
            if self.not_serving_after is None and servers.health(
                    self.server.address, timeout=0.5) == "NOT_SERVING":
                self.not_serving_after = time.monotonic() - self.sent
            time.sleep(0.02)
        if not self.server.alive():
            self.exited_after = time.monotonic() - self.sent


def run_once(args, workdir, run, references_alone):
    """Starts the replicas and the balancer, drives them, stops them; the results, the
    per-replica call logs, and how many requests were sent alone to r0 first (filling
    `references_alone` when it is empty)."""
    folder = os.path.join(workdir, run.name.replace(" ", "_").replace("=", ""))
    os.makedirs(folder)
    replicas = [servers.Server(args.server_binary, folder, f"r{i}", REPLICA_FLAGS)
                for i in range(run.replicas)]
    balancer = run.balancer(folder, [r.address for r in replicas])
    for _ in range(50):  # haproxy's first checks, spread over one interval
        if servers.health(balancer.address, timeout=0.5) == "SERVING":
            break
        time.sleep(0.1)
    mix = kinds.valid_mix()
    # The meshes the requests get alone, straight from r0, in the first run only: every replica
    # runs the same binary, so they hold for every run.
    references = 0 if references_alone else len(mix)
    if not references_alone:
        alone = kinds.Target(replicas[0].address, args.cli, folder, 0.0)
        for kind, _ in mix:
            kind.reference(alone, None)
        references_alone.update(alone.references)
    target = kinds.Target(balancer.address, args.cli, folder, 0.0)
    target.references = references_alone
    drain = DrainWatch(replicas[-1]) if run.event == "drain" else None
    events = []
    if run.event == "kill":
        events = [(args.seconds / 2, lambda: replicas[-1].signal(signal.SIGKILL))]
    elif run.event == "drain":
        events = [(args.seconds / 2, drain.start)]
    results, wall = driver.drive(target, mix, args.clients, args.seconds, args.max_requests,
                                 args.seed, events=events)
    logs = {r.name: r.calls() for r in replicas}
    exits = {r.name: r.stop() for r in replicas}
    balancer.stop()
    return results, wall, logs, exits, drain, references


def accounting_row(run, results, wall, logs, exits, references):
    """One row of the scale-out table."""
    ok_first = sum(r.problem is None and r.busy_retries == 0 for r in results)
    ok_retried = sum(r.problem is None and r.busy_retries > 0 for r in results)
    failed = [r for r in results if r.problem is not None]
    retry_codes = collections.Counter(c for r in results for c in r.codes[:-1])
    failures = failure_summary(failed) if failed else "0"
    per_replica = ", ".join(
        f"{name} {sum(c['code'] == 'OK' for c in calls) - (references if name == 'r0' else 0)}"
        + (f" (+{sum(c['code'] != 'OK' for c in calls)} refused)"
           if any(c["code"] != "OK" for c in calls) else "")
        for name, calls in logs.items())
    sent = sum(len(r.codes) for r in results) + references
    logged = sum(len(calls) for calls in logs.values())
    valid, same, lost, different = driver.mesh_counts(results)
    return [run.name, len(results), ok_first, ok_retried,
            driver.format_counts(retry_codes), failures,
            f"{sum(r.problem is None for r in results) / wall:.2f}", per_replica,
            sent - logged, f"{same}/{same + different}",
            ", ".join(f"{n} {'killed' if code == -signal.SIGKILL else code}"
                      for n, code in exits.items())]


def scaleout(args, workdir, checks):
    """Every run for each balancer present; prints the table and adds the checks."""
    balancers = [b for b in (servers.Nginx, servers.Haproxy) if b.available()
                 and (not args.balancers or b.name in args.balancers)]
    missing = [b.name for b in (servers.Nginx, servers.Haproxy) if not b.available()]
    if missing:
        print(f"afmesh-load scaleout: not installed: {', '.join(missing)} "
              f"(scripts/install-deps.sh --balancers)")
    if not balancers:
        return None
    rows = []
    throughput = {}
    references_alone = {}
    for balancer in balancers:
        for replicas, event in [(1, None), (2, None), (2, "kill"), (2, "drain")]:
            if args.runs and f"{replicas}{event or ''}" not in args.runs:
                continue
            run = Run(balancer, replicas, event)
            print(f"  {run.name}: {args.clients} CLI clients for {args.seconds:g} s, load "
                  f"average {driver.load_average()}", flush=True)
            results, wall, logs, exits, drain, references = run_once(args, workdir, run,
                                                                    references_alone)
            rows.append(accounting_row(run, results, wall, logs, exits, references))
            judge(run, results, logs, exits, drain, references, checks)
            if event is None:
                throughput[(balancer.name, replicas)] = (
                    sum(r.problem is None for r in results) / wall)
            for line in driver.problems(results, limit=5):
                print(f"    {line.strip()}")
            if drain is not None:
                print(f"    drain: health NOT_SERVING after {fmt(drain.not_serving_after)} s, "
                      f"replica exited after {fmt(drain.exited_after)} s")
    print()
    print(driver.table(
        ["run", "requests", "ok first try", "ok after retry", "retried codes", "failed",
         "ok/s", "ok calls per replica", "calls unlogged", "same mesh", "replica exits"], rows))
    for name in [b.name for b in balancers]:
        if (name, 1) in throughput and (name, 2) in throughput:
            print(f"{name}: throughput K=2 / K=1 = "
                  f"{throughput[(name, 2)] / throughput[(name, 1)]:.2f}")
    return rows


def failure_summary(failed):
    """What the failed calls ended with, counted: the CLI's exit code and last message."""
    return driver.format_counts(collections.Counter(
        r.problem.split(": ", 1)[0] + " (" + r.problem.rsplit(": ", 1)[-1] + ")"
        for r in failed))


def judge(run, results, logs, exits, drain, references, checks):
    failed = [r for r in results if r.problem is not None]
    if run.event == "drain":
        checks.add(f"{run.name}: no failed call", not failed, f"{len(failed)} failed")
        checks.add(f"{run.name}: the drained replica exited 0", exits["r1"] == 0,
                   f"exit {exits['r1']}")
        checks.add(f"{run.name}: health NOT_SERVING during the drain",
                   drain.not_serving_after is not None or drain.exited_after is not None,
                   f"after {fmt(drain.not_serving_after)} s")
    elif run.event == "kill":
        # The calls r1 held when killed left no line in its log: only those may fail.
        held = sum(len(r.codes) for r in results) + references - sum(map(len, logs.values()))
        checks.add(f"{run.name}: only the calls the killed replica held failed",
                   len(failed) <= held, f"{len(failed)} failed, {held} held by r1")
        checks.note(f"{run.name}: calls held by r1 retried by the CLI",
                    f"{held - len(failed)} of {held}" + (
                        f"; not retried: {failure_summary(failed)}" if failed else ""))
    else:
        checks.add(f"{run.name}: every call succeeded with the same mesh", not failed,
                   f"{len(failed)} failed")
        if run.replicas > 1:
            counts = [sum(c["code"] == "OK" for c in calls) for calls in logs.values()]
            checks.add(f"{run.name}: calls spread over every replica", min(counts) > 0,
                       str(counts))


def fmt(seconds):
    return "-" if seconds is None else f"{seconds:.2f}"

