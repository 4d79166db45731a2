#!/usr/bin/env bash
# Builds stochtex from scratch and runs every test (unit, statistical, CLI, fuzz) with CTest.
# Installs the Debian 12 packages it needs first. Usage: bash scripts/test.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTOCHTEX_WERROR=ON
cmake --build "$build" --parallel
ctest --test-dir "$build" --output-on-failure --parallel 2
