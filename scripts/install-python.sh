#!/usr/bin/env bash
# Builds the Python module and installs it for the user's /usr/bin/python3 (docs/python.md):
# the package build/python/stochtex is copied into `python3 -m site --user-site`. Nothing is
# downloaded beyond the Debian 12 packages of scripts/install-deps.sh (Debian's pip refuses user
# installs, PEP 668, so pip is not used). Usage: bash scripts/install-python.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
python=/usr/bin/python3
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTOCHTEX_BUILD_PYTHON=ON
cmake --build "$build" --target stochtex_python
site="$("$python" -m site --user-site)"
mkdir -p "$site"
rm -rf "$site/stochtex"
cp -r "$build/python/stochtex" "$site/stochtex"
(cd / && "$python" -c "import stochtex; print('stochtex: installed', stochtex.__file__)")
