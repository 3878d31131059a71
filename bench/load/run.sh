#!/usr/bin/env bash
# The load driver, one command: bench/load/run.sh faults|scaleout [OPTIONS] (--help for them).
# Generates the Python stubs of proto/afmesh/v1 into a temporary folder (protoc and Debian's
# grpc_python_plugin; python3-grpcio has no grpc_tools) and runs bench/load/afmesh_load.py with
# Debian's /usr/bin/python3. AFMESH_BUILD picks the build folder (default build/release).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
stubs="$(mktemp -d -t afmesh-load-stubs.XXXXXX)"
trap 'rm -rf "$stubs"' EXIT
protoc -I "$root/proto" --python_out="$stubs" --grpc_python_out="$stubs" \
  --plugin=protoc-gen-grpc_python="$(command -v grpc_python_plugin)" \
  "$root/proto/afmesh/v1/mesher.proto"
status=0
PYTHONPATH="$stubs:$here:$root/deploy" /usr/bin/python3 "$here/afmesh_load.py" \
  --build "${AFMESH_BUILD:-$root/build/release}" "$@" || status=$?
exit "$status"
