"""The kinds of request the load driver sends, each with the answer it must get.

A kind's run(target, rng) sends one request (again while the server answers "busy",
RESOURCE_EXHAUSTED with a retry-after-ms hint) and returns a Result saying what came back and,
when that is not the expected answer, what is wrong. Valid meshes are checked byte for byte
against the same request sent alone before the load (Target.references).
"""
import dataclasses
import hashlib
import math
import os
import re
import subprocess
import threading
import time

import grpc

from afmesh.v1 import mesher_pb2_grpc as pb_grpc
import fronts

# Through the CLI: a request's whole life, retries included, is bounded by this (--timeout of
# each call) times the attempts; through Python, each attempt is bounded by it.
CALL_TIMEOUT_S = 60.0
CLI_RETRIES = 8
# Retries of a busy refusal by the driver's own Python calls (the CLI has --retries).
MAX_BUSY_ATTEMPTS = 30

# Valid requests: small fronts, a few distinct ones (name: front, size).
SMALL = {
    "cube-h0.15": (fronts.box_front(1, 1, 1, 0.15), 0.15),
    "slab-h0.15": (fronts.box_front(1.5, 1, 0.6, 0.15), 0.15),
    "cube-h0.12": (fronts.box_front(1, 1, 1, 0.12), 0.12),
}
# A job of 0.1 to 0.4 s alone (42k tetrahedra), to stream a mesh larger than the HTTP/2
# flow-control windows to a client that stops reading.
MEDIUM = (fronts.box_front(1, 1, 1, 0.06), 0.06)
# A job that outlives a 0.4 s deadline, or a cancel up to 0.3 s after its first progress, on any
# machine: 0.58M tetrahedra, seconds of one worker. (On MEDIUM the 0.4 s deadline expired only
# when the job had waited in the queue: on an unloaded fast machine CI saw OK for 12 of 18.)
LONG = (fronts.box_front(1, 1, 1, 0.025), 0.025)

CLI_RETRY_LINE = re.compile(r"^afmesh volume: (.*); retry \d+ of \d+ in [\d.]+ s$", re.M)


@dataclasses.dataclass
class Result:
    kind: str
    expected: str
    codes: list  # the code of each attempt, in order ("OK", "RESOURCE_EXHAUSTED", ...)
    seconds: float  # from the first attempt's start to the last attempt's end
    problem: str = None  # None when the answer was the expected one
    busy_retries: int = 0  # attempts sent again after a refusal that may pass later
    mesh: str = None  # for valid kinds: "same", "different" or "none"


@dataclasses.dataclass
class Attempt:
    code: str
    details: str
    trailing: dict
    digest: str
    tets: int


class Target:
    """Where the requests go, and what they are compared with. One per run; `channel()` gives
    each client thread its own channel (its own HTTP/2 connection), like separate clients."""

    def __init__(self, address, cli, workdir, slow_pause_s):
        self.address = address
        self.cli = cli
        self.workdir = workdir
        self.slow_pause_s = slow_pause_s
        self.references = {}  # request name -> digest of its mesh sent alone
        self._local = threading.local()
        self._counter = 0
        self._lock = threading.Lock()

    def stub(self, small_window=False):
        """This thread's stub; with `small_window`, on a channel whose HTTP/2 stream window stays
        at 64 KiB (no BDP probing), so that a client that stops reading stalls the server's
        stream after 64 KiB instead of after the several MiB gRPC's window can grow to."""
        stubs = self._local.__dict__.setdefault("stubs", {})
        if small_window not in stubs:
            options = [("grpc.max_receive_message_length", 8 << 20)]
            if small_window:
                options += [("grpc.http2.bdp_probe", 0), ("grpc.http2.lookahead_bytes", 65535)]
            stubs[small_window] = pb_grpc.MesherStub(grpc.insecure_channel(self.address, options))
        return stubs[small_window]

    def scratch(self, suffix):
        with self._lock:
            self._counter += 1
            return os.path.join(self.workdir, f"out-{self._counter}{suffix}")

    def front_file(self, name, front):
        """`front` as a Medit file for the CLI, written once (under the lock: client threads
        ask for it at the same time, and none may read it half written)."""
        path = os.path.join(self.workdir, f"{name}.mesh")
        with self._lock:
            if not os.path.exists(path):
                fronts.write_medit(path, front)
        return path


def attempt(stub, messages, timeout, watch=None):
    """One MeshVolume call: `messages` up, the responses read and digested, `watch(response,
    call)` shown each response (to cancel, or to stop reading for a while)."""
    digest = fronts.MeshDigest()
    call = stub.MeshVolume(iter(messages), timeout=timeout)
    code, details = "OK", ""
    try:
        for response in call:
            digest.add(response)
            if watch is not None:
                watch(response, call)
    except grpc.RpcError as error:
        code, details = error.code().name, error.details() or ""
    trailing = dict(call.trailing_metadata() or ())
    return Attempt(code, details, trailing, digest.hexdigest(), digest.tets)


def send(target, messages, rng, timeout=CALL_TIMEOUT_S, watch_factory=None, small_window=False):
    """attempt(), again after a jittered wait while the server answers busy (RESOURCE_EXHAUSTED
    with retry-after-ms): the attempts made and the seconds they took."""
    attempts = []
    start = time.monotonic()
    while True:
        watch = watch_factory(rng) if watch_factory else None
        attempts.append(attempt(target.stub(small_window), messages, timeout, watch))
        hint = attempts[-1].trailing.get("retry-after-ms")
        if (attempts[-1].code != "RESOURCE_EXHAUSTED" or hint is None
                or len(attempts) >= MAX_BUSY_ATTEMPTS):
            return attempts, time.monotonic() - start
        time.sleep(int(hint) / 1000.0 * rng.uniform(0.5, 1.5))


class PythonKind:
    """A request sent by the driver itself, expecting the final code `code` (and, when given,
    `detail` in its message)."""

    def __init__(self, name, messages, code, detail=None, timeout=CALL_TIMEOUT_S,
                 watch_factory=None, small_window=False):
        self.name = name
        self.messages = messages
        self.code = code
        self.detail = detail
        self.timeout = timeout
        self.watch_factory = watch_factory
        self.small_window = small_window
        self.expected = code + (" + message" if detail else "")

    def run(self, target, rng):
        attempts, seconds = send(target, self.messages, rng, self.timeout, self.watch_factory,
                                 self.small_window)
        result = Result(self.name, self.expected, [a.code for a in attempts], seconds,
                        busy_retries=len(attempts) - 1)
        self.judge(target, attempts[-1], result)
        return result

    def judge(self, target, last, result):
        if last.code != self.code:
            result.problem = f"{last.code}: {last.details[:160]}"
        elif self.detail and not re.search(self.detail, last.details):
            result.problem = f"message lacks {self.detail!r}: {last.details[:160]}"


class OverLimitKind(PythonKind):
    """RESOURCE_EXHAUSTED that no retry can cure: the message names the limit, and no
    retry-after-ms hint comes with it."""

    def judge(self, target, last, result):
        super().judge(target, last, result)
        if result.problem is None and "retry-after-ms" in last.trailing:
            result.problem = "an over-limit refusal carries a retry hint"


class StreamedMeshKind(PythonKind):
    """A valid request sent by the driver: OK, with the mesh the same request got alone."""

    def __init__(self, name, front, size, **kwargs):
        super().__init__(name, fronts.request_stream(front, size), "OK", **kwargs)
        self.expected = "OK, same mesh"

    def reference(self, target, rng):
        attempts, _ = send(target, self.messages, rng)
        self.tets = attempts[-1].tets
        if attempts[-1].code != "OK":
            raise RuntimeError(f"{self.name} alone: {attempts[-1].code} {attempts[-1].details}")
        target.references[self.name] = attempts[-1].digest

    def judge(self, target, last, result):
        super().judge(target, last, result)
        if last.code != "OK":
            result.mesh = "none"
        elif last.digest == target.references[self.name]:
            result.mesh = "same"
        else:
            result.mesh = "different"
            result.problem = "the mesh differs from the one the request got alone"


class CliKind:
    """A valid request through the afmesh CLI (`afmesh volume FRONT -o OUT.msh --server ...`,
    its own retries): exit 0 and an output file byte-identical to the request's alone."""

    expected = "exit 0, same file"

    def __init__(self, name, front, size):
        self.name = name
        self.front = front
        self.size = size

    def command(self, target, output):
        return [target.cli, "volume", target.front_file(self.name, self.front), "-o", output,
                "--size", repr(self.size), "--server", target.address, "--json",
                "--timeout", str(CALL_TIMEOUT_S), "--retries", str(CLI_RETRIES)]

    def call(self, target):
        """Runs the CLI: (exit code, stderr, output digest or None, seconds)."""
        output = target.scratch(".msh")
        start = time.monotonic()
        done = subprocess.run(self.command(target, output), capture_output=True, text=True,
                              env={**os.environ, "TERM": "dumb"})
        seconds = time.monotonic() - start
        digest = None
        if done.returncode == 0 and os.path.exists(output):
            with open(output, "rb") as mesh:
                digest = hashlib.sha256(mesh.read()).hexdigest()
        if os.path.exists(output):
            os.remove(output)
        return done.returncode, done.stderr, digest, seconds

    def reference(self, target, rng):
        code, stderr, digest, _ = self.call(target)
        if code != 0:
            raise RuntimeError(f"{self.name} alone: exit {code}: {stderr[-400:]}")
        target.references[self.name] = digest

    def run(self, target, rng):
        code, stderr, digest, seconds = self.call(target)
        retries = CLI_RETRY_LINE.findall(stderr)
        codes = [retry_reason(message) for message in retries] + [
            "OK" if code == 0 else f"exit {code}"]
        result = Result(self.name, self.expected, codes, seconds, busy_retries=len(retries))
        if code != 0:
            result.mesh = "none"
            last = [line for line in stderr.splitlines() if line.startswith("afmesh volume:")]
            result.problem = f"exit {code}: {(last or [''])[-1][:200]}"
        elif digest == target.references[self.name]:
            result.mesh = "same"
        else:
            result.mesh = "different"
            result.problem = "the output file differs from the one the request got alone"
        return result


def retry_reason(message):
    """The code behind a CLI retry line: the CLI prints the server's message (or gRPC's), so the
    code is told from the messages the server sends with each retryable refusal."""
    if "the server is busy" in message or "memory budget" in message:
        return "RESOURCE_EXHAUSTED"
    return "UNAVAILABLE"  # the only other code the CLI retries (draining or unreachable)


def cancel_mid_mesh(rng):
    """Cancels the call 0 to 300 ms after the first Progress event past "queued"."""
    state = {"done": False}

    def watch(response, call):
        if state["done"] or not response.HasField("progress"):
            return
        if response.progress.stage != "queued":
            state["done"] = True
            time.sleep(rng.uniform(0.0, 0.3))
            call.cancel()
    return watch


def stop_reading(pause_s):
    """Stops reading the response stream for `pause_s` at the first mesh slice."""
    def factory(rng):
        state = {"paused": False}

        def watch(response, call):
            if not state["paused"] and response.WhichOneof("event") == "points":
                state["paused"] = True
                time.sleep(pause_s)
        return watch
    return factory


def with_points(front, change):
    points, triangles = front
    points = list(points)
    change(points)
    return points, triangles


def invalid_kinds():
    """Requests the server must refuse, each with its code and what the message names."""
    front, size = SMALL["cube-h0.15"]
    points, triangles = front
    open_front = (points, triangles[:-1])
    bad_index = (points, triangles[:-1] + [(0, 1, len(points) + 5)])

    def set_nan(p):
        p[3] = (math.nan, 0.0, 0.0)
    nan_front = with_points(front, set_nan)
    slice_first = list(fronts.slices(front))[:1] + fronts.request_stream(front, size)
    wrong_count = [fronts.header(size, 1.0, len(points) + 1, len(triangles))] + list(
        fronts.slices(front))
    return [
        PythonKind("invalid-open-front", fronts.request_stream(open_front, size),
                   "INVALID_ARGUMENT", r"holes"),
        PythonKind("invalid-index", fronts.request_stream(bad_index, size), "INVALID_ARGUMENT",
                   r"refers to point"),
        PythonKind("invalid-nan-point", fronts.request_stream(nan_front, size),
                   "INVALID_ARGUMENT", r"finite"),
        PythonKind("invalid-size", fronts.request_stream(front, -1.0), "INVALID_ARGUMENT",
                   r"max_?[sS]ize"),
        PythonKind("invalid-growth", fronts.request_stream(front, size, growth=0.5),
                   "INVALID_ARGUMENT", r"growth"),
        PythonKind("invalid-slice-first", slice_first, "INVALID_ARGUMENT", r"header"),
        PythonKind("invalid-count", wrong_count, "INVALID_ARGUMENT", r"count|declared|header"),
    ]


def over_limit_kinds():
    front, _ = SMALL["cube-h0.15"]
    points, triangles = front
    huge_count = [fronts.header(0.15, 1.0, 10**9, len(triangles))] + list(fronts.slices(front))
    return [
        OverLimitKind("over-max-elements", fronts.request_stream(front, 0.004),
                      "RESOURCE_EXHAUSTED", r"about [\d.e+]+ tetrahedra.*--max-elements"),
        OverLimitKind("over-max-points", huge_count, "RESOURCE_EXHAUSTED", r"--max-points"),
    ]


def fault_mix(slow_pause_s):
    """The load test's mix, name -> (kind, weight): valid requests (through the CLI and
    streamed), bad ones, stopped ones, over-limit ones and slow readers."""
    medium_front, medium_size = MEDIUM
    medium = fronts.request_stream(medium_front, medium_size)
    long_job = fronts.request_stream(*LONG)
    kinds = [(CliKind(name, front, size), 3) for name, (front, size) in SMALL.items()]
    kinds += [
        (StreamedMeshKind("slow-reader", medium_front, medium_size,
                          watch_factory=stop_reading(slow_pause_s), small_window=True), 1),
        (PythonKind("cancelled-mid-mesh", long_job, "CANCELLED",
                    watch_factory=cancel_mid_mesh), 1),
        (PythonKind("deadline-0.4s", long_job, "DEADLINE_EXCEEDED", timeout=0.4), 1),
    ]
    kinds += [(kind, 1) for kind in invalid_kinds() + over_limit_kinds()]
    return kinds


def unmeshable_kind():
    """A front the mesher cannot close (fronts.cube_with_cavity): FAILED_PRECONDITION saying
    where it got stuck, after about 12 s of one worker (measured in release): sent once per run."""
    return PythonKind("unmeshable", fronts.request_stream(fronts.cube_with_cavity(), 0.6),
                      "FAILED_PRECONDITION", r"did not close|got stuck")


# Scale-out requests: jobs of 0.2 to 0.4 s, so that the replicas' work, not the clients'
# start-up, sets the throughput, and a replica killed mid-run holds calls.
SCALE = {
    "cube-h0.06": MEDIUM,
    "slab-h0.06": (fronts.box_front(1.5, 1, 0.6, 0.06), 0.06),
}


def valid_mix():
    """The scale-out mix: valid requests through the CLI only."""
    return [(CliKind(name, front, size), 1) for name, (front, size) in SCALE.items()]
