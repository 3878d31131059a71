#!/usr/bin/env bash
# Builds the seed corpora of the fuzz targets in OUT_DIR/<target>/ (default build/fuzz/corpus):
# the generated seeds of afmesh-fuzz-seeds (a unit cube in every format, MeshVolume request
# streams, mesher fronts) and copies of the real files in tests/data and examples/.
# Usage: fuzz/make_corpora.sh [BUILD_DIR [OUT_DIR]]   (BUILD_DIR: the fuzz preset's, built)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build/fuzz}"
out="${2:-$build_dir/corpus}"
mkdir -p "$out"
"$build_dir/fuzz/afmesh-fuzz-seeds" "$out"

copy() {  # copy TARGET FILES...
  local target="$1"; shift
  mkdir -p "$out/$target"
  for f in "$@"; do
    [[ -f "$f" ]] && cp "$f" "$out/$target/$(echo "$f" | tr / _)"
  done
  return 0
}
copy stl tests/data/*.stl examples/*/*.stl
copy msh tests/data/*.msh examples/*/*.msh
copy medit tests/data/*.mesh examples/*/*.mesh
copy size_spec examples/*/*.json
# The design notes' example specification (design.md, "Size specification").
cat > "$out/size_spec/design_example.json" <<'JSON'
{"maxSize": 0.8, "growth": 1.2, "sources": [
 {"points": [{"x": 0, "y": 0, "z": 0}], "delta0": 0.15, "r0": 1.0, "r1": 0.2,
  "polynomial": {"coefficients": [1.0, 0.0]}},
 {"points": [{"x": 0, "y": 0, "z": 0}, {"x": 1, "y": 0, "z": 0}], "delta0": 0.1, "r0": 0.0,
  "r1": 0.5, "power": {"gamma": 1.5}},
 {"points": [{"x": 0, "y": 0, "z": 1}, {"x": 1, "y": 0, "z": 1}, {"x": 0, "y": 1, "z": 1}],
  "delta0": 0.1, "r0": 0.1, "r1": 1.0, "exponential": {"gamma": 0.7}}]}
JSON
