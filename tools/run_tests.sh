#!/usr/bin/env bash
# Builds fusemap and runs its test suite (the README's second command; .ci/run calls it).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! pkg-config --exists lcm 2>/dev/null || ! command -v lcm-gen >/dev/null || \
   ! dpkg -s libceres-dev libapriltag-dev libgtest-dev >/dev/null 2>&1; then
  echo "[run_tests] dependencies missing: running tools/install_deps.sh"
  bash tools/install_deps.sh
fi
build_dir=${FUSEMAP_BUILD_DIR:-build}
# Tests on explicitly: the demo configures the same build folder with them off.
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DFUSEMAP_BUILD_TESTS=ON
cmake --build "$build_dir" -j"$(nproc)"
cd "$build_dir"
ctest --output-on-failure --no-tests=error -j"$(nproc)" --timeout 900
