#!/usr/bin/env bash
# The whole test suite: install what is missing, build (Release), run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SCULPT_BUILD_DIR:-build}
scripts/install-deps.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSCULPT_BUILD_TESTS=ON ${SCULPT_CMAKE_ARGS:-}
cmake --build "$build_dir" -j"$(nproc)"
ctest --test-dir "$build_dir" -j"$(nproc)" --output-on-failure --timeout 600
