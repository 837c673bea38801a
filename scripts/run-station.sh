#!/usr/bin/env bash
# The station's main job: install what is missing, build (Release), run.
# Extra arguments go to `sculpt run`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target sculpt
exec build/bin/sculpt run "$@"
