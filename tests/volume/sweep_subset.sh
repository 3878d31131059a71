#!/bin/sh
# The CI subset of the robustness sweep (bench/sweep, issue 10 part 1): the first solid of each
# of the twelve families of make_solids.py (fused and cut boxes, cylinder, cone, sphere, torus,
# cavity, thin walls, curvature, through holes, disjoint bodies, random CSG), meshed by the
# afmesh CLI at their surface size and with no --size, each judged by `afmesh stats` and the
# independent ../shared/tools/check_volume.py. Fails when any run is not valid.
# Usage: sweep_subset.sh SOURCE_DIR AFMESH_BINARY
set -eu
src=$1
afmesh=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/afmesh-sweep-XXXXXX")
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$src/bench/sweep/make_solids.py" --count 12 --out "$work/solids" >/dev/null
/usr/bin/python3 "$src/bench/sweep/run_sweep.py" --afmesh "$afmesh" --solids "$work/solids" \
  --out "$work/out" --groups solids --limit 12 --sizes 1,none --timeout 60 --fail-on-invalid
