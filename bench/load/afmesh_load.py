"""afmesh load driver: `faults` drives one afmesh-server with a mix of valid, invalid, cancelled,
deadline-expired, over-limit and slow-reading requests; `scaleout` drives K replicas behind nginx
and haproxy, killing one and draining one mid-run. Loopback only, bounded in time and count.
Run through bench/load/run.sh (it generates the Python stubs); see bench/load/README.md."""
import argparse
import os
import shutil
import sys
import tempfile

import driver
import faults
import scaleout


def run_faults(args):
    """Issue 12 part 9; exit 1 when a check fails."""
    workdir = tempfile.mkdtemp(prefix="afmesh-load-", dir=args.workdir)
    checks = driver.Checks()
    faults.faults(args, workdir, checks)
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
        return run_faults(args)
    return scale(args)


def scale(args):
    """Issue 13 part 3; exit 77 (CTest's skip) when neither balancer is installed."""
    workdir = tempfile.mkdtemp(prefix="afmesh-scaleout-", dir=args.workdir)
    print(f"afmesh-load scaleout: work folder {workdir}; load average {driver.load_average()}")
    checks = driver.Checks()
    if scaleout.scaleout(args, workdir, checks) is None:
        print("afmesh-load scaleout: SKIPPED: neither nginx nor haproxy is installed")
        shutil.rmtree(workdir, ignore_errors=True)
        return 77
    print("\nchecks:\n" + checks.report())
    return finish(checks, workdir)


if __name__ == "__main__":
    sys.exit(main())
