"""Processes the load driver runs: afmesh-server replicas (their address, RSS and call log) and
the HTTP/2 balancers in front of them (nginx grpc_pass, haproxy proto h2), all on loopback, as the
user running the driver, with every file in one work folder."""
import os
import re
import shutil
import signal
import socket
import subprocess
import threading
import time

import grpc

import health_probe  # deploy/health_probe.py: the health request and SERVING bytes, one place

LISTENING = re.compile(r"listening on (127\.0\.0\.1:\d+)")
LOGFMT_PAIR = re.compile(r'(\w+)=("(?:[^"\\]|\\.)*"|\S*)')


def health(address, timeout=2.0):
    """grpc.health.v1 Check of the whole server at `address`: "SERVING", "NOT_SERVING", or the
    gRPC code name of the failed call (e.g. "UNAVAILABLE" when nothing listens)."""
    with grpc.insecure_channel(address) as channel:
        check = channel.unary_unary("/grpc.health.v1.Health/Check")
        try:
            response = check(health_probe.request_bytes(""), timeout=timeout)
        except grpc.RpcError as error:
            return error.code().name
    return "SERVING" if health_probe.is_serving(response) else "NOT_SERVING"


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_for_port(port, seconds=10.0):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            return
        except OSError:
            time.sleep(0.05)
    raise RuntimeError(f"nothing listens on 127.0.0.1:{port} after {seconds} s")


def parse_call_line(line):
    """The fields of one call_log line (server/call_log.cc) as strings, or None for other lines."""
    if not line.startswith("call "):
        return None
    return {key: value.strip('"') for key, value in LOGFMT_PAIR.findall(line)}


class Server:
    """One afmesh-server on a free loopback port, its stderr (the call log) in `workdir`."""

    def __init__(self, binary, workdir, name, flags):
        self.name = name
        self.log_path = os.path.join(workdir, f"{name}.log")
        with open(self.log_path, "w") as log:
            self.process = subprocess.Popen([binary, "--listen", "127.0.0.1:0", *flags],
                                            stdout=subprocess.DEVNULL, stderr=log)
        self.address = self._wait_for_address()
        self.port = int(self.address.rsplit(":", 1)[1])

    def _wait_for_address(self, seconds=10.0):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            with open(self.log_path) as log:
                found = LISTENING.search(log.read())
            if found:
                return found.group(1)
            if self.process.poll() is not None:
                break
            time.sleep(0.02)
        raise RuntimeError(f"{self.name} did not start (see {self.log_path})")

    @property
    def pid(self):
        return self.process.pid

    def alive(self):
        return self.process.poll() is None

    def rss_kib(self):
        """VmRSS from /proc/PID/status, or None once the process is gone."""
        try:
            with open(f"/proc/{self.pid}/status") as status:
                for line in status:
                    if line.startswith("VmRSS:"):
                        return int(line.split()[1])
        except OSError:
            pass
        return None

    def calls(self):
        """Every call the server logged so far, as parse_call_line dicts."""
        with open(self.log_path) as log:
            return [c for c in map(parse_call_line, log) if c is not None]

    def signal(self, number):
        if self.alive():
            self.process.send_signal(number)

    def stop(self, seconds=30.0):
        """SIGTERM (drain), then SIGKILL if it has not exited after `seconds`; the exit code."""
        self.signal(signal.SIGTERM)
        try:
            return self.process.wait(seconds)
        except subprocess.TimeoutExpired:
            self.process.kill()
            return self.process.wait()


class RssSampler:
    """Samples VmRSS of some servers every `interval` seconds in a thread: peak per server."""

    def __init__(self, servers, interval=0.05):
        self.servers = servers
        self.interval = interval
        self.peak = {s.name: 0 for s in servers}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()

    def _run(self):
        while not self._stop.is_set():
            for server in self.servers:
                rss = server.rss_kib()
                if rss is not None:
                    self.peak[server.name] = max(self.peak[server.name], rss)
            self._stop.wait(self.interval)


class Balancer:
    """A balancer process started from a config file written into `workdir`; `address` is its
    loopback listen address. Subclasses write the config and name the command line."""

    name = ""

    def __init__(self, workdir, backends):
        self.dir = os.path.join(workdir, self.name)
        os.makedirs(self.dir, exist_ok=True)
        self.port = free_port()
        self.address = f"127.0.0.1:{self.port}"
        self.config = os.path.join(self.dir, f"{self.name}.conf")
        with open(self.config, "w") as out:
            out.write(self.config_text(backends))
        self.log_path = os.path.join(self.dir, "stderr.log")
        with open(self.log_path, "w") as log:
            self.process = subprocess.Popen(self.command(), stdout=log, stderr=log,
                                            cwd=self.dir)
        wait_for_port(self.port)

    @classmethod
    def available(cls):
        return shutil.which(cls.name) is not None

    def stop(self):
        self.process.terminate()
        try:
            self.process.wait(10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


class Nginx(Balancer):
    """nginx, grpc_pass to an upstream of the replicas, round robin (the default). Open-source
    nginx has no active health checks: a replica is passed over for `fail_timeout` after a
    connection to it fails (max_fails=1), and a call that cannot connect goes to the next one."""

    name = "nginx"

    def command(self):
        return ["nginx", "-p", self.dir, "-c", self.config, "-e", "stderr"]

    def config_text(self, backends):
        servers = "\n".join(f"    server {b} max_fails=1 fail_timeout=2s;" for b in backends)
        temp = "\n".join(f"  {kind}_temp_path {self.dir}/{kind};"
                         for kind in ("client_body", "proxy", "fastcgi", "uwsgi", "scgi"))
        return f"""daemon off;
master_process off;
worker_processes 1;
pid {self.dir}/nginx.pid;
error_log stderr warn;
events {{ worker_connections 1024; }}
http {{
  access_log {self.dir}/access.log;
{temp}
  upstream afmesh {{
{servers}
  }}
  server {{
    listen 127.0.0.1:{self.port} http2;
    client_max_body_size 0;
    location / {{
      grpc_pass grpc://afmesh;
      grpc_next_upstream error timeout;
      grpc_read_timeout 300s;
      grpc_send_timeout 300s;
    }}
  }}
}}
"""


def h2_frame(kind, flags, stream, payload):
    return len(payload).to_bytes(3, "big") + bytes([kind, flags]) + stream.to_bytes(4, "big") + payload


def hpack_literal(name, value):
    """An HPACK "literal without indexing" field (RFC 7541 6.2.2), no Huffman coding: `name` is
    a static-table index or a new name (bytes)."""
    if isinstance(name, int):
        field = bytes([name]) if name < 15 else bytes([0x0F, name - 15])
    else:
        field = b"\x00" + bytes([len(name)]) + name
    return field + bytes([len(value)]) + value


def grpc_health_check_bytes():
    """One whole HTTP/2 connection's client side asking grpc.health.v1.Health/Check about the
    server (service ""), as haproxy's tcp-check sends it, and the bytes of the answer SERVING:
    the DATA frame on stream 1 carrying the gRPC message 08 01 (status = SERVING)."""
    headers = (b"\x83\x86"  # :method POST, :scheme http (static table 3 and 6)
               + hpack_literal(4, b"/grpc.health.v1.Health/Check")  # :path
               + hpack_literal(1, b"afmesh")  # :authority
               + hpack_literal(31, b"application/grpc")  # content-type
               + hpack_literal(b"te", b"trailers"))
    empty_request = b"\x00\x00\x00\x00\x00"  # not compressed, length 0
    request = (b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n" + h2_frame(4, 0, 0, b"")  # preface, SETTINGS
               + h2_frame(1, 0x4, 1, headers)  # HEADERS, END_HEADERS
               + h2_frame(0, 0x1, 1, empty_request))  # DATA, END_STREAM
    serving = h2_frame(0, 0, 1, b"\x00\x00\x00\x00\x02\x08\x01")
    return request, serving


class Haproxy(Balancer):
    """haproxy, HTTP/2 to clients and replicas (`proto h2`), round robin, each replica checked
    actively every 300 ms through grpc.health.v1.Health/Check and taken out at the first answer
    that is not SERVING (NOT_SERVING while it drains, or no answer).

    haproxy 2.6's `http-check send ... body` cannot carry a gRPC request: `body` and `body-lf`
    end at the first NUL byte, and every gRPC message starts with a 5-byte prefix holding NULs
    (a check sending none gets "could not parse request", INVALID_ARGUMENT). So the check is a
    tcp-check that sends a whole HTTP/2 exchange as bytes and expects the SERVING DATA frame
    (grpc_health_check_bytes)."""

    name = "haproxy"

    def command(self):
        return ["haproxy", "-f", self.config, "-db"]

    def config_text(self, backends):
        request, serving = grpc_health_check_bytes()
        servers = "\n".join(
            f"  server r{i} {b} proto h2 check inter 300ms fall 1 rise 1"
            for i, b in enumerate(backends))
        return f"""global
  maxconn 1024
defaults
  mode http
  timeout connect 2s
  timeout client 300s
  timeout server 300s
  timeout check 1s
frontend grpc
  bind 127.0.0.1:{self.port} proto h2
  default_backend afmesh
backend afmesh
  balance roundrobin
  option tcp-check
  tcp-check connect
  tcp-check send-binary {request.hex()}
  tcp-check expect binary {serving.hex()}
{servers}
"""
