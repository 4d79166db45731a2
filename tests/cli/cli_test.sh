#!/usr/bin/env bash
# The `stochtex` command as a user meets it (docs/design.md §6 and §9). Every bad input must
# exit with its code (1 runtime failure, 2 usage error), print exactly one line on stderr starting
# with "stochtex: error:", and leave no output file behind, not even a temporary one. The good
# paths must work, print valid JSON where asked, and render the same bytes whatever the threads.
#
# usage: cli_test.sh STOCHTEX_BINARY TEXTURE_DIR
set -u

if [[ $# -ne 2 ]]; then
  echo "usage: $0 STOCHTEX_BINARY TEXTURE_DIR" >&2
  exit 2
fi
stochtex=$1
textures=$2
exemplar=$textures/grass_lawn_128.png
for required in "$stochtex" "$exemplar"; do
  if [[ ! -f $required ]]; then
    echo "cli_test: $required does not exist" >&2
    exit 2
  fi
done
if ! command -v python3 >/dev/null; then
  echo "cli_test: python3 is needed to check JSON output and to write test images" >&2
  exit 2
fi

work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
inputs=$work/in     # bad and good inputs, made below
models=$work/models # outputs of the good paths
out=$work/out       # where failing commands are told to write: must stay empty
mkdir -p "$inputs" "$models" "$out"

passed=0
failed=()

pass() { passed=$((passed + 1)); }
fail() {
  failed+=("$1")
  echo "FAIL: $1: $2"
  if [[ -s $work/stderr ]]; then sed 's/^/  stderr: /' "$work/stderr"; fi
}

# Runs the command with stdout and stderr captured in $work/stdout and $work/stderr; sets $status.
capture() {
  "$@" >"$work/stdout" 2>"$work/stderr"
  status=$?
}

# Checks a failure after `capture`: exit code, one "stochtex: error:" line, no file left in $out.
# With mention non-empty, the sentence must also name it (the bad file).
check_failure() {
  local name=$1 code=$2 mention=$3 lines
  lines=$(wc -l <"$work/stderr")
  if [[ $status -ne $code ]]; then
    fail "$name" "exit code $status, expected $code"
  elif [[ $lines -ne 1 ]] || ! head -n 1 "$work/stderr" | grep -q '^stochtex: error: .'; then
    fail "$name" "stderr is $lines line(s), expected one 'stochtex: error: ...' line"
  elif [[ -n $mention ]] && ! grep -qF -- "$mention" "$work/stderr"; then
    fail "$name" "the message does not name '$mention'"
  elif [[ -n $(find "$out" -mindepth 1 -print -quit) ]]; then
    fail "$name" "left output behind: $(find "$out" -mindepth 1 | tr '\n' ' ')"
  else
    pass
  fi
  find "$out" -mindepth 1 -delete
}

# expect_error NAME CODE MENTION COMMAND...: a bad input the CLI itself diagnoses.
expect_error() {
  local name=$1 code=$2 mention=$3
  shift 3
  capture "$@"
  check_failure "$name" "$code" "$mention"
}

# expect_parse_error NAME COMMAND...: rejected by the option parser (CLI11), whose own message
# is accepted; the exit code must still be 2 and nothing may be written.
expect_parse_error() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 2 ]]; then
    fail "$name" "exit code $status, expected 2"
  elif [[ ! -s $work/stderr ]]; then
    fail "$name" "no message on stderr"
  elif [[ -n $(find "$out" -mindepth 1 -print -quit) ]]; then
    fail "$name" "left output behind"
  else
    pass
  fi
  find "$out" -mindepth 1 -delete
}

# expect_ok NAME COMMAND...: exit code 0.
expect_ok() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 0 ]]; then
    fail "$name" "exit code $status, expected 0"
    return 1
  fi
  pass
}

# expect_readme_files NAME DIR: every GLSL and data file an export's README names was written.
expect_readme_files() {
  local name=$1 dir=$2 files missing=""
  files=$(grep -o '`[A-Za-z0-9_]*\.\(png\|exr\|glsl\)`' "$dir/README.md" | tr -d '`' | sort -u)
  for file in $files; do
    [[ -s $dir/$file ]] || missing+=" $file"
  done
  if [[ -z $files ]]; then
    fail "$name" "the README names no file"
  elif [[ -n $missing ]]; then
    fail "$name" "missing:$missing"
  else
    pass
  fi
}

# expect_json NAME COMMAND...: exit code 0 and stdout is one valid JSON document.
expect_json() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 0 ]]; then
    fail "$name" "exit code $status, expected 0"
  elif ! python3 -c 'import json,sys; json.load(sys.stdin)' <"$work/stdout" 2>/dev/null; then
    fail "$name" "stdout is not one valid JSON document"
  else
    pass
  fi
}

# expect_file NAME PATH: a good path wrote a non-empty file and no temporary beside it.
expect_file() {
  local name=$1 path=$2 leftovers
  leftovers=$(find "$(dirname "$path")" -name '*.tmp*' | tr '\n' ' ')
  if [[ ! -s $path ]]; then
    fail "$name" "did not write $path"
  elif [[ -n $leftovers ]]; then
    fail "$name" "left temporaries: $leftovers"
  else
    pass
  fi
}

# --- inputs -------------------------------------------------------------------------------------

printf 'this is not an image\n' >"$inputs/x.png"
head -c 2000 "$exemplar" >"$inputs/truncated.png"
# Minimal 8-bit PNGs: a 1x1 grey image, a constant 16x16 one, and 2048² and 4096² colour ramps.
python3 - "$inputs" <<'EOF'
import struct, sys, zlib

def png(path, width, height, row, colour_type=0):
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n"
                + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress((b"\x00" + row) * height))
                + chunk(b"IEND", b""))

png(sys.argv[1] + "/one_pixel.png", 1, 1, bytes([128]))
png(sys.argv[1] + "/constant.png", 16, 16, bytes([128]) * 16)
png(sys.argv[1] + "/ramp_2048.png", 2048, 2048, bytes(range(256)) * 24, colour_type=2)
png(sys.argv[1] + "/ramp_4096.png", 4096, 4096, bytes(range(256)) * 48, colour_type=2)
EOF
# A 4x4 greyscale PFM (negative scale: little-endian) alternating 0.25 and 0.75, one pixel NaN.
{
  printf 'Pf\n4 4\n-1.0\n'
  for i in $(seq 0 15); do
    if [[ $i -eq 5 ]]; then
      printf '\x00\x00\xc0\x7f'
    elif ((i % 2)); then
      printf '\x00\x00\x40\x3f'
    else
      printf '\x00\x00\x80\x3e'
    fi
  done
} >"$inputs/nan.pfm"

# --- good paths ---------------------------------------------------------------------------------

model=$models/grass.stx
size=(--size 64x64)
fast=(-m texton -p support=32)

expect_ok "methods" "$stochtex" methods && if ! grep -q texton "$work/stdout"; then
  fail "methods lists texton" "stdout does not mention texton"
fi
expect_json "methods --json" "$stochtex" methods --json
# Every method of the registry, never a list written here: a new method is covered by itself.
methods=$(python3 -c 'import json, sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))' \
  <"$work/stdout")
if [[ -z $methods ]]; then fail "methods --json lists methods" "no method names"; fi
expect_ok "languages" "$stochtex" languages && if ! grep -q "^glsl: GLSL 4.50" "$work/stdout"; then
  fail "languages lists glsl" "stdout does not start a line with glsl: GLSL 4.50"
fi
expect_json "languages --json" "$stochtex" languages --json
# Every export language of the table (src/gl/languages.hpp), never a list written here; the
# cross-compiled ones are all but glsl, the methods' own source.
languages=$(python3 -c 'import json, sys; print(" ".join(l["name"] for l in json.load(sys.stdin)))' \
  <"$work/stdout")
cross_languages=$(tr ' ' '\n' <<<"$languages" | grep -vx glsl | tr '\n' ' ')
if [[ -z $cross_languages ]]; then fail "languages --json lists languages" "no language names"; fi
expect_ok "--help" "$stochtex" --help
for command in analyze mix render render-mesh synth gaussian compare info edit methods languages \
  report studio; do
  expect_ok "$command --help" "$stochtex" "$command" --help
done
expect_parse_error "studio --port out of range" "$stochtex" studio --port 70000

if expect_ok "analyze" "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$model"; then
  expect_file "analyze writes the model" "$model"
fi
expect_ok "info" "$stochtex" info "$model"
expect_json "info --json" "$stochtex" info "$model" --json
# Enumerated parameters go in and come out by name.
expect_ok "analyze -p blend=variance" "$stochtex" analyze "$exemplar" -m tiling -p blend=variance \
  -o "$models/variance.stx" && expect_ok "info of a named choice" "$stochtex" info \
  "$models/variance.stx" && if ! grep -q "blend = variance" "$work/stdout"; then
  fail "info names the blend" "stdout does not show blend = variance"
fi
for extension in png exr pfm; do
  expect_ok "render .$extension" "$stochtex" render "$model" -o "$models/render.$extension" \
    "${size[@]}" --seed 3 && expect_file "render writes .$extension" "$models/render.$extension"
done
expect_ok "render zoomed out, supersampled" "$stochtex" render "$model" -o "$models/zoom.png" \
  "${size[@]}" --origin 1e7,-2.5 --scale 4 --supersample 2
expect_ok "synth" "$stochtex" synth "$exemplar" "${fast[@]}" -o "$models/synth.png" "${size[@]}" &&
  expect_file "synth writes the image" "$models/synth.png"
expect_ok "gaussian" "$stochtex" gaussian "$exemplar" -o "$models/gaussian.png" --size 128x128 &&
  expect_file "gaussian writes the image" "$models/gaussian.png"
expect_ok "compare" "$stochtex" compare "$exemplar" "$models/gaussian.png"
expect_json "compare --json" "$stochtex" compare "$exemplar" "$models/gaussian.png" --json
expect_ok "gaussian seed 2" "$stochtex" gaussian "$exemplar" -o "$models/gaussian2.png" \
  --size 128x128 --seed 2
capture "$stochtex" compare "$exemplar" "$models/gaussian.png" "$models/gaussian2.png" --json
if [[ $status -ne 0 ]] || ! python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["images"] == [sys.argv[1], sys.argv[2]]
assert "averaged_spectral_error" in d and "averaged_spectral_error_adsn" in d
assert d["averaged_spectral_error"] < d["spectral_error"]' "$models/gaussian.png" \
  "$models/gaussian2.png" <"$work/stdout"; then
  fail "compare of two renders" "no averaged spectral error below the single ones in its JSON"
else
  pass
fi
expect_error "compare renders of two sizes" 1 "first image is 128x128" \
  "$stochtex" compare "$exemplar" "$models/gaussian.png" "$models/render.png"

# The output is a pure function of (model, grid, seed): threads and tiles change nothing.
expect_ok "render seed 5, 1 thread" "$stochtex" render "$model" -o "$models/t1.pfm" "${size[@]}" \
  --seed 5 --threads 1
expect_ok "render seed 5, 2 threads" "$stochtex" render "$model" -o "$models/t2.pfm" "${size[@]}" \
  --seed 5 --threads 2 --tile 16
expect_ok "render seed 6" "$stochtex" render "$model" -o "$models/s6.pfm" "${size[@]}" --seed 6
if cmp -s "$models/t1.pfm" "$models/t2.pfm"; then pass; else
  fail "same seed, 1 and 2 threads" "the renders differ"
fi
if [[ -s $models/s6.pfm ]] && ! cmp -s "$models/t1.pfm" "$models/s6.pfm"; then pass; else
  fail "different seeds" "the renders are identical"
fi

# Every CPU target gives the scalar reference's bytes (tests/unit/cpu_target_test.cpp forces each).
expect_ok "analyze lrp" "$stochtex" analyze "$exemplar" -m lrp -p cosines=12 -o "$models/lrp.stx"
for target in reference best; do
  expect_ok "render --cpu-target $target" "$stochtex" render "$models/lrp.stx" \
    -o "$models/cpu_$target.pfm" --size 40x30 --scale 3 --seed 4 --cpu-target "$target"
done
if [[ -s $models/cpu_best.pfm ]] && cmp -s "$models/cpu_reference.pfm" "$models/cpu_best.pfm"; then
  pass
else
  fail "--cpu-target reference and best" "the renders differ"
fi
expect_parse_error "unknown --cpu-target" "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" \
  --cpu-target neon

# The OpenGL backend (llvmpipe without a GPU): same grid and seed, same picture as the CPU.
expect_ok "render --backend gl" "$stochtex" render "$model" -o "$models/gl.png" --size 48x40 \
  --seed 5 --backend gl && expect_file "render --backend gl writes the image" "$models/gl.png"
expect_ok "render tiling --backend gl" "$stochtex" synth "$exemplar" -m tiling -p transport=1 \
  -o "$models/tiling_gl.png" --size 40x32 --backend gl &&
  expect_file "synth tiling --backend gl writes the image" "$models/tiling_gl.png"
expect_ok "render --gl-filter hardware" "$stochtex" render "$model" -o "$models/gl_hw.png" \
  --size 32x32 --scale 4 --backend gl --gl-filter hardware &&
  expect_file "render --gl-filter hardware writes the image" "$models/gl_hw.png"
expect_parse_error "unknown --gl-filter" "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" \
  --backend gl --gl-filter bicubic
expect_parse_error "unknown backend" "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" \
  --backend vulkan
expect_error "--supersample with --backend gl" 2 "--supersample" \
  "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" --backend gl --supersample 2

# Each method with its defaults: analysis, info, a CPU and a GPU render, the shader export.
for method in $methods; do
  each=$models/every_$method
  if expect_ok "analyze -m $method" "$stochtex" analyze "$exemplar" -m "$method" -o "$each.stx"; then
    expect_json "info $method --json" "$stochtex" info "$each.stx" --json
    expect_ok "render $method" "$stochtex" render "$each.stx" -o "$each.png" --size 24x24 &&
      expect_file "render $method writes the image" "$each.png"
    expect_ok "render $method --backend gl" "$stochtex" render "$each.stx" -o "${each}_gl.png" \
      --size 24x24 --backend gl && expect_file "render $method --backend gl" "${each}_gl.png"
    expect_ok "export-shader $method" "$stochtex" export-shader "$each.stx" -o "${each}_shader" &&
      expect_file "export-shader $method writes the GLSL" "${each}_shader/stochtex_$method.glsl"
    expect_ok "export-shader $method --variant fast" "$stochtex" export-shader "$each.stx" \
      -o "${each}_fast" --variant fast &&
      expect_readme_files "export-shader $method --variant fast writes its README's files" \
        "${each}_fast"
    # The fast variant in every language (gabor's float-only shader included).
    for language in $cross_languages; do
      expect_ok "export-shader $method --variant fast --language $language" "$stochtex" \
        export-shader "$each.stx" -o "${each}_fast_$language" --variant fast --language "$language" &&
        expect_readme_files "export-shader $method --variant fast --language $language writes" \
          "${each}_fast_$language"
    done
  fi
done

expect_parse_error "unknown --variant" "$stochtex" export-shader "$model" -o "$out/shader" \
  --variant fastest
expect_ok "export-shader" "$stochtex" export-shader "$model" -o "$models/shader" &&
  expect_file "export-shader writes the GLSL" "$models/shader/stochtex_texton.glsl" &&
  expect_file "export-shader writes the atlas" "$models/shader/texton_atlas.exr" &&
  expect_file "export-shader writes the README" "$models/shader/README.md"
if expect_ok "analyze gabor" "$stochtex" analyze "$exemplar" -m gabor -p impulses=64 \
  -o "$models/gabor.stx"; then
  expect_ok "render gabor --backend gl" "$stochtex" render "$models/gabor.stx" \
    -o "$models/gabor_gl.png" --size 24x24 --backend gl &&
    expect_file "render gabor --backend gl writes the image" "$models/gabor_gl.png"
  expect_ok "export-shader gabor" "$stochtex" export-shader "$models/gabor.stx" \
    -o "$models/gabor_shader" &&
    expect_file "export-shader gabor writes the GLSL" "$models/gabor_shader/stochtex_gabor.glsl" &&
    expect_file "export-shader gabor writes the data" "$models/gabor_shader/gabor_data.exr"
fi

# export-shader --language: each target's files; a language the model cannot be written in
# (gabor's doubles), an unknown language and folders that cannot take the files are refused with
# nothing written. (tests/gl/export_language_test.cpp compiles and runs what is written.)
for language in $cross_languages; do
  expect_ok "export-shader --language $language" "$stochtex" export-shader "$model" \
    -o "$models/shader_$language" --language "$language" &&
    expect_file "export-shader --language $language writes the README" \
      "$models/shader_$language/README.md" &&
    expect_file "export-shader --language $language writes the atlas" \
      "$models/shader_$language/texton_atlas.exr"
done
expect_file "export-shader --language essl writes the GLSL ES" "$models/shader_essl/stochtex_texton.essl"
expect_file "export-shader --language hlsl writes the HLSL" "$models/shader_hlsl/stochtex_texton.hlsl"
expect_file "export-shader --language hlsl writes the Shader Graph function" \
  "$models/shader_hlsl/stochtex_texton_shadergraph.hlsl"
expect_file "export-shader --language msl writes the Metal" "$models/shader_msl/stochtex_texton.metal"
if expect_ok "export-shader --language glsl" "$stochtex" export-shader "$model" \
  -o "$models/shader_glsl" --language glsl; then
  if cmp -s "$models/shader/stochtex_texton.glsl" "$models/shader_glsl/stochtex_texton.glsl"; then
    pass
  else
    fail "export-shader --language glsl" "differs from the default export"
  fi
fi
if [[ -f $models/gabor.stx ]]; then
  for language in $cross_languages; do
    expect_error "export-shader gabor --language $language" 2 "float-only shader with --variant fast" \
      "$stochtex" export-shader "$models/gabor.stx" -o "$out/gabor_$language" --language "$language"
  done
fi
expect_parse_error "unknown --language" "$stochtex" export-shader "$model" -o "$out/shader" \
  --language wgsl
touch "$inputs/not_a_folder"
expect_error "export-shader into a path below a file" 1 "not_a_folder" \
  "$stochtex" export-shader "$model" -o "$inputs/not_a_folder/shader" --language hlsl
# One of the files' places is a folder: refused before any file is written.
mkdir -p "$work/taken/README.md"
capture "$stochtex" export-shader "$model" -o "$work/taken" --language essl
if [[ $status -ne 1 ]]; then
  fail "export-shader into a folder holding README.md/" "exit code $status, expected 1"
elif [[ -n $(find "$work/taken" -type f -print -quit) ]]; then
  fail "export-shader into a folder holding README.md/" "wrote $(find "$work/taken" -type f)"
else
  pass
fi

# lrp structure preservation (section 5) and continuous targets (section 6.1, figure 10).
expect_ok "analyze lrp with structure" "$stochtex" analyze "$exemplar" -m lrp -p cosines=10 \
  -p ratio=0.3 -p turbulence=2 -o "$models/lrp_structure.stx" &&
  expect_ok "render lrp with structure" "$stochtex" render "$models/lrp_structure.stx" \
    -o "$models/lrp_structure.png" "${size[@]}" &&
  expect_file "render lrp with structure writes the image" "$models/lrp_structure.png"
expect_ok "render lrp with structure --backend gl" "$stochtex" render \
  "$models/lrp_structure.stx" -o "$models/lrp_structure_gl.png" "${size[@]}" --backend gl &&
  expect_file "render lrp with structure --backend gl writes the image" \
    "$models/lrp_structure_gl.png"
expect_ok "analyze --target ring" "$stochtex" analyze --method lrp \
  --target ring:radius=0.2,width=0.02 -p cosines=5 -p strata=1 -o "$models/ring.stx" &&
  expect_ok "render a ring target" "$stochtex" render "$models/ring.stx" -o "$models/ring.png" \
    "${size[@]}" && expect_file "render a ring target writes the image" "$models/ring.png"
expect_ok "analyze --target gaussian" "$stochtex" analyze --method lrp \
  --target gaussian:cx=0.1,cy=0.05,along=0.03,across=0.01,variance=0.02,mean=0.4,size=64 \
  -o "$models/gaussian_target.stx"
target_to=(-o "$out/target.stx")
expect_error "--target of an unknown kind" 2 "blob" \
  "$stochtex" analyze --method lrp --target blob:radius=0.2 "${target_to[@]}"
expect_error "--target missing a key" 2 "width" \
  "$stochtex" analyze --method lrp --target ring:radius=0.2 "${target_to[@]}"
expect_error "--target with a bad number" 2 "0.2x" \
  "$stochtex" analyze --method lrp --target ring:radius=0.2x,width=0.02 "${target_to[@]}"
expect_error "--target with an unknown key" 2 "foo" \
  "$stochtex" analyze --method lrp --target ring:radius=0.2,width=0.02,foo=1 "${target_to[@]}"
expect_error "--target out of range" 2 "radius" \
  "$stochtex" analyze --method lrp --target ring:radius=0.9,width=0.02 "${target_to[@]}"
expect_error "--target with an odd size" 2 "size" \
  "$stochtex" analyze --method lrp --target ring:radius=0.2,width=0.02,size=33 "${target_to[@]}"
expect_error "--target for another method" 2 "texton" \
  "$stochtex" analyze --method texton --target ring:radius=0.2,width=0.02 "${target_to[@]}"
expect_error "--target with ratio > 0" 2 "phases" \
  "$stochtex" analyze --method lrp --target ring:radius=0.2,width=0.02 -p ratio=0.2 \
  "${target_to[@]}"
expect_error "analyze without INPUT or --target" 2 "INPUT" \
  "$stochtex" analyze --method lrp "${target_to[@]}"
expect_parse_error "analyze with INPUT and --target" "$stochtex" analyze "$exemplar" \
  --method lrp --target ring:radius=0.2,width=0.02 "${target_to[@]}"
expect_error "lrp ratio out of range" 2 "ratio" \
  "$stochtex" analyze "$exemplar" -m lrp -p ratio=1.5 "${target_to[@]}"

# Editing a gabor model (section 8 of the Gabor noise paper): groups, then an edit of one group.
gabor_model=$models/gabor.stx
if expect_ok "analyze gabor" "$stochtex" analyze "$exemplar" -m gabor -p iterations=30 \
  -o "$gabor_model"; then
  expect_ok "edit --list-groups" "$stochtex" edit "$gabor_model" --list-groups &&
    if ! grep -q anisotropic "$work/stdout"; then
      fail "edit --list-groups lists the groups" "stdout does not mention anisotropic"
    fi
  expect_json "edit --list-groups --json" "$stochtex" edit "$gabor_model" --list-groups --json
  expect_ok "edit a group" "$stochtex" edit "$gabor_model" -o "$models/edited.stx" \
    --group stochastic --rotate 30 --scale 1.2 --translate 0.01,-0.02 --magnitude 0.5 \
    --bandwidth 2 && expect_file "edit writes the model" "$models/edited.stx"
  expect_ok "render the edited model" "$stochtex" render "$models/edited.stx" \
    -o "$models/edited.png" --size 32x32
  expect_ok "render the unedited model" "$stochtex" render "$gabor_model" \
    -o "$models/unedited.png" --size 32x32
  if [[ -s $models/edited.png ]] && ! cmp -s "$models/edited.png" "$models/unedited.png"; then
    pass
  else
    fail "edit changes the render" "the edited and unedited renders are identical"
  fi
fi

# The comparison report: two small exemplars, every method, small renders. The pages and pictures
# must exist and the JSON summary must hold finite, plausible numbers for every synthesis.
report=$models/report
second=$textures/nuts_grey_256.png
if expect_json "report --json" "$stochtex" report "$exemplar" "$second" -o "$report" \
  --size 32x32 --json; then
  for file in index.html report.json grass_lawn_128.html nuts_grey_256.html \
    grass_lawn_128/exemplar.png grass_lawn_128/gaussian_spectrum.png \
    nuts_grey_256/gabor.png nuts_grey_256/tiling_histogram.png; do
    expect_file "report writes $file" "$report/$file"
  done
  if python3 - "$work/stdout" $methods <<'PY'; then
import json, math, sys
doc = json.load(open(sys.argv[1]))
assert [e["name"] for e in doc["exemplars"]] == ["grass_lawn_128", "nuts_grey_256"]
assert doc["failures"] == 0 and doc["wall_seconds"] > 0 and doc["cpu_seconds"] > 0
for exemplar in doc["exemplars"]:
    names = [s["name"] for s in exemplar["syntheses"]]
    assert names == ["gaussian"] + sys.argv[2:], names
    assert 0 < exemplar["histogram_error_floor"] < 0.5
    for synthesis in exemplar["syntheses"]:
        for key in ("spectral_error", "histogram_error", "mean_error", "covariance_error",
                    "nonstationarity"):
            assert math.isfinite(synthesis[key]) and 0 <= synthesis[key] < 5, (key, synthesis)
        if synthesis["name"] != "gaussian":
            assert synthesis["analysis_seconds"] > 0 and synthesis["ns_per_sample"] > 0, synthesis
PY
    pass
  else
    fail "report JSON numbers" "the summary's numbers are not sane"
  fi
fi
# Same inputs and seed, other threads and the exemplar twice: the same pictures, byte for byte.
if expect_ok "report --threads 1, an exemplar twice" "$stochtex" report "$exemplar" "$exemplar" \
  -o "$models/report1" --size 32x32 --methods tiling,texton --threads 1 --thumbnail 16; then
  expect_file "report --thumbnail writes thumbnails" \
    "$models/report1/thumbnails/grass_lawn_128_2_tiling.png"
  for picture in tiling.png texton.png texton_spectrum.png gaussian.png; do
    if cmp -s "$report/grass_lawn_128/$picture" "$models/report1/grass_lawn_128/$picture" &&
      cmp -s "$report/grass_lawn_128/$picture" "$models/report1/grass_lawn_128_2/$picture"; then
      pass
    else
      fail "report is deterministic ($picture)" "the pictures differ between runs"
    fi
  done
fi

# --- bad inputs ---------------------------------------------------------------------------------

analyze_to=(-o "$out/model.stx")
expect_error "missing input file" 1 "missing.png" \
  "$stochtex" analyze "$inputs/missing.png" -m texton "${analyze_to[@]}"
expect_error "text file named .png" 1 "x.png" \
  "$stochtex" analyze "$inputs/x.png" -m texton "${analyze_to[@]}"
expect_error "truncated PNG" 1 "truncated.png" \
  "$stochtex" analyze "$inputs/truncated.png" -m texton "${analyze_to[@]}"
expect_error "1x1 PNG" 1 "one_pixel.png" \
  "$stochtex" analyze "$inputs/one_pixel.png" -m texton "${analyze_to[@]}"
expect_error "constant PNG" 1 "constant.png" \
  "$stochtex" analyze "$inputs/constant.png" -m texton "${analyze_to[@]}"
expect_error "PFM with a NaN" 1 "nan.pfm" \
  "$stochtex" analyze "$inputs/nan.pfm" -m texton "${analyze_to[@]}"
# 2048² in colour: about 4.1 GB for gabor's analysis (docs/design.md §9), refused before any work.
expect_error "analysis beyond the memory budget" 2 "ramp_2048.png" \
  "$stochtex" analyze "$inputs/ramp_2048.png" -m gabor "${analyze_to[@]}"
expect_error "synth of a truncated PNG" 1 "truncated.png" \
  "$stochtex" synth "$inputs/truncated.png" "${fast[@]}" -o "$out/synth.png" "${size[@]}"
expect_error "gaussian of a constant PNG" 1 "constant.png" \
  "$stochtex" gaussian "$inputs/constant.png" -o "$out/gaussian.png" "${size[@]}"
expect_error "compare with a missing image" 1 "missing.png" \
  "$stochtex" compare "$exemplar" "$inputs/missing.png"

expect_error "unknown method" 2 "nosuch" \
  "$stochtex" analyze "$exemplar" -m nosuch "${analyze_to[@]}"
for param in support=1 mni=0 order=2; do
  expect_error "out-of-range -p $param" 2 "${param%%=*}" \
    "$stochtex" analyze "$exemplar" -m texton -p "$param" "${analyze_to[@]}"
done
expect_error "non-numeric -p mni=abc" 2 "mni" \
  "$stochtex" analyze "$exemplar" -m texton -p mni=abc "${analyze_to[@]}"
# Enumerations take their names; a wrong name is refused with the list of names.
expect_error "unknown choice -p blend=foo" 2 "histogram, variance, linear" \
  "$stochtex" analyze "$exemplar" -m tiling -p blend=foo "${analyze_to[@]}"
expect_error "unknown parameter" 2 "nosuch" \
  "$stochtex" analyze "$exemplar" -m texton -p nosuch=1 "${analyze_to[@]}"
expect_error "-p without =" 2 "support" \
  "$stochtex" analyze "$exemplar" -m texton -p support "${analyze_to[@]}"
# Usage errors come before reading files: a bad parameter wins over a missing input.
expect_error "bad parameter and missing input" 2 "support" \
  "$stochtex" analyze "$inputs/missing.png" -m texton -p support=1 "${analyze_to[@]}"

for bad_size in 0x10 abc 100000x100000; do
  expect_error "render --size $bad_size" 2 "$bad_size" \
    "$stochtex" render "$model" -o "$out/render.png" --size "$bad_size"
done
expect_error "synth --size 0x10" 2 "0x10" \
  "$stochtex" synth "$exemplar" "${fast[@]}" -o "$out/synth.png" --size 0x10
expect_error "gaussian --size abc" 2 "abc" \
  "$stochtex" gaussian "$exemplar" -o "$out/gaussian.png" --size abc
expect_error "render --origin abc" 2 "abc" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --origin abc

expect_parse_error "unknown subcommand" "$stochtex" nosuch
expect_parse_error "analyze without --method" "$stochtex" analyze "$exemplar" "${analyze_to[@]}"
expect_parse_error "render without --size" "$stochtex" render "$model" -o "$out/render.png"
expect_parse_error "render --threads -1" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --threads -1
expect_parse_error "render --scale 0" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --scale 0

render_to=(-o "$out/render.png" "${size[@]}")
expect_error "render of a missing model" 1 "missing.stx" \
  "$stochtex" render "$inputs/missing.stx" "${render_to[@]}"
expect_error "info of a missing model" 1 "missing.stx" "$stochtex" info "$inputs/missing.stx"
expect_error "render of an image as a model" 1 "x.png" \
  "$stochtex" render "$inputs/x.png" "${render_to[@]}"
if [[ -s $model ]]; then
  head -c 100 "$model" >"$inputs/truncated.stx"
  expect_error "render of a truncated model" 1 "truncated.stx" \
    "$stochtex" render "$inputs/truncated.stx" "${render_to[@]}"
  # One byte flipped in the magic, the version, the header length, the arrays and the checksum.
  model_bytes=$(wc -c <"$model")
  for offset in 0 8 12 $((model_bytes / 2)) $((model_bytes - 1)); do
    corrupt=$inputs/corrupt_$offset.stx
    cp "$model" "$corrupt"
    byte=$(od -An -tu1 -j "$offset" -N 1 "$corrupt" | tr -d ' ')
    # shellcheck disable=SC2059 # the format is the escaped byte itself
    printf "$(printf '\\%03o' $((byte ^ 255)))" |
      dd of="$corrupt" bs=1 seek="$offset" count=1 conv=notrunc status=none
    expect_error "render of a model with byte $offset flipped" 1 "corrupt_$offset.stx" \
      "$stochtex" render "$corrupt" "${render_to[@]}"
  done
else
  fail "truncated and corrupt models" "analyze wrote no model to damage"
fi

expect_error "render into a missing folder" 1 "missing" \
  "$stochtex" render "$model" -o "$out/missing/render.png" "${size[@]}"
expect_error "analyze into a missing folder" 1 "missing" \
  "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$out/missing/model.stx"
expect_error "gaussian into a missing folder" 1 "missing" \
  "$stochtex" gaussian "$exemplar" -o "$out/missing/gaussian.png" "${size[@]}"
expect_error "render to an unknown extension" 2 "render.bmpx" \
  "$stochtex" render "$model" -o "$out/render.bmpx" "${size[@]}"

edit_to=(-o "$out/edited.stx")
expect_error "edit of a texton model" 2 "texton" "$stochtex" edit "$model" "${edit_to[@]}"
expect_error "edit of a missing model" 1 "missing.stx" \
  "$stochtex" edit "$inputs/missing.stx" "${edit_to[@]}"
expect_error "edit without -o" 2 "-o" "$stochtex" edit "$gabor_model" --rotate 10
expect_error "edit --bandwidth 3" 2 "--bandwidth" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --bandwidth 3
expect_error "edit --translate abc" 2 "abc" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --translate abc
expect_error "edit --magnitude -1" 2 "--magnitude" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --magnitude -1
expect_error "edit removing every Gaussian" 2 "no Gaussian" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --magnitude 0
expect_error "edit into a missing folder" 1 "missing" \
  "$stochtex" edit "$gabor_model" -o "$out/missing/edited.stx"
expect_parse_error "edit --group nosuch" "$stochtex" edit "$gabor_model" "${edit_to[@]}" \
  --group nosuch
expect_error "report of a missing exemplar" 1 "missing.png" \
  "$stochtex" report "$exemplar" "$inputs/missing.png" -o "$out/report"
expect_error "report of a truncated PNG" 1 "truncated.png" \
  "$stochtex" report "$inputs/truncated.png" -o "$out/report"
expect_error "report of a constant PNG" 1 "constant.png" \
  "$stochtex" report "$inputs/constant.png" -o "$out/report"
expect_error "report into a folder under a file" 1 "x.png" \
  "$stochtex" report "$exemplar" -o "$inputs/x.png/report"
expect_error "report with an unknown method" 2 "nosuch" \
  "$stochtex" report "$exemplar" -o "$out/report" --methods texton,nosuch
expect_error "report --size 8x8" 2 "8x8" "$stochtex" report "$exemplar" -o "$out/report" --size 8x8
expect_parse_error "report without exemplars" "$stochtex" report -o "$out/report"
expect_parse_error "report without -o" "$stochtex" report "$exemplar"

# --- safe writes: targets, messages, concurrency, signals (issue 19) ---------------------------

# Outputs replace only a missing path or a regular file, never the input, checked before any work.
targets=$work/targets
mkdir -p "$targets"
mkdir "$targets/d.stx" "$targets/d.png"
cp "$exemplar" "$targets/in.png"
ln "$targets/in.png" "$targets/in_link.png"
cp "$model" "$targets/model.stx"
cp "$model" "$targets/model.png" # a model under an image's name: render reads it by content
cp "$gabor_model" "$targets/gabor.stx"
printf 'kept\n' >"$targets/kept.png"
ln -s "$targets/kept.png" "$targets/link.png"
mkfifo "$targets/fifo.png"
expect_error "analyze onto a folder" 1 "$targets/d.stx" \
  "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$targets/d.stx"
if grep -q "Success" "$work/stderr"; then fail "analyze onto a folder" "says Success"; fi
expect_error "render onto a folder" 1 "a folder" \
  "$stochtex" render "$model" -o "$targets/d.png" "${size[@]}"
expect_error "render onto a symbolic link" 1 "$targets/link.png" \
  "$stochtex" render "$model" -o "$targets/link.png" "${size[@]}"
expect_error "render onto a FIFO" 1 "$targets/fifo.png" \
  "$stochtex" render "$model" -o "$targets/fifo.png" "${size[@]}"
# A device of our own, never /dev/null: a regression run as root would replace the machine's.
if mknod "$targets/null" c 1 3 2>/dev/null; then
  expect_error "analyze onto a device" 1 "$targets/null" \
    "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$targets/null"
  if [[ ! -c $targets/null ]]; then fail "analyze onto a device" "the device was replaced"; fi
fi
if [[ -L $targets/link.png && -p $targets/fifo.png && $(cat "$targets/kept.png") == kept ]]; then
  pass
else
  fail "refused targets are left as they were" "a link or FIFO was replaced"
fi
expect_error "analyze onto its input" 2 "$targets/in.png" \
  "$stochtex" analyze "$targets/in.png" "${fast[@]}" -o "$targets/in.png"
expect_error "analyze onto a hard link of its input" 2 "$targets/in_link.png" \
  "$stochtex" analyze "$targets/in.png" "${fast[@]}" -o "$targets/in_link.png"
expect_error "synth onto its input" 2 "$targets/in.png" \
  "$stochtex" synth "$targets/in.png" "${fast[@]}" -o "$targets/in.png" "${size[@]}"
expect_error "gaussian onto its input" 2 "$targets/in.png" \
  "$stochtex" gaussian "$targets/in.png" -o "$targets/in.png" "${size[@]}"
expect_error "render onto its model" 2 "$targets/model.png" \
  "$stochtex" render "$targets/model.png" -o "$targets/model.png" "${size[@]}"
expect_error "edit onto its model" 2 "$targets/gabor.stx" \
  "$stochtex" edit "$targets/gabor.stx" -o "$targets/gabor.stx" --scale 2
if cmp -s "$exemplar" "$targets/in.png" && cmp -s "$model" "$targets/model.png" &&
  cmp -s "$gabor_model" "$targets/gabor.stx"; then pass; else
  fail "inputs named as outputs are left as they were" "an input was overwritten"
fi
# A folder where the old fixed temporary name was does not matter any more.
mkdir "$targets/busy.png.tmp"
expect_ok "render beside a folder named like a temporary" \
  "$stochtex" render "$model" -o "$targets/busy.png" "${size[@]}" &&
  if [[ ! -s $targets/busy.png ]]; then fail "render beside a busy.png.tmp folder" "no file"; fi

# Wrong messages and codes.
python3 - "$inputs" <<'EOF'
import random, struct, sys, zlib
folder = sys.argv[1]
with open(folder + "/thin.pfm", "wb") as f:  # 1x4096 grey
    f.write(b"Pf\n1 4096\n-1.0\n" + b"".join(struct.pack("<f", (i % 7) / 7) for i in range(4096)))
random.seed(1)
with open(folder + "/huge.pfm", "wb") as f:  # finite values near the top of float's range
    f.write(b"Pf\n32 32\n-1.0\n"
            + b"".join(struct.pack("<f", random.choice((-3e38, 3e38))) for _ in range(1024)))
with open(folder + "/huge_rgb.pfm", "wb") as f:  # one channel near float's limit, one tiny
    f.write(b"PF\n32 32\n-1.0\n" + b"".join(
        struct.pack("<fff", random.choice((-3e38, 3e38)), random.random() * 1e-30, random.random())
        for _ in range(1024)))
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
rows = b"".join(b"\x00" + bytes(random.randrange(256) for _ in range(2 * 32)) for _ in range(32))
with open(folder + "/grey_alpha.png", "wb") as f:  # 32x32 grey + alpha
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 32, 32, 8, 4, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
EOF
expect_error "compare with a 1x4096 image" 1 "thin.pfm" \
  "$stochtex" compare "$exemplar" "$inputs/thin.pfm"
if grep -q "welch" "$work/stderr"; then fail "compare 1x4096" "names an internal function"; fi
expect_error "compare with a NaN image" 1 "nan.pfm" "$stochtex" compare "$exemplar" "$inputs/nan.pfm"
# Two 4096² colour images: about 3.1 GB for the measures (docs/design.md §9), refused before them.
expect_error "compare beyond the memory budget" 2 "4096x4096 image" \
  "$stochtex" compare "$inputs/ramp_4096.png" "$inputs/ramp_4096.png"
expect_error "lrp of values near float's limit is a data problem" 1 "huge.pfm" \
  "$stochtex" analyze "$inputs/huge.pfm" -m lrp -o "$out/huge.stx"
expect_error "gabor's singular colour transform names the file" 1 "huge_rgb.pfm" \
  "$stochtex" analyze "$inputs/huge_rgb.pfm" -m gabor -o "$out/huge.stx"
expect_ok "edit --list-groups with -o" "$stochtex" edit "$gabor_model" --list-groups \
  -o "$out/listed.stx" && if [[ -e $out/listed.stx ]]; then
  fail "edit --list-groups only lists" "it wrote the -o model"
  rm -f "$out/listed.stx"
else pass; fi
expect_ok "analyze a 2-channel exemplar" "$stochtex" analyze "$inputs/grey_alpha.png" "${fast[@]}" \
  -o "$models/grey_alpha.stx"
expect_error "render of 2 channels to .pfm fails before the render" 1 "PFM" \
  timeout 10 "$stochtex" render "$models/grey_alpha.stx" -o "$out/two.pfm" --size 8192x8192
expect_error "gaussian of 2 channels to .pfm" 1 "PFM" \
  "$stochtex" gaussian "$inputs/grey_alpha.png" -o "$out/two.pfm" "${size[@]}"

# Two concurrent writers of one output: each either succeeds or fails with one sentence, the file
# left is complete and is the one a successful writer wrote, and no temporary remains.
race=$work/race
mkdir -p "$race"
big=(--size 768x768)
"$stochtex" render "$model" -o "$race/seed3.png" "${big[@]}" --seed 3 2>/dev/null
"$stochtex" render "$model" -o "$race/seed4.png" "${big[@]}" --seed 4 2>/dev/null
for trial in 1 2 3; do
  "$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 3 2>"$race/err3" &
  pid3=$!
  "$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 4 2>"$race/err4" &
  pid4=$!
  wait $pid3
  status3=$?
  wait $pid4
  status4=$?
  matches=no
  if [[ $status3 -eq 0 ]] && cmp -s "$race/out.png" "$race/seed3.png"; then matches=yes; fi
  if [[ $status4 -eq 0 ]] && cmp -s "$race/out.png" "$race/seed4.png"; then matches=yes; fi
  clean=yes
  for seed in 3 4; do
    status_var=status$seed
    if [[ ${!status_var} -ne 0 ]] && ! grep -q '^stochtex: error: ' "$race/err$seed"; then
      clean=no
    fi
  done
  leftovers=$(find "$race" -name '*.tmp' | tr '\n' ' ')
  if [[ $matches == yes && $clean == yes && -z $leftovers ]]; then pass; else
    fail "two concurrent writers, trial $trial" \
      "exit $status3 and $status4, file of a successful writer: $matches, left: $leftovers"
  fi
  rm -f "$race/out.png"
done

# A reader during a write sees the old file or the new one, never a part.
cp "$race/seed3.png" "$race/out.png"
"$stochtex" render "$model" -o "$race/out.png" "${big[@]}" --seed 4 2>/dev/null &
writer=$!
partial=0
reads=0
while kill -0 $writer 2>/dev/null && ((reads++ < 5000)); do
  if ! cmp -s "$race/out.png" "$race/seed3.png" && ! cmp -s "$race/out.png" "$race/seed4.png"; then
    partial=$((partial + 1))
  fi
done
wait $writer
if [[ $? -eq 0 && $partial -eq 0 ]] && cmp -s "$race/out.png" "$race/seed4.png"; then pass; else
  fail "a reader during a write" "$partial read(s) saw neither the old nor the new file"
fi

# SIGINT or SIGTERM while the output is being written: no file and no temporary are left, and the
# exit status says the signal. Job control (set -m) keeps SIGINT from being ignored by background
# jobs; the signal is sent once the temporary exists, that is during the write.
for signal in INT TERM; do
  rm -rf "$race/signal"
  mkdir "$race/signal"
  set -m
  "$stochtex" gaussian "$exemplar" -o "$race/signal/out.png" --size 2048x2048 2>/dev/null &
  victim=$!
  set +m
  for _ in $(seq 200); do
    [[ -n $(find "$race/signal" -name '*.tmp' -print -quit) ]] && break
    sleep 0.05
  done
  kill -s $signal $victim
  wait $victim
  status=$?
  expected=$((128 + $(kill -l $signal)))
  left=$(find "$race/signal" -mindepth 1 | tr '\n' ' ')
  if [[ $status -eq $expected && -z $left ]]; then pass; else
    fail "SIG$signal during a write" "exit $status (expected $expected), left: $left"
  fi
done

# --- NaN, infinities and huge values (issue 19) ---------------------------------------------------
# Every numeric option refuses NaN, infinities and out-of-range values with one sentence (exit 2,
# nothing written); positions stay within +-2^32, the precise range (docs/design.md §4), for every
# method; exemplar values beyond +-1e6 are refused naming the file (exit 1).
for method in $methods; do
  each=$models/every_$method.stx
  [[ -s $each ]] || continue
  render_each=("$stochtex" render "$each" -o "$out/x.pfm" --size 16x16)
  expect_error "render $method --scale nan" 2 "--scale nan" "${render_each[@]}" --scale nan
  expect_error "render $method --scale -nan" 2 "--scale" "${render_each[@]}" --scale -nan
  expect_parse_error "render $method --scale inf" "${render_each[@]}" --scale inf
  expect_error "render $method --origin 1e300,-1e300" 2 "1e300" \
    "${render_each[@]}" --origin 1e300,-1e300
  expect_error "render $method --origin 1e19,0" 2 "1e19" "${render_each[@]}" --origin 1e19,0
  expect_error "render $method --origin past 2^32 by the grid" 2 "4294967296" \
    "${render_each[@]}" --origin 4294967000,0 --scale 100
  for origin in nan,0 0,inf -inf,0 1e400,0; do
    expect_error "render $method --origin $origin" 2 "$origin" "${render_each[@]}" --origin "$origin"
  done
  expect_error "render $method --backend gl --scale nan" 2 "--scale" \
    "${render_each[@]}" --scale nan --backend gl
  # At the edge of the range the render is finite.
  if expect_ok "render $method at the edge of the range" "$stochtex" render "$each" \
    -o "$models/edge_$method.pfm" --size 8x8 --origin 4294967000,-4294967000 --scale 10; then
    if python3 - "$models/edge_$method.pfm" <<'PY'; then
import array, math, sys
data = open(sys.argv[1], "rb").read().split(b"\n", 3)[3]  # after "PF", the size, the scale
values = array.array("f", data)
assert len(values) > 0 and all(math.isfinite(v) for v in values)
PY
      pass
    else
      fail "render $method at the edge of the range is finite" "non-finite values"
    fi
  fi
done
for value in nan inf -1 1e99 4294967296; do
  expect_parse_error "render --seed $value" "$stochtex" render "$model" -o "$out/x.png" \
    "${size[@]}" --seed "$value"
  expect_parse_error "gaussian --seed $value" "$stochtex" gaussian "$exemplar" -o "$out/x.png" \
    "${size[@]}" --seed "$value"
  expect_parse_error "analyze --analysis-seed $value" "$stochtex" analyze "$exemplar" \
    "${analyze_to[@]}" -m texton --analysis-seed "$value"
  expect_parse_error "report --seed $value" "$stochtex" report "$exemplar" -o "$out/report" \
    --seed "$value"
done
for option in --threads --supersample --tile; do
  for value in nan inf 1e99; do
    expect_parse_error "render $option $value" "$stochtex" render "$model" -o "$out/x.png" \
      "${size[@]}" "$option" "$value"
  done
done
for option in --threads --thumbnail; do
  for value in nan inf; do
    expect_parse_error "report $option $value" "$stochtex" report "$exemplar" -o "$out/report" \
      "$option" "$value"
  done
done
expect_error "synth --scale nan" 2 "--scale" "$stochtex" synth "$exemplar" "${fast[@]}" \
  -o "$out/x.png" "${size[@]}" --scale nan
expect_error "synth --origin 1e300,0" 2 "1e300" "$stochtex" synth "$exemplar" "${fast[@]}" \
  -o "$out/x.png" "${size[@]}" --origin 1e300,0
for value in nanxnan infx16 16x1e9; do
  expect_error "render --size $value" 2 "$value" "$stochtex" render "$model" -o "$out/x.png" \
    --size "$value"
  expect_error "gaussian --size $value" 2 "$value" "$stochtex" gaussian "$exemplar" \
    -o "$out/x.png" --size "$value"
  expect_error "report --size $value" 2 "$value" "$stochtex" report "$exemplar" \
    -o "$out/report" --size "$value"
done
for value in nan inf -inf 1e300; do
  expect_error "-p mni=$value" 2 "mni" "$stochtex" analyze "$exemplar" "${analyze_to[@]}" \
    -m texton -p mni="$value"
  expect_error "--target ring radius $value" 2 "radius" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=$value,width=0.02"
  expect_error "--target ring mean $value" 2 "mean" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=0.2,width=0.02,mean=$value"
  expect_error "--target ring variance $value" 2 "variance" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=0.2,width=0.02,variance=$value"
done
if [[ -s $gabor_model ]]; then
  for option in --rotate --scale --magnitude --bandwidth; do
    for value in nan inf -inf; do
      expect_error "edit $option $value" 2 "$option" "$stochtex" edit "$gabor_model" \
        "${edit_to[@]}" "$option" "$value"
    done
  done
  for option in --magnitude --bandwidth; do
    expect_error "edit $option 1e300" 2 "$option" "$stochtex" edit "$gabor_model" \
      "${edit_to[@]}" "$option" 1e300
  done
  for value in nan,0 0,inf 1e300,0; do
    expect_error "edit --translate $value" 2 "$value" "$stochtex" edit "$gabor_model" \
      "${edit_to[@]}" --translate "$value"
  done
fi
# nan.pfm with its NaN pixel made 3e38: finite, but beyond the exemplar value range.
python3 -c 'import struct, sys
data = open(sys.argv[1], "rb").read()
open(sys.argv[2], "wb").write(data.replace(struct.pack("<f", float("nan")), struct.pack("<f", 3e38)))' \
  "$inputs/nan.pfm" "$inputs/huge.pfm"
expect_error "gaussian of a PFM with 3e38" 1 "huge.pfm' has a value beyond" \
  "$stochtex" gaussian "$inputs/huge.pfm" -o "$out/x.png" --size 16x16
for method in $methods; do
  expect_error "synth -m $method of a PFM with 3e38" 1 "huge.pfm' has a value beyond" \
    "$stochtex" synth "$inputs/huge.pfm" -m "$method" -o "$out/x.png" --size 16x16
done

# --- memory budget and hostile sizes (docs/design.md §9) -----------------------------------------
# Requests beyond the memory budget are refused before any work, naming the option to change, and
# tiny files declaring huge contents are refused without allocating them.
expect_parse_error "render --threads 1024" "$stochtex" render "$gabor_model" -o "$out/x.png" \
  --size 64x64 --threads 1024
expect_error "render --supersample 64 on 8 threads" 2 "--threads" \
  "$stochtex" render "$gabor_model" -o "$out/x.png" --size 512x512 --supersample 64 --threads 8
expect_error "synth --supersample 64 on 8 threads" 2 "--supersample" \
  "$stochtex" synth "$exemplar" -m gabor -o "$out/x.png" --size 512x512 --supersample 64 \
  --threads 8
expect_error "gaussian --size 8192x8192" 2 "--size" \
  "$stochtex" gaussian "$exemplar" -o "$out/x.png" --size 8192x8192
python3 - "$inputs" <<'PY'
import struct, sys, zlib
folder = sys.argv[1]
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
signature = b'\x89PNG\r\n\x1a\n'
ihdr = chunk(b'IHDR', struct.pack('>IIBBBBB', 1, 1, 8, 0, 0, 0, 0))
with open(folder + '/text_bomb.png', 'wb') as f:  # a tEXt chunk declaring 2^31 - 1 bytes
    f.write(signature + ihdr + struct.pack('>I', 0x7fffffff) + b'tEXt')
with open(folder + '/huge_rgba16.png', 'wb') as f:  # 8192x8192 RGBA16 in 68 bytes
    f.write(signature + chunk(b'IHDR', struct.pack('>IIBBBBB', 8192, 8192, 16, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(bytes(16))) + chunk(b'IEND', b''))
PY
for hostile in text_bomb.png huge_rgba16.png; do
  expect_error "gaussian of $hostile" 1 "$hostile" \
    "$stochtex" gaussian "$inputs/$hostile" -o "$out/x.png" --size 16x16
done

# --- meshes (docs/meshes.md) --------------------------------------------------------------------

meshes=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../data/meshes" && pwd)
tiling_model=$models/every_tiling.stx
expect_ok "render-mesh --help" "$stochtex" render-mesh --help
if ! grep -q "1024 / the bounding box" "$work/stdout"; then
  fail "render-mesh --help" "does not state the default --texture-scale"
fi
for mesh in sphere torus scan; do
  expect_ok "render-mesh $mesh" "$stochtex" render-mesh "$meshes/$mesh.obj" --model "$tiling_model" \
    -o "$models/mesh_$mesh.png" --size 64x48 &&
    expect_file "render-mesh $mesh writes the image" "$models/mesh_$mesh.png"
done
# Every method: linear triplanar mapping on the scan (no uvs), and the sphere's uvs.
for method in $methods; do
  expect_ok "render-mesh $method triplanar-linear" "$stochtex" render-mesh "$meshes/scan.obj" \
    --model "$models/every_$method.stx" -o "$models/mesh_$method.png" --size 40x32 \
    --mapping triplanar-linear --camera 120,-10,1.2
  expect_ok "render-mesh $method uv" "$stochtex" render-mesh "$meshes/sphere.obj" \
    --model "$models/every_$method.stx" -o "$models/mesh_${method}_uv.pfm" --size 40x32 \
    --mapping uv --texture-scale 300
done
# The mappings of their own: surface noise (texton, gabor) on the scan, which has no uvs, and
# histogram-preserving triplanar blending (tiling); threads change nothing.
for method in texton gabor; do
  for threads in 1 2; do
    expect_ok "render-mesh $method surface, $threads threads" "$stochtex" render-mesh \
      "$meshes/scan.obj" --model "$models/every_$method.stx" -o "$models/surface_${method}_$threads.pfm" \
      --size 40x32 --mapping surface --surface-mni 30 --threads "$threads"
  done
  if cmp -s "$models/surface_${method}_1.pfm" "$models/surface_${method}_2.pfm"; then pass; else
    fail "render-mesh $method surface, 1 and 2 threads" "the renders differ"
  fi
done
expect_ok "render-mesh tiling triplanar" "$stochtex" render-mesh "$meshes/torus.obj" \
  --model "$tiling_model" -o "$models/triplanar.png" --size 40x32 --mapping triplanar --sharpness 8
# --backend gl: every shipped mesh (histogram-preserving triplanar, tiling) and the sphere's uvs
# with every method; a mapping without GLSL is refused before the mesh is read.
for mesh in sphere torus scan; do
  expect_ok "render-mesh $mesh --backend gl" "$stochtex" render-mesh "$meshes/$mesh.obj" \
    --model "$tiling_model" -o "$models/mesh_gl_$mesh.png" --size 40x32 --mapping triplanar \
    --backend gl && expect_file "render-mesh $mesh --backend gl writes the image" \
    "$models/mesh_gl_$mesh.png"
done
for method in $methods; do
  expect_ok "render-mesh $method uv --backend gl" "$stochtex" render-mesh "$meshes/sphere.obj" \
    --model "$models/every_$method.stx" -o "$models/mesh_gl_${method}_uv.pfm" --size 40x32 \
    --mapping uv --texture-scale 300 --backend gl
done
for method in texton gabor; do
  expect_ok "render-mesh $method surface --backend gl" "$stochtex" render-mesh "$meshes/scan.obj" \
    --model "$models/every_$method.stx" -o "$models/mesh_gl_${method}_surface.png" --size 40x32 \
    --mapping surface --backend gl
  expect_ok "render-mesh $method triplanar-linear --backend gl" "$stochtex" render-mesh \
    "$meshes/scan.obj" --model "$models/every_$method.stx" -o "$models/mesh_gl_${method}_tl.png" \
    --size 40x32 --backend gl
done
expect_error "render-mesh --backend gl, lrp triplanar-linear" 2 "no GLSL triplanar-linear mapping" \
  "$stochtex" render-mesh "$inputs/missing.obj" --model "$models/every_lrp.stx" -o "$out/x.png" \
  --backend gl
expect_parse_error "render-mesh --backend vulkan" "$stochtex" render-mesh "$meshes/sphere.obj" \
  --model "$tiling_model" -o "$out/x.png" --backend vulkan
expect_error "render-mesh --mapping triplanar for texton" 2 "texton models have no triplanar" \
  "$stochtex" render-mesh "$meshes/scan.obj" --model "$models/every_texton.stx" -o "$out/x.png" \
  --mapping triplanar
expect_error "render-mesh --surface-mni 0" 2 "--surface-mni" "$stochtex" render-mesh \
  "$meshes/scan.obj" --model "$models/every_texton.stx" -o "$out/x.png" --surface-mni 0
expect_error "render-mesh --sharpness nan" 2 "--sharpness" "$stochtex" render-mesh \
  "$meshes/scan.obj" --model "$tiling_model" -o "$out/x.png" --sharpness nan
# A pure function of its arguments: threads change nothing, the seed and the camera do.
for threads in 1 3; do
  expect_ok "render-mesh, $threads threads" "$stochtex" render-mesh "$meshes/torus.obj" \
    --model "$tiling_model" -o "$models/mesh_t$threads.pfm" --size 50x40 --seed 4 \
    --threads "$threads" --camera 0.5,2,3,0,0,0
done
if cmp -s "$models/mesh_t1.pfm" "$models/mesh_t3.pfm"; then pass; else
  fail "render-mesh, 1 and 3 threads" "the renders differ"
fi

# Bad meshes: one sentence naming the file, exit 1, no image.
printf '# no faces\nv 0 0 0\n' >"$inputs/empty.obj"
printf 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n' >"$inputs/nan.obj"
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' >"$inputs/degenerate.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 2 5\n' \
  >"$inputs/fin.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$inputs/range.obj"
head -c 3000 /dev/urandom >"$inputs/noise.obj"
for bad in empty nan degenerate fin range; do
  expect_error "render-mesh $bad.obj" 1 "$bad.obj" \
    "$stochtex" render-mesh "$inputs/$bad.obj" --model "$tiling_model" -o "$out/x.png"
done
capture "$stochtex" render-mesh "$inputs/noise.obj" --model "$tiling_model" -o "$out/x.png"
if [[ $status -eq 0 ]]; then find "$out" -mindepth 1 -delete && pass; else
  check_failure "render-mesh of random bytes" 1 "noise.obj"
fi
expect_error "render-mesh of a missing mesh" 1 "missing.obj" \
  "$stochtex" render-mesh "$inputs/missing.obj" --model "$tiling_model" -o "$out/x.png"
# Usage: refused before the mesh is read or anything rendered.
expect_error "render-mesh --mapping surface for lrp" 2 "lrp models have no surface mapping" \
  "$stochtex" render-mesh "$meshes/scan.obj" --model "$models/every_lrp.stx" -o "$out/x.png" \
  --mapping surface
expect_error "render-mesh --mapping uv without uvs" 2 "scan.obj" \
  "$stochtex" render-mesh "$meshes/scan.obj" --model "$tiling_model" -o "$out/x.png" --mapping uv
for bad_camera in 1 1,2,3,4 a,b 0,90 0,0,0 1,1,1,1,1,1; do
  expect_error "render-mesh --camera $bad_camera" 2 "camera" \
    "$stochtex" render-mesh "$meshes/sphere.obj" --model "$tiling_model" -o "$out/x.png" \
    --camera "$bad_camera"
done
expect_error "render-mesh --size 0x5" 2 "--size" \
  "$stochtex" render-mesh "$meshes/sphere.obj" --model "$tiling_model" -o "$out/x.png" --size 0x5
expect_parse_error "render-mesh --mapping planar" "$stochtex" render-mesh "$meshes/sphere.obj" \
  --model "$tiling_model" -o "$out/x.png" --mapping planar
expect_parse_error "render-mesh without --model" "$stochtex" render-mesh "$meshes/sphere.obj" \
  -o "$out/x.png"
expect_error "render-mesh onto its mesh" 2 "" \
  "$stochtex" render-mesh "$meshes/sphere.obj" --model "$tiling_model" -o "$meshes/sphere.obj"

# --- large renders (docs/large-renders.md) ------------------------------------------------------

large=$work/large
mkdir -p "$large"
# Four --region quadrants of a render, each written alone, assemble into the whole render exactly.
expect_ok "render the whole of a region split" "$stochtex" render "$model" -o "$large/whole.pfm" \
  --size 300x200 --origin 17.5,-3 --scale 1.5 --seed 9
quadrants=()
for region in 0,0,137,90 137,0,163,90 0,90,137,110 137,90,163,110; do
  expect_ok "render --region $region" "$stochtex" render "$model" -o "$large/$region.pfm" \
    --size 300x200 --origin 17.5,-3 --scale 1.5 --seed 9 --region "$region" --threads 1
  quadrants+=("$large/$region.pfm")
done
# PFM: a three-line header, then rows of floats from the bottom row to the top.
if python3 - "$large/whole.pfm" "${quadrants[@]}" <<'PY'; then
import sys

def rows(path):
    data = open(path, "rb").read()
    header = data.split(b"\n", 3)
    width, height = map(int, header[1].split())
    row_bytes = width * 3 * 4
    body = header[3]
    assert len(body) == row_bytes * height
    return [body[i * row_bytes:(i + 1) * row_bytes] for i in range(height)][::-1]

whole = rows(sys.argv[1])
top_left, top_right, bottom_left, bottom_right = (rows(p) for p in sys.argv[2:])
assembled = [l + r for l, r in zip(top_left, top_right)] + \
    [l + r for l, r in zip(bottom_left, bottom_right)]
sys.exit(0 if assembled == whole else 1)
PY
  pass
else
  fail "four --region quadrants assemble into the whole render" "the bytes differ"
fi
# Tiled, mip-mapped and half-float OpenEXR files: stochtex reads their level 0, and it is the
# in-memory (scanline) render's pixels: the same pixels analysed give the same model bytes.
expect_ok "render to a scanline .exr" "$stochtex" render "$model" -o "$large/scanline.exr" \
  --size 300x200 --seed 9
for flag in --tiled --mipmap; do
  expect_ok "render $flag" "$stochtex" render "$model" -o "$large/${flag#--}.exr" \
    --size 300x200 --seed 9 "$flag"
done
expect_ok "render --mipmap --half" "$stochtex" render "$model" -o "$large/half.exr" \
  --size 300x200 --seed 9 --mipmap --half
for image in scanline tiled mipmap; do
  mkdir -p "$large/$image"
  cp "$large/$image.exr" "$large/$image/exemplar.exr"
  expect_ok "analyze the $image .exr" "$stochtex" analyze "$large/$image/exemplar.exr" -m tiling \
    -o "$large/$image/model.stx"
done
for image in tiled mipmap; do
  if cmp -s "$large/scanline/model.stx" "$large/$image/model.stx"; then pass; else
    fail "the $image .exr holds the scanline render's pixels" "their models differ"
  fi
done
if [[ $(stat -c %s "$large/half.exr") -lt $(stat -c %s "$large/mipmap.exr") ]]; then pass; else
  fail "--half writes a smaller file" "half.exr is not smaller than mipmap.exr"
fi
expect_ok "compare reads a tiled .exr" "$stochtex" compare "$exemplar" "$large/half.exr"
expect_ok "render --backend gl --tiled" "$stochtex" render "$model" -o "$large/gl.exr" \
  --size 100x70 --seed 9 --backend gl --tiled
# A render beyond the in-memory limit (64 Mpixel) to .exr is streamed strip by strip: its peak
# memory is a strip's (44 MB measured), not the 816 MB of the image. Under AddressSanitizer
# (scripts/sanitize.sh sets ASAN_OPTIONS) shadow memory and the 256 MB quarantine of freed blocks
# add to it (427 MB measured): the bound is then the image's own size.
if python3 - "$stochtex" "$tiling_model" "$large/wide.exr" <<'PY'; then
import os, resource, subprocess, sys
stochtex, model, output = sys.argv[1:]
subprocess.run([stochtex, "render", model, "-o", output, "--size", "40000x1700", "--threads", "2"],
               check=True, stderr=subprocess.DEVNULL)
peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
bound_mb = 816 if "ASAN_OPTIONS" in os.environ else 200
print(f"peak {peak_mb:.0f} MB (bound {bound_mb} MB)")
sys.exit(0 if peak_mb < bound_mb else 1)
PY
  pass
else
  fail "a render beyond the in-memory limit streams with bounded memory" "see the peak above"
fi
rm -f "$large/wide.exr"
# Refused with one sentence before any work.
expect_error "render .png beyond the in-memory limit" 2 "write a .exr file" \
  "$stochtex" render "$model" -o "$out/x.png" --size 65536x65536
expect_error "render .pfm region beyond the in-memory limit" 2 "--region 0,0,40000,1700" \
  "$stochtex" render "$model" -o "$out/x.pfm" --size 65536x65536 --region 0,0,40000,1700
expect_error "render --size beyond 2^20" 2 "2000000x16" \
  "$stochtex" render "$model" -o "$out/x.exr" --size 2000000x16
expect_error "render a tiled .exr larger than the disk" 1 "free" \
  timeout 10 "$stochtex" render "$model" -o "$out/x.exr" --size 1048576x1048576
expect_error "render --mipmap to .png" 2 "--mipmap" \
  "$stochtex" render "$model" -o "$out/x.png" --size 64x64 --mipmap
expect_error "render --mipmap --region" 2 "--region" \
  "$stochtex" render "$model" -o "$out/x.exr" --size 64x64 --mipmap --region 0,0,8,8
for region in 0,0,0,8 60,0,8,8 0,60,8,8 1,2,3 a,b,c,d -1,0,8,8; do
  expect_error "render --region $region" 2 "--region" \
    "$stochtex" render "$model" -o "$out/x.png" --size 64x64 --region "$region"
done

# --- mix: texton noise mixing (texton paper section 7) -------------------------------------------

grey=$textures/metal_grey_256.png
mixfast=(-p support=16 -p iterations=5 --steps 3)
if expect_ok "mix" "$stochtex" mix "$exemplar" "$textures/wood_planks_256.png" "${mixfast[@]}" \
  --ramp 0,64 --direction 1,1 -o "$models/mix.stx"; then
  expect_file "mix writes the model" "$models/mix.stx"
fi
expect_ok "info of a mix" "$stochtex" info "$models/mix.stx" && if ! grep -q "texton_mix" \
  "$work/stdout" || ! grep -q "steps = 3" "$work/stdout"; then
  fail "info of a mix" "no method or steps line"
fi
expect_ok "render a mix, 1 thread" "$stochtex" render "$models/mix.stx" -o "$models/m1.pfm" \
  --size 48x20 --seed 5 --threads 1
expect_ok "render a mix, 2 threads" "$stochtex" render "$models/mix.stx" -o "$models/m2.pfm" \
  --size 48x20 --seed 5 --threads 2 --tile 16
if cmp -s "$models/m1.pfm" "$models/m2.pfm"; then pass; else
  fail "a mix renders the same bytes whatever the threads" "m1.pfm and m2.pfm differ"
fi
expect_ok "mix with a mask" "$stochtex" mix "$grey" "$textures/nuts_grey_256.png" "${mixfast[@]}" \
  --mask "$grey" --mask-scale 0.5 -o "$models/mask.stx"
expect_error "mix of grey with colour" 1 "nuts_grey_256.png" "$stochtex" mix \
  "$textures/nuts_grey_256.png" "$exemplar" "${mixfast[@]}" -o "$out/x.stx"
expect_error "mix with a colour mask" 1 "grass_lawn_128.png" "$stochtex" mix "$grey" \
  "$textures/nuts_grey_256.png" "${mixfast[@]}" --mask "$exemplar" -o "$out/x.stx"
expect_error "mix --ramp nan" 2 "--ramp" "$stochtex" mix "$grey" "$grey" --ramp nan,4 \
  -o "$out/x.stx"
expect_error "mix --ramp inf" 2 "--ramp" "$stochtex" mix "$grey" "$grey" --ramp 0,1e999 \
  -o "$out/x.stx"
expect_error "mix --ramp of one point" 2 "ramp_end" "$stochtex" mix "$grey" "$grey" --ramp 3,3 \
  -o "$out/x.stx"
expect_error "mix --direction 0,0" 2 "direction" "$stochtex" mix "$grey" "$grey" \
  --direction 0,0 -o "$out/x.stx"
expect_error "mix --steps 1" 2 "steps" "$stochtex" mix "$grey" "$grey" --steps 1 -o "$out/x.stx"
expect_error "mix -p mni=nan" 2 "mni" "$stochtex" mix "$grey" "$grey" -p mni=nan -o "$out/x.stx"
expect_error "mix of a missing file" 1 "missing.png" "$stochtex" mix "$grey" \
  "$inputs/missing.png" -o "$out/x.stx"
# Beyond the memory budget (docs/design.md §9), refused before any work: 4096² colour exemplars
# (about 2.8 GB), and 2048² ones into 256 textons of 1024² (about 23 GB of textons).
expect_error "mix beyond the memory budget" 2 "ramp_4096.png" "$stochtex" mix \
  "$inputs/ramp_4096.png" "$inputs/ramp_4096.png" -o "$out/x.stx"
expect_error "mix into textons beyond the memory budget" 2 "--steps" "$stochtex" mix \
  "$inputs/ramp_2048.png" "$inputs/ramp_2048.png" --steps 256 -p support=1024 -o "$out/x.stx"
if [[ -e $out/x.stx ]]; then fail "a refused mix writes nothing" "x.stx exists"; else pass; fi
# The GPU twin: both fields on the gl backend (both --gl-filter values run the exact path), and
# the export in every language.
for field in mix mask; do
  expect_ok "render a $field model on the gl backend" "$stochtex" render "$models/$field.stx" \
    -o "$models/$field-gl.png" --size 48x20 --seed 5 --backend gl --scale 2
  expect_ok "render a $field model, --gl-filter hardware" "$stochtex" render "$models/$field.stx" \
    -o "$models/$field-glh.png" --size 48x20 --seed 5 --backend gl --gl-filter hardware --scale 2
  if cmp -s "$models/$field-gl.png" "$models/$field-glh.png"; then pass; else
    fail "a $field model's hardware filter is its exact path" "$field-gl.png and $field-glh.png differ"
  fi
  for language in $languages; do
    expect_ok "export-shader of a $field model, $language" "$stochtex" export-shader \
      "$models/$field.stx" -o "$out/$field-$language" --language "$language"
    expect_file "the $field export's README" "$out/$field-$language/README.md"
  done
done
expect_file "the mask export's mask data" "$out/mask-glsl/texton_mix_mask.exr"

# --- materials (docs/materials.md) ---------------------------------------------------------------

rock=$textures/../materials/rock_sandstone
find "$out" -mindepth 1 -delete
expect_ok "analyze a material" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map roughness="$rock/roughness.png" -m tiling -o "$models/material.stx" &&
  expect_file "the material model" "$models/material.stx"
expect_ok "info lists a material's maps" "$stochtex" info "$models/material.stx" &&
  if grep -q '^map       albedo (colour, 3 channels)' "$work/stdout" &&
    grep -q '^map       roughness (scalar, 1 channel)' "$work/stdout"; then pass; else
    fail "info lists a material's maps" "no map lines in: $(cat "$work/stdout")"
  fi
expect_json "info --json of a material" "$stochtex" info "$models/material.stx" --json &&
  if python3 -c 'import json,sys; d=json.load(sys.stdin); assert [m["name"] for m in d["maps"]] == ["albedo", "roughness"]' \
    <"$work/stdout"; then pass; else fail "info --json lists the maps" "no maps"; fi
expect_ok "render a material's maps" "$stochtex" render "$models/material.stx" \
  -o "$models/mat_{map}.png" --size 40x24 --seed 3 &&
  expect_file "the albedo map" "$models/mat_albedo.png" &&
  expect_file "the roughness map" "$models/mat_roughness.png"
expect_ok "a normal map in a material" "$stochtex" analyze --map normal="$rock/normal.png" \
  --map height="$rock/height.png" -m tiling -o "$models/relief.stx" &&
  expect_ok "render a normal map" "$stochtex" render "$models/relief.stx" \
    -o "$models/relief_{map}.pfm" --size 32x32 &&
  if python3 - "$models/relief_normal.pfm" <<'PY'; then pass; else
import math, struct, sys
# A PFM of 0.5 + 0.5 n: every decoded normal is unit length and faces out.
data = open(sys.argv[1], "rb").read()
lines = data.split(b"\n", 3)
assert lines[0] == b"PF", lines[0]
width, height = map(int, lines[1].split())
values = struct.unpack("<%df" % (width * height * 3), lines[3][: width * height * 12])
for i in range(0, len(values), 3):
    n = [2.0 * v - 1.0 for v in values[i : i + 3]]
    assert abs(math.sqrt(sum(c * c for c in n)) - 1.0) < 1e-5 and n[2] > 0.0, n
PY
    fail "rendered normals are unit length" "see the assertion above"
  fi
expect_ok "texton derives a normal map from the height" "$stochtex" analyze \
  --map normal="$rock/normal.png" --map height="$rock/height.png" -m texton -p iterations=3 \
  -o "$models/derived.stx" &&
  expect_ok "info of a derived normal map" "$stochtex" info "$models/derived.stx" &&
  if grep -q '^map       normal (normal, derived: .* times the gradient of height)' "$work/stdout"; then
    pass
  else
    fail "info says the normal map is derived" "$(cat "$work/stdout")"
  fi
expect_error "a material rendered into one file" 2 "{map}" "$stochtex" render \
  "$models/material.stx" -o "$out/x.png" --size 8x8
expect_error "{map} for a model of one image" 2 "{map}" "$stochtex" render "$model" \
  -o "$out/x_{map}.png" --size 8x8
# Materials streamed to tiled, mip-mapped maps: each map's level 0 is its in-memory render's,
# a normal map derived from the height (texton) included: every strip renders its own margin.
mkdir -p "$large/maps"
expect_ok "a texton material with a derived normal map" "$stochtex" analyze \
  --map normal="$rock/normal.png" --map height="$rock/height.png" -m texton -p support=24 \
  -o "$models/derived.stx"
for material in "material albedo roughness" "derived normal height"; do
  read -r name maps <<<"$material"
  expect_ok "render the $name maps --mipmap" "$stochtex" render "$models/$name.stx" \
    -o "$large/maps/tiled_{map}.exr" --size 90x70 --seed 4 --mipmap || continue
  expect_ok "render the $name maps to scanline .exr" "$stochtex" render "$models/$name.stx" \
    -o "$large/maps/scanline_{map}.exr" --size 90x70 --seed 4 || continue
  for map in $maps; do
    for image in tiled scanline; do
      mkdir -p "$large/maps/$image-$map"
      cp "$large/maps/${image}_$map.exr" "$large/maps/$image-$map/exemplar.exr"
      "$stochtex" analyze "$large/maps/$image-$map/exemplar.exr" -m tiling \
        -o "$large/maps/$image-$map/model.stx" 2>/dev/null
    done
    if cmp -s "$large/maps/tiled-$map/model.stx" "$large/maps/scanline-$map/model.stx"; then pass
    else fail "the tiled $map map holds the in-memory render's pixels" "their models differ"; fi
  done
done
expect_error "maps of different sizes" 1 "the same size" "$stochtex" analyze \
  --map albedo="$rock/albedo.png" --map roughness="$exemplar" -m tiling -o "$out/x.stx"
expect_error "a normal map that is not one" 1 "not a tangent-space normal map" "$stochtex" \
  analyze --map normal="$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_error "more channels than a material may have" 1 "17 channels in 7 maps" "$stochtex" \
  analyze --map a="$rock/albedo.png" --map b="$rock/albedo.png" --map c="$rock/albedo.png" \
  --map d="$rock/albedo.png" --map e="$rock/albedo.png" --map ao="$rock/ao.png" \
  --map height="$rock/height.png" -m tiling -o "$out/x.stx"
expect_ok "a material's groups on tiling's gpu twin" "$stochtex" render "$models/relief.stx" \
  -o "$models/relief_gl_{map}.png" --size 8x8 --backend gl &&
  expect_file "the gl backend's tiling height map" "$models/relief_gl_height.png"
expect_ok "export-shader of a tiling material" "$stochtex" export-shader "$models/relief.stx" \
  -o "$models/relief_shader" &&
  if grep -qF "StochtexMaterial stochtex_tiling_material(vec2 p" \
    "$models/relief_shader/stochtex_tiling.glsl"; then pass; else
    fail "export-shader of a tiling material" "no stochtex_tiling_material"
  fi
expect_ok "tiling's rotation with a normal map" "$stochtex" analyze --map normal="$rock/normal.png" \
  --map height="$rock/height.png" -m tiling -p rotation=30 -p scale_jitter=0.2 \
  -o "$models/turned.stx" &&
  expect_ok "render turned slopes" "$stochtex" render "$models/turned.stx" \
    -o "$models/turned_{map}.png" --size 24x24 --scale 4 &&
  expect_file "the turned normal map" "$models/turned_normal.png"
expect_ok "turned slopes on tiling's gpu twin" "$stochtex" render "$models/turned.stx" \
  -o "$models/turned_gl_{map}.png" --size 8x8 --backend gl &&
  expect_file "the gl backend's turned normal map" "$models/turned_gl_normal.png"
expect_ok "tiling's height-aware blend" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map height="$rock/height.png" -m tiling -p height_blend=0.1 -o "$models/height_blend.stx" &&
  expect_ok "the height-aware blend on tiling's gpu twin" "$stochtex" render \
    "$models/height_blend.stx" -o "$models/height_blend_gl_{map}.png" --size 8x8 --backend gl &&
  expect_file "the gl backend's height-blended albedo" "$models/height_blend_gl_albedo.png"
expect_error "a map named twice" 1 "twice" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map albedo="$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_error "a colour roughness map" 1 "one channel" "$stochtex" analyze \
  --map roughness="$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_error "a malformed --map" 2 "--map expects" "$stochtex" analyze --map "Albedo=$rock/albedo.png" \
  -m tiling -o "$out/x.stx"
expect_error "an unknown map kind" 2 "colour, normal, height, scalar" "$stochtex" analyze \
  --map "albedo:rgb=$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_error "a missing map file" 1 "missing.png" "$stochtex" analyze \
  --map "albedo=$inputs/missing.png" -m tiling -o "$out/x.stx"
expect_parse_error "--map with INPUT" "$stochtex" analyze "$exemplar" \
  --map "albedo=$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_ok "a material of 9 channels" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map normal="$rock/normal.png" --map roughness="$rock/roughness.png" \
  --map height="$rock/height.png" --map ao="$rock/ao.png" -m texton -p iterations=3 \
  -o "$models/rock.stx" &&
  expect_ok "render its maps on the gl backend" "$stochtex" render "$models/rock.stx" \
    -o "$models/rock_{map}.png" --size 24x24 --backend gl &&
  expect_file "the gl backend's ao map" "$models/rock_ao.png" &&
  expect_ok "export-shader of a material" "$stochtex" export-shader "$models/rock.stx" \
    -o "$models/rock_shader" &&
  expect_readme_files "export-shader of a material writes its README's files" \
    "$models/rock_shader" &&
  if grep -qF "StochtexMaterial stochtex_texton_material(vec2 p" "$models/rock_shader/README.md" &&
    grep -qF "float ao;" "$models/rock_shader/stochtex_texton.glsl"; then
    pass
  else
    fail "export-shader of a material" "no StochtexMaterial with the map ao"
  fi &&
  expect_error "export-shader --variant fast of a material beyond 4 channels" 1 \
    "export it with --variant exact" "$stochtex" export-shader "$models/rock.stx" \
    -o "$out/rock" --variant fast
# render-mesh shades a material's colour map (3 channels), bumped by a derived normal map (rock) or
# none (material), through every mapping its method has.
for mapping in uv triplanar-linear surface; do
  expect_ok "render-mesh of a material, $mapping" "$stochtex" render-mesh \
    "$textures/../meshes/sphere.obj" --model "$models/rock.stx" -o "$models/rock_mesh.pfm" \
    --size 24x16 --mapping "$mapping" &&
    if head -c 3 "$models/rock_mesh.pfm" | grep -q '^PF$'; then pass; else
      fail "render-mesh of a material writes its colour map" "not a 3-channel PFM"
    fi
done
expect_ok "render-mesh of a material without a normal map" "$stochtex" render-mesh \
  "$textures/../meshes/sphere.obj" --model "$models/material.stx" -o "$models/material_mesh.png" \
  --size 16x16 && expect_file "the material's picture" "$models/material_mesh.png"
expect_error "render-mesh of a material without a colour map" 1 "relief.stx" "$stochtex" \
  render-mesh "$textures/../meshes/sphere.obj" --model "$models/relief.stx" -o "$out/x.png" \
  --size 16x16
# --backend gl: a material at the mesh's uvs through its exported material function (texton and
# tiling); refused on another mapping.
expect_ok "render-mesh --backend gl of a material, uv" "$stochtex" render-mesh \
  "$textures/../meshes/sphere.obj" --model "$models/rock.stx" -o "$models/rock_mesh_gl.pfm" \
  --size 24x16 --mapping uv --backend gl &&
  if head -c 3 "$models/rock_mesh_gl.pfm" | grep -q '^PF$'; then pass; else
    fail "render-mesh --backend gl of a material writes its colour map" "not a 3-channel PFM"
  fi
expect_error "render-mesh --backend gl of a material, triplanar-linear" 1 "--mapping uv" \
  "$stochtex" render-mesh "$textures/../meshes/sphere.obj" --model "$models/rock.stx" \
  -o "$out/x.png" --size 16x16 --mapping triplanar-linear --backend gl
expect_ok "render-mesh --backend gl of a tiling material" "$stochtex" render-mesh \
  "$textures/../meshes/sphere.obj" --model "$models/material.stx" \
  -o "$models/material_mesh_gl.png" --size 16x16 --mapping uv --backend gl &&
  expect_file "the gl backend's tiling material on a mesh" "$models/material_mesh_gl.png"

# --- summary ------------------------------------------------------------------------------------

echo "cli_test: ${passed} passed, ${#failed[@]} failed"
if [[ ${#failed[@]} -gt 0 ]]; then
  printf '  failed: %s\n' "${failed[@]}"
  exit 1
fi
