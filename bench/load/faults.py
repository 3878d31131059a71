"""Issue 12 part 9: one afmesh-server under the fault mix (kinds.fault_mix) for a fixed time;
then its health, RSS, exit on SIGTERM and call log, and every answer, are checked."""
import collections
import dataclasses
import time

import driver
import kinds
import servers


@dataclasses.dataclass
class Measured:
    """What one run found."""
    results: list
    wall: float
    references: int  # requests sent alone before the load
    rss_kib: dict  # "start", "before", "peak", "after"
    alive: bool
    health: str
    exit_code: int
    logged: list  # the server's call log, parsed (servers.parse_call_line)
    slow_reader_tets: int


def server_flags(args):
    return ["--workers", str(args.workers), "--max-queue", str(args.max_queue),
            "--max-elements", "2000000", "--memory-budget-mb", str(args.memory_budget_mb),
            "--max-request-mb", "64", "--grace-period", "10"]


def run(args, workdir, mix):
    """Starts the server, sends each valid request alone, drives the mix, stops the server."""
    flags = server_flags(args)
    server = servers.Server(args.server_binary, workdir, "server", flags)
    print(f"afmesh-load faults: server pid {server.pid} on {server.address} "
          f"({' '.join(flags)}); {args.clients} clients for {args.seconds:g} s; work folder "
          f"{workdir}; load average {driver.load_average()}", flush=True)
    rss = {"start": server.rss_kib()}
    target = kinds.Target(server.address, args.cli, workdir, args.slow_pause)
    valid = [kind for kind, _ in mix if hasattr(kind, "reference")]
    for kind in valid:
        kind.reference(target, None)
    time.sleep(0.5)
    rss["before"] = server.rss_kib()
    once = [kinds.unmeshable_kind()] if args.unmeshable else []
    with servers.RssSampler([server]) as sampler:
        results, wall = driver.drive(target, mix, args.clients, args.seconds, args.max_requests,
                                     args.seed, once=once)
    time.sleep(1.0)
    rss["after"] = server.rss_kib()
    alive, health = server.alive(), servers.health(server.address)
    exit_code = server.stop()
    rss["peak"] = max(sampler.peak["server"], rss["before"] or 0, rss["after"] or 0)
    slow = next(kind for kind, _ in mix if kind.name == "slow-reader")
    return Measured(results, wall, len(valid), rss, alive, health, exit_code, server.calls(),
                    slow.tets)


def mib(kib):
    return "-" if kib is None else f"{kib / 1024:.1f}"


def attempts(m):
    return sum(len(r.codes) for r in m.results) + m.references


def report(m):
    print()
    print(driver.kind_table(m.results))
    valid, same, lost, different = driver.mesh_counts(m.results)
    print(f"\nvalid requests {valid}: same mesh as alone {same}, lost {lost}, wrong {different}")
    print(f"server RSS MiB: at start {mib(m.rss_kib['start'])}, before the load (after the "
          f"{m.references} requests alone) {mib(m.rss_kib['before'])}, peak "
          f"{mib(m.rss_kib['peak'])}, 1 s after {mib(m.rss_kib['after'])}")
    retries = attempts(m) - m.references - len(m.results)
    codes = collections.Counter(call["code"] for call in m.logged)
    print(f"server log: {len(m.logged)} calls logged for {attempts(m)} sent ({len(m.results)} "
          f"requests, {retries} retries, {m.references} alone): {driver.format_counts(codes)}")
    print(f"run: {m.wall:.1f} s wall, {len(m.results)} requests, load average "
          f"{driver.load_average()}")


def check(args, m, mix, checks):
    checks.add("server alive after the load", m.alive)
    checks.add("health SERVING after the load", m.health == "SERVING", m.health)
    checks.add("server drained and exited 0 on SIGTERM", m.exit_code == 0, f"exit {m.exit_code}")
    problems = driver.problems(m.results)
    checks.add("every request got its expected answer", not problems,
               "\n" + "\n".join(problems) if problems else "")
    _, _, lost, different = driver.mesh_counts(m.results)
    checks.add("no valid mesh lost or different", lost == 0 and different == 0,
               f"lost {lost}, different {different}")
    checks.add("every kind was sent", {k.name for k, _ in mix} <= {r.kind for r in m.results})
    checks.add("every call sent was logged by the server", len(m.logged) == attempts(m),
               f"{len(m.logged)} of {attempts(m)}")
    before = m.rss_kib["before"] or 0
    growth_mib = ((m.rss_kib["after"] or 0) - before) / 1024
    checks.add(f"RSS 1 s after within {args.rss_margin_mb:g} MiB of before",
               growth_mib <= args.rss_margin_mb, f"{growth_mib:+.1f} MiB")
    peak_mib = (m.rss_kib["peak"] - before) / 1024
    checks.add(f"peak RSS within the memory budget ({args.memory_budget_mb} MiB) over before",
               peak_mib <= args.memory_budget_mb, f"+{peak_mib:.1f} MiB")
    # A slow reader's call, in the server's log: an OK call with its tet count open at least the
    # pause. Other calls of that front (the one sent alone) may take as long on a slow machine,
    # so at least one such call per slow reader.
    slow = sum(r.kind == "slow-reader" for r in m.results)
    held = sum(c["code"] == "OK" and int(c["tets_out"]) == m.slow_reader_tets
               and float(c["seconds"]) >= args.slow_pause for c in m.logged)
    checks.add("the server waited for each slow reader (its call open >= the pause)",
               held >= slow, f"{held} for {slow}")


def faults(args, workdir, checks):
    mix = kinds.fault_mix(args.slow_pause)
    measured = run(args, workdir, mix)
    report(measured)
    check(args, measured, mix, checks)
