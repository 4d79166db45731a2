#!/usr/bin/env bash
# Builds stochtex from scratch and runs every test (unit, statistical, CLI, fuzz) with CTest.
# Installs the Debian 12 packages it needs first. Usage: bash scripts/test.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
source "$root/scripts/timing.sh"
bash "$root/scripts/install-deps.sh"
phase "Debian packages"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTOCHTEX_WERROR=ON
cmake --build "$build" --parallel
phase "release build"
ctest --test-dir "$build" --output-on-failure --parallel 2
phase "release tests (every tier)"
