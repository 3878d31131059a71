#!/usr/bin/python3
"""afmesh-health-probe ADDR [SERVICE]: exit 0 when ADDR answers grpc.health.v1.Health/Check
with SERVING, 1 otherwise (NOT_SERVING while the server drains, unreachable, timeout).

The image's HEALTHCHECK (Kubernetes uses its native gRPC probe instead). Raw bytes keep it free
of generated code: HealthCheckRequest is field 1 (service, string); HealthCheckResponse is
field 1 (status, enum; SERVING = 1). To be replaced by an `afmesh health` subcommand when the
CLI gets one (client/ is not part of deploy/)."""
import sys

import grpc


def request_bytes(service: str) -> bytes:
    data = service.encode()
    assert len(data) < 128, "service name too long for a one-byte length"
    return b"\x0a" + bytes([len(data)]) + data if data else b""


def is_serving(response: bytes) -> bool:
    return response == b"\x08\x01"  # status = SERVING; nothing else in a Check response


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print(__doc__.splitlines()[0], file=sys.stderr)
        return 2
    address, service = sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else ""
    with grpc.insecure_channel(address) as channel:
        check = channel.unary_unary("/grpc.health.v1.Health/Check")
        try:
            response = check(request_bytes(service), timeout=2.0)
        except grpc.RpcError as error:
            print(f"afmesh-health-probe: {address}: {error.code().name}: {error.details()}",
                  file=sys.stderr)
            return 1
    if not is_serving(response):
        print(f"afmesh-health-probe: {address}: not SERVING ({response.hex()})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
