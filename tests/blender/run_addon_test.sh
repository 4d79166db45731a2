#!/usr/bin/env bash
# The Blender add-on in Blender (tests/blender/addon_test.py, docs/engines.md), under Xvfb so that
# EEVEE has an OpenGL context (Mesa's llvmpipe without a GPU): skipped (77, CTest's
# SKIP_RETURN_CODE) where blender or xvfb-run is not installed; scripts/install-deps.sh installs
# both. Blender's user folders point into a temporary folder, so installing the add-on leaves the
# user's own Blender untouched.
#
# usage: run_addon_test.sh ADDON_ZIP STOCHTEX PYTHON_MODULE_DIR EXEMPLAR_DIR
set -euo pipefail
if [[ $# -ne 4 ]]; then
  echo "usage: $0 ADDON_ZIP STOCHTEX PYTHON_MODULE_DIR EXEMPLAR_DIR" >&2
  exit 2
fi
for tool in blender xvfb-run; do
  if ! command -v $tool >/dev/null; then
    echo "$tool is not installed (scripts/install-deps.sh installs it): skipped"
    exit 77
  fi
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/tmp"
BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config TMPDIR=$work/tmp \
  PYTHONPATH=$3 PYTHONDONTWRITEBYTECODE=1 \
  xvfb-run -a -s "-screen 0 640x480x24" blender -b --factory-startup --python-exit-code 1 \
  -P "$(dirname "$0")/addon_test.py" -- "$1" "$2" "$work" "$4"
