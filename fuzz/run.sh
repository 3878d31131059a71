#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 30), one after the other, on its seed corpus
# (fuzz/make_corpora.sh) plus what earlier runs found (build/fuzz/corpus/<target>, kept between
# runs). Prints one line per target: executions, exec/s, coverage (libFuzzer's cov: edges and
# ft: features) and corpus size. A crash, leak, sanitizer report or an input slower than
# AFMESH_FUZZ_TIMEOUT seconds (default 10) fails the run; the input is saved as
# build/fuzz/artifacts/<target>/crash-* (or timeout-*, leak-*) and the log is printed.
# Usage: fuzz/run.sh [SECONDS] [TARGET...]   (builds the fuzz preset first)
# Environment: AFMESH_FUZZ_JOBS (build parallelism, default 2), AFMESH_FUZZ_TIMEOUT.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
shift || true
targets=("$@")
[[ ${#targets[@]} -eq 0 ]] && targets=(stl obj msh medit medit_sol size_spec volume_request
  volume_mesher surface_request surface_mesher delaunay)

scripts/install-deps.sh --fuzz
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "${AFMESH_FUZZ_JOBS:-2}"
build=build/fuzz
fuzz/make_corpora.sh "$build" "$build/seeds"

failed=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" artifacts="$build/artifacts/$t" log="$build/logs/$t.log"
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  rc=0
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout="${AFMESH_FUZZ_TIMEOUT:-10}" \
    -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "$corpus" "$build/seeds/$t" >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\) ft: \([0-9]*\) corp: \([0-9]*\).*/edges \1, features \2, corpus \3/p' <<<"$last")
  printf '%-16s %4ss  runs %-9s exec/s %-6s %s\n' "$t" "$seconds" "${runs:-?}" "${rate:-?}" "$cov"
  if [[ $rc -ne 0 ]]; then
    echo "fuzz_$t FAILED (exit $rc); input in $artifacts/, log $log:" >&2
    grep -E -A30 '^==[0-9]+==ERROR|runtime error|ALARM|deadly signal|abort' "$log" | head -60 >&2 || tail -40 "$log" >&2
    failed=1
  fi
done
exit "$failed"
