#!/usr/bin/env bash
# The test command: installs what is missing, configures, builds and runs every test.
# Usage: scripts/test.sh [PRESET]   (release (default), debug, asan; fuzz runs fuzz/run.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
[[ "$preset" == fuzz ]] && exec fuzz/run.sh "${AFMESH_FUZZ_SECONDS:-30}"
scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset" -j "$(nproc)"
