#!/usr/bin/env bash
# The long fuzzing run, apart from CI's 30-60 s per target: every libFuzzer
# target to a million executions (or RUNS), seeded from its corpus, new
# inputs kept in a scratch folder. Prints each target's executions and
# whether it found anything; exits 1 on the first finding (its input is
# left in the current folder as crash-*/leak-*/timeout-*).
#
#   bash scripts/fuzz-long.sh [BUILD_DIR] [RUNS] [TARGET...]
# BUILD_DIR holds the fuzz targets (default build-asan: .ci/run's clang
# address,undefined build with SCULPT_BUILD_FUZZ=ON; see it for the
# configure line).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
runs=${2:-1000000}
shift $(( $# < 2 ? $# : 2 ))
targets=("$@")
if ((${#targets[@]} == 0)); then
  targets=(session_file session_text nrrd probe_file hid_report mesh_file text_formats dab_script
           project_file falcon_packet evdev_ff opentrack_datagram vrpn_message evdev_events
           openxr_report vdb_file glb_file)
fi
for target in "${targets[@]}"; do
  case $target in
    session_file) seeds=sim/sessions ;;
    *) seeds=tests/fuzz/corpus/$target ;;
  esac
  work=$(mktemp -d)
  start=$(date +%s)
  mkdir -p "$build/fuzz-artifacts"  # findings go here, not into the checkout
  if ! "$build/bin/${target}_fuzz" "$work" "$seeds" -runs="$runs" -rss_limit_mb=2048 \
       -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/" > "$work.log" 2>&1; then
    tail -n 40 "$work.log"
    echo "fuzz-long: $target found an input that fails (above; saved in $build/fuzz-artifacts)"
    exit 1
  fi
  done_runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work.log" | grep -o '[0-9]*$')
  echo "$target: $done_runs executions, no finding ($(( $(date +%s) - start )) s)"
  rm -rf "$work" "$work.log"
done
