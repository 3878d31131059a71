#!/usr/bin/env bash
# The main job on a shipped example: installs what is missing, builds (release preset), then
# prints the counts, validity and quality of examples/cube/cube.msh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target afmesh
build/release/client/afmesh stats examples/cube/cube.msh
