#!/usr/bin/env bash
# The benchmarks: afmesh's volume mesher against gmsh (Delaunay, HXT), netgen and tetgen on the
# same sphere and torus surfaces at about 50k, 500k and 2M tets, core/io converting a
# ~1M-triangle STL to MSH 4.1 against gmsh, the size field's evaluations per second with 1 to
# 1000 sources (afmesh alone: the peers have no source fields), and the thin examples
# (examples/dome, examples/sails: thin shells whose two sides' triangulations cross, environment
# tags as triangle refs) given as they are to afmesh (its CLI, --envs tags and --envs auto) and to
# each peer (tetgen also as plain -p and as -d, which counts the intersecting face pairs), every
# volume mesh checked by afmesh stats and tools/check_volume.py --envs (tets across a gap). Prints
# one table per case; see bench/run_bench.py. Every volume row has mean interior edge / h (h = the
# size asked of that tool) and the share of interior edges in [0.7 h, 1.4 h]. The equal-count
# comparison then adjusts each tool's size (afmesh --size, gmsh MeshSizeMax, netgen maxh, tetgen
# -a) until its tet count is within 10% of each target, and compares tets/s, bytes/tet and
# quality at those equal counts (a failed or timed-out search says so).
#
# Usage: scripts/bench.sh [bench/run_bench.py options]
#   scripts/bench.sh                                   everything (netgen at 2M takes tens of minutes)
#   scripts/bench.sh --netgen-max-target 500k          skip netgen at 2M (the tables say so)
#   scripts/bench.sh --targets 50k,500k --no-io        the quick cases only
#   scripts/bench.sh --sizing-only                     the size-field throughput alone
#   scripts/bench.sh --thin-only                       the thin inputs alone (seconds); --no-thin skips them
#   scripts/bench.sh --shapes sphere --tools afmesh,tetgen --size sphere:2M=0.031
#   scripts/bench.sh --equal-count-only                equal counts alone, 50k tets (a few minutes)
#   scripts/bench.sh --equal-count-only --count-targets 50k,500k,2M --count-timeout 3600
#                                                      also at 500k and 2M (netgen: tens of minutes)
#   scripts/bench.sh --no-equal-count                  the equal-size tables without it
# Environment: AFMESH_BENCH_BUILD_DIR (default build/release, the release preset),
#              AFMESH_BENCH_JOBS (build parallelism, default 2),
#              AFMESH_CHECK_VOLUME (the independent checker, default ../shared/tools/check_volume.py).
# Run it on an otherwise idle machine: each measurement is one thread, one process at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --peers

build_dir="${AFMESH_BENCH_BUILD_DIR:-build/release}"
if [[ -z "${AFMESH_BENCH_BUILD_DIR:-}" ]]; then
  cmake --preset release >/dev/null
else
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build_dir" --target afmesh-bench-volume afmesh-bench-io \
  afmesh-bench-sizing afmesh afmesh-server make-thin-examples -j "${AFMESH_BENCH_JOBS:-2}"

exec /usr/bin/python3 bench/run_bench.py --build-dir "$build_dir" \
  --work-dir "$build_dir/bench-work" "$@"
