"""afmesh load driver: `faults` drives one afmesh-server with a mix of valid, invalid, cancelled,
deadline-expired, over-limit and slow-reading requests; `scaleout` drives K replicas behind nginx
and haproxy, killing one and draining one mid-run. Loopback only, bounded in time and count.
Run through bench/load/run.sh (it generates the Python stubs); see bench/load/README.md."""
import argparse
import collections
import os
import shutil
import signal
import sys
import tempfile
import time

import driver
import kinds
import scaleout
import servers


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


def mib(kib):
    return "-" if kib is None else f"{kib / 1024:.1f}"


def attempts_of(results):
    return sum(len(r.codes) for r in results)


def server_codes(server_list):
    return collections.Counter(c["code"] for s in server_list for c in s.calls())


def faults(args):
    """Issue 12 part 9: one server under the fault mix; exit 1 when a check fails."""
    workdir = tempfile.mkdtemp(prefix="afmesh-load-", dir=args.workdir)
    flags = ["--workers", str(args.workers), "--max-queue", str(args.max_queue),
             "--max-elements", "2000000", "--memory-budget-mb", str(args.memory_budget_mb),
             "--max-request-mb", "64", "--grace-period", "10"]
    server = servers.Server(args.server_binary, workdir, "server", flags)
    print(f"afmesh-load faults: server pid {server.pid} on {server.address} "
          f"({' '.join(flags)}); {args.clients} clients for {args.seconds:g} s; work folder "
          f"{workdir}; load average {driver.load_average()}", flush=True)
    rss_start = server.rss_kib()
    target = kinds.Target(server.address, args.cli, workdir, args.slow_pause)
    mix = kinds.fault_mix(args.slow_pause)
    once = [kinds.unmeshable_kind()] if args.unmeshable else []
    reference_results = 0
    for kind, _ in mix:
        if hasattr(kind, "reference"):
            kind.reference(target, None)
            reference_results += 1
    time.sleep(0.5)
    rss_before = server.rss_kib()

    with servers.RssSampler([server]) as sampler:
        results, wall = driver.drive(target, mix, args.clients, args.seconds, args.max_requests,
                                     args.seed, once=once)
    time.sleep(1.0)
    rss_after = server.rss_kib()
    alive = server.alive()
    health = servers.health(server.address)
    logged = server_codes([server])
    exit_code = server.stop()
    rss_peak = max(sampler.peak["server"], rss_before or 0, rss_after or 0)

    print()
    print(driver.kind_table(results))
    valid, same, lost, different = driver.mesh_counts(results)
    print(f"\nvalid requests {valid}: same mesh as alone {same}, lost {lost}, wrong {different}")
    print(f"server RSS MiB: at start {mib(rss_start)}, before the load (after the "
          f"{reference_results} requests alone) {mib(rss_before)}, peak {mib(rss_peak)}, "
          f"1 s after {mib(rss_after)}")
    sent = attempts_of(results) + reference_results
    print(f"server log: {sum(logged.values())} calls logged for {sent} sent ({len(results)} "
          f"requests, {attempts_of(results) - len(results)} retries, {reference_results} alone): "
          f"{driver.format_counts(logged)}")
    print(f"run: {wall:.1f} s wall, {len(results)} requests, load average {driver.load_average()}")

    checks = Checks()
    checks.add("server alive after the load", alive)
    checks.add("health SERVING after the load", health == "SERVING", health)
    checks.add("server drained and exited 0 on SIGTERM", exit_code == 0, f"exit {exit_code}")
    checks.add("every request got its expected answer",
               all(r.problem is None for r in results),
               "\n" + "\n".join(driver.problems(results)) if driver.problems(results) else "")
    checks.add("no valid mesh lost or different", lost == 0 and different == 0,
               f"lost {lost}, different {different}")
    checks.add("every kind was sent", {k.name for k, _ in mix} <= {r.kind for r in results})
    checks.add("every call sent was logged by the server", sum(logged.values()) == sent,
               f"{sum(logged.values())} of {sent}")
    growth_mib = ((rss_after or 0) - (rss_before or 0)) / 1024
    checks.add(f"RSS 1 s after within {args.rss_margin_mb} MiB of before", growth_mib <=
               args.rss_margin_mb, f"{growth_mib:+.1f} MiB")
    checks.add(f"peak RSS within the memory budget ({args.memory_budget_mb} MiB) over before",
               (rss_peak - (rss_before or 0)) / 1024 <= args.memory_budget_mb,
               f"+{(rss_peak - (rss_before or 0)) / 1024:.1f} MiB")
    slow = [r for r in results if r.kind == "slow-reader"]
    slow_kind = next(k for k, _ in mix if k.name == "slow-reader")
    held = [c for c in server.calls() if c["code"] == "OK" and int(c["tets_out"]) == slow_kind.tets
            and float(c["seconds"]) >= args.slow_pause]
    checks.add("the server waited for each slow reader (its call open >= the pause)",
               len(held) == len(slow), f"{len(held)} of {len(slow)}")
    print("\nchecks:\n" + checks.report())
    return finish(checks, workdir)


def finish(checks, workdir):
    """The exit code; the work folder (logs, configs) is kept when a check failed."""
    if checks.failed():
        print(f"\n{len(checks.failed())} check(s) failed; logs kept in {workdir}")
        return 1
    shutil.rmtree(workdir, ignore_errors=True)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", required=True, help="the build folder (build/release)")
    parser.add_argument("--workdir", default=None, help="where the work folder is made")
    commands = parser.add_subparsers(dest="command", required=True)
    one = commands.add_parser("faults", help="the load and fault test against one server")
    one.add_argument("--seconds", type=float, default=60.0)
    one.add_argument("--clients", type=int, default=6)
    one.add_argument("--max-requests", type=int, default=5000)
    one.add_argument("--workers", type=int, default=2)
    one.add_argument("--max-queue", type=int, default=4)
    one.add_argument("--memory-budget-mb", type=int, default=1024)
    one.add_argument("--slow-pause", type=float, default=3.0,
                     help="seconds a slow reader stops reading")
    one.add_argument("--rss-margin-mb", type=float, default=64.0)
    one.add_argument("--no-unmeshable", dest="unmeshable", action="store_false",
                     help="leave out the unmeshable request (12 s of one worker)")
    one.add_argument("--seed", type=int, default=1)
    out = commands.add_parser("scaleout", help="K replicas behind nginx and haproxy")
    out.add_argument("--seconds", type=float, default=20.0, help="of each run")
    out.add_argument("--clients", type=int, default=4)
    out.add_argument("--max-requests", type=int, default=2000, help="of each run")
    out.add_argument("--runs", nargs="*", default=None,
                     help="some of 1 2 2kill 2drain (default: all four)")
    out.add_argument("--balancers", nargs="*", default=None, help="nginx, haproxy (default both)")
    out.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    args.server_binary = os.path.join(args.build, "client", "afmesh-server")
    args.cli = os.path.join(args.build, "client", "afmesh")
    if args.command == "faults":
        return faults(args)
    return scale(args)


def scale(args):
    """Issue 13 part 3; exit 77 (CTest's skip) when neither balancer is installed."""
    workdir = tempfile.mkdtemp(prefix="afmesh-scaleout-", dir=args.workdir)
    print(f"afmesh-load scaleout: work folder {workdir}; load average {driver.load_average()}")
    checks = Checks()
    if scaleout.scaleout(args, workdir, checks) is None:
        print("afmesh-load scaleout: SKIPPED: neither nginx nor haproxy is installed")
        shutil.rmtree(workdir, ignore_errors=True)
        return 77
    print("\nchecks:\n" + checks.report())
    return finish(checks, workdir)


if __name__ == "__main__":
    sys.exit(main())
