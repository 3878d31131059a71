#!/usr/bin/env bash
# The main job on a shipped example: installs what is missing, builds (release preset), then
# meshes examples/lblock/lblock.stl (an L-shaped block with a through-hole) through the service:
# `afmesh volume` starts a private afmesh-server on a local socket, streams the surface to it,
# receives the tetrahedra and writes build/example/lblock.msh; then `afmesh stats` prints the
# mesh's validity and quality.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target afmesh afmesh-server
mkdir -p build/example
build/release/client/afmesh volume examples/lblock/lblock.stl -o build/example/lblock.msh --size 0.25
build/release/client/afmesh stats build/example/lblock.msh
