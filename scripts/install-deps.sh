#!/usr/bin/env bash
# Installs every build, test and benchmark dependency of stochtex from Debian 12 packages
# (docs/design.md §3). Nothing else is downloaded. Safe to run repeatedly.
# Usage: bash scripts/install-deps.sh [--sanitize]   (--sanitize: also what scripts/sanitize.sh
# needs: clang with its sanitizer and libFuzzer runtimes, and llvm-symbolizer for the reports)
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build clang-format
  libfftw3-dev libpng-dev liblcms2-dev libopenexr-dev libeigen3-dev
  libjpeg-dev libexif-dev libtiff-dev libwebp-dev libstb-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libtinyobjloader-dev
  libgtest-dev libgmock-dev libbenchmark-dev libhwy-dev libxxhash-dev
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
  glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev libcpp-httplib-dev
  libarchive-dev
  # the photo tests (tests/cli/cli_photos.sh) write a JPEG with cjpeg
  libjpeg-turbo-progs
  python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-dask python3-distributed
  python3-zarr
  # the browser test (tests/browser): headless Chromium, its WebDriver and Selenium
  chromium chromium-driver python3-selenium
  # the Blender add-on's test (tests/blender): Blender 3.4, and Xvfb for EEVEE's OpenGL context
  blender xvfb xauth
  # the Unity package's test (tests/unity): mono's C# compiler and runtime (mcs, mono: 16
  # packages, 7.2 MB to download, 25 MB installed)
  mono-mcs
  # the Godot test (tests/godot): Debian's Godot 3.2.3, run headless under Xvfb (above)
  godot3
)
# the three.js test (tests/browser/three_test.py) installs three.js with npm; Debian's npm, unless
# an npm is there already (NodeSource's nodejs has its own, and conflicts with Debian's)
if ! command -v npm >/dev/null; then
  packages+=(npm)
fi
if [[ ${1:-} == --sanitize ]]; then
  packages+=(clang libclang-rt-14-dev llvm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
echo "stochtex: installing ${missing[*]}" >&2
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
