#!/usr/bin/env bash
# Runs libFuzzer targets one after the other (./dev fuzz calls this).
#
#   fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]
#
# TARGET is query_csv, truth, pairs, ply, scene, query_kernels, planar,
# point_kinds or expansion_stage (default: all).
# Each target starts from the corpus it grew before (BUILD_DIR/corpus/T),
# the seeds cut from ../shared/data (BUILD_DIR/seeds/T) and the hand-written
# ones (fuzz/seeds/T). A finding is saved as BUILD_DIR/artifacts/T-crash-...
# (reproduce: BUILD_DIR/fuzz/fuzz_T FILE) and fails the run; a finding
# becomes a regression test in tests/test_bad_input.cpp.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${1:?usage: fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(query_csv truth pairs ply scene query_kernels planar point_kinds expansion_stage)

# A small quarantine keeps the kernel target's memory flat over long runs.
export ASAN_OPTIONS=${ASAN_OPTIONS:-quarantine_size_mb=64:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

failed=0
for target in "${targets[@]}"; do
  binary="$build_dir/fuzz/fuzz_$target"
  corpus="$build_dir/corpus/$target"
  log="$build_dir/logs/$target.log"
  mkdir -p "$corpus" "$build_dir/artifacts" "$build_dir/logs"
  inputs=("$corpus")
  for seeds in "$build_dir/seeds/$target" "fuzz/seeds/$target"; do
    [ -d "$seeds" ] && inputs+=("$seeds")
  done
  options=(-max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 -print_final_stats=1
           -artifact_prefix="$build_dir/artifacts/$target-")
  [ -f "fuzz/seeds/$target.dict" ] && options+=(-dict="fuzz/seeds/$target.dict")
  echo "fuzz_$target: ${seconds}s, log in $log"
  status=0
  "$binary" "${options[@]}" "${inputs[@]}" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  if [ "$status" -ne 0 ]; then
    failed=1
    echo "fuzz_$target: FINDING (exit $status); the end of $log:"
    tail -n 30 "$log"
  else
    echo "fuzz_$target: ${runs:-?} executions, no finding"
  fi
done
exit "$failed"
