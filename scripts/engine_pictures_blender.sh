#!/usr/bin/env bash
# Regenerates docs/images/engines/blender_*.png (docs/engines.md, "Blender"): the add-on installed
# in Blender 3.4, a plane showing cobblestone_512 4 x 4 times, rendered by Cycles as the Image
# Texture node shows it and as the add-on's node group does (side by side, one picture), and a
# screenshot of Blender's Shading workspace (the viewport in Material Preview, EEVEE, above the
# Shader Editor with the node group), taken in a window under Xvfb (Mesa's llvmpipe). Installs
# what it needs with scripts/install-deps.sh. The exemplar is MIT (data/exemplars/ATTRIBUTION.md).
# Usage: bash scripts/engine_pictures_blender.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
out="$root/docs/images/engines"
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel 2 --target stochtex stochtex_python blender_addon
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/tmp" "$out"
# Blender's user folders and the add-on's files in the temporary folder, the module from the build.
export BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config TMPDIR=$work/tmp
export PYTHONPATH=$build/python PYTHONDONTWRITEBYTECODE=1
script=$root/scripts/engine_pictures_blender.py
blender -b --factory-startup --python-exit-code 1 -P "$script" -- scene \
  "$build/stochtex_blender_addon.zip" "$build/stochtex" "$root/data/exemplars/cobblestone_512.png" \
  "$work"
xvfb-run -a -s "-screen 0 1440x900x24" blender --factory-startup "$work/stochtex.blend" \
  -P "$script" -- screenshot "$work"
/usr/bin/python3 - "$work" "$out" <<'PY'
import sys
from PIL import Image
work, out = sys.argv[1:]
left, right = Image.open(work + "/image_texture.png"), Image.open(work + "/node_group.png")
gap = 8
both = Image.new("RGB", (left.width + gap + right.width, left.height), "white")
both.paste(left.convert("RGB"), (0, 0))
both.paste(right.convert("RGB"), (left.width + gap, 0))
both.save(out + "/blender_cycles.png", optimize=True)
Image.open(work + "/screenshot.png").convert("RGB").save(out + "/blender_screenshot.png",
                                                           optimize=True)
PY
echo "wrote $out/blender_cycles.png and $out/blender_screenshot.png"
