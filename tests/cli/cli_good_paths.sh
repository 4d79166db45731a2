#!/usr/bin/env bash
# The good paths of every command: each works, prints valid JSON where asked, renders the same
# bytes whatever the threads and CPU target, exports every method's shader in every language, and
# edits a gabor model (the comparison report: cli_report.sh).
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

expect_ok "methods" "$stochtex" methods && if ! grep -q texton "$work/stdout"; then
  fail "methods lists texton" "stdout does not mention texton"
fi
expect_ok "--help" "$stochtex" --help
for command in analyze mix render render-mesh synth gaussian compare info edit methods languages \
  report studio; do
  expect_ok "$command --help" "$stochtex" "$command" --help
done
expect_parse_error "studio --port out of range" "$stochtex" studio --port 70000

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
expect_ok "analyze lrp" "$stochtex" analyze "$exemplar" -m lrp -p cosines=12 "${data[@]}" \
  -o "$models/lrp.stx"
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
if ! gl_skipped 2 "render --backend gl"; then
  expect_ok "render --backend gl" "$stochtex" render "$model" -o "$models/gl.png" --size 48x40 \
    --seed 5 --backend gl && expect_file "render --backend gl writes the image" "$models/gl.png"
fi
if ! gl_skipped 2 "render tiling --backend gl"; then
  expect_ok "render tiling --backend gl" "$stochtex" synth "$exemplar" -m tiling -p transport=1 \
    -o "$models/tiling_gl.png" --size 40x32 --backend gl &&
    expect_file "synth tiling --backend gl writes the image" "$models/tiling_gl.png"
fi
if ! gl_skipped 2 "render --gl-filter hardware"; then
  expect_ok "render --gl-filter hardware" "$stochtex" render "$model" -o "$models/gl_hw.png" \
    --size 32x32 --scale 4 --backend gl --gl-filter hardware &&
    expect_file "render --gl-filter hardware writes the image" "$models/gl_hw.png"
fi
expect_parse_error "unknown --gl-filter" "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" \
  --backend gl --gl-filter bicubic
expect_parse_error "unknown backend" "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" \
  --backend vulkan
expect_error "--supersample with --backend gl" 2 "--supersample" \
  "$stochtex" render "$model" -o "$out/x.png" "${size[@]}" --backend gl --supersample 2

# Each method with its defaults (cli_setup.sh analysed them): info, a CPU and a GPU render, the
# shader export.
for method in $methods; do
  each=$models/every_$method
  expect_json "info $method --json" "$stochtex" info "$each.stx" --json
  expect_ok "render $method" "$stochtex" render "$each.stx" -o "$each.png" --size 24x24 &&
    expect_file "render $method writes the image" "$each.png"
  # The one GL render of each method that STOCHTEX_CLI_GL=one-per-method keeps.
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
done

expect_parse_error "unknown --variant" "$stochtex" export-shader "$model" -o "$out/shader" \
  --variant fastest
expect_ok "export-shader" "$stochtex" export-shader "$model" -o "$models/shader" &&
  expect_file "export-shader writes the GLSL" "$models/shader/stochtex_texton.glsl" &&
  expect_file "export-shader writes the atlas" "$models/shader/texton_atlas.exr" &&
  expect_file "export-shader writes the README" "$models/shader/README.md"
if expect_ok "analyze gabor" "$stochtex" analyze "$exemplar" -m gabor -p impulses=64 "${data[@]}" \
  -o "$models/gabor.stx"; then
  if ! gl_skipped 2 "render gabor --backend gl"; then
    expect_ok "render gabor --backend gl" "$stochtex" render "$models/gabor.stx" \
      -o "$models/gabor_gl.png" --size 24x24 --backend gl &&
      expect_file "render gabor --backend gl writes the image" "$models/gabor_gl.png"
  fi
  expect_ok "export-shader gabor" "$stochtex" export-shader "$models/gabor.stx" \
    -o "$models/gabor_shader" &&
    expect_file "export-shader gabor writes the GLSL" "$models/gabor_shader/stochtex_gabor.glsl" &&
    expect_file "export-shader gabor writes the data" "$models/gabor_shader/gabor_data.exr"
fi

# export-shader --language: each target's files; a language the model cannot be written in
# (gabor's doubles), an unknown language and folders that cannot take the files are refused with
# nothing written. (tests/gl/export_language_test.cpp compiles and runs what is written.)
for language in $cross_languages; do
  # Godot imports no float32 file: its atlas is the floats' bytes in a PNG (docs/engines.md).
  atlas=texton_atlas.exr
  [[ $language == godot ]] && atlas=texton_atlas.png
  expect_ok "export-shader --language $language" "$stochtex" export-shader "$model" \
    -o "$models/shader_$language" --language "$language" &&
    expect_file "export-shader --language $language writes the README" \
      "$models/shader_$language/README.md" &&
    expect_file "export-shader --language $language writes the atlas" \
      "$models/shader_$language/$atlas"
done
expect_file "export-shader --language essl writes the GLSL ES" "$models/shader_essl/stochtex_texton.essl"
expect_file "export-shader --language hlsl writes the HLSL" "$models/shader_hlsl/stochtex_texton.hlsl"
expect_file "export-shader --language hlsl writes the Shader Graph function" \
  "$models/shader_hlsl/stochtex_texton_shadergraph.hlsl"
expect_file "export-shader --language msl writes the Metal" "$models/shader_msl/stochtex_texton.metal"
# Godot: the shaders, the scene and each data file's import settings (tests/godot runs them).
for file in stochtex_texton.shader stochtex_texton_canvas.shader stochtex_texton.tscn \
  stochtex_texton.gdshader texton_atlas.png.import; do
  expect_file "export-shader --language godot writes $file" "$models/shader_godot/$file"
done
if [[ -f $models/shader_godot/texton_atlas.png.import ]]; then
  if grep -qx 'flags/srgb=0' "$models/shader_godot/texton_atlas.png.import"; then pass; else
    fail "export-shader --language godot imports its data without sRGB" "no flags/srgb=0"
  fi
fi
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
  -p ratio=0.3 -p turbulence=2 "${data[@]}" -o "$models/lrp_structure.stx" &&
  expect_ok "render lrp with structure" "$stochtex" render "$models/lrp_structure.stx" \
    -o "$models/lrp_structure.png" "${size[@]}" &&
  expect_file "render lrp with structure writes the image" "$models/lrp_structure.png"
if ! gl_skipped 2 "render lrp with structure --backend gl"; then
  expect_ok "render lrp with structure --backend gl" "$stochtex" render \
    "$models/lrp_structure.stx" -o "$models/lrp_structure_gl.png" "${size[@]}" --backend gl &&
    expect_file "render lrp with structure --backend gl writes the image" \
      "$models/lrp_structure_gl.png"
fi
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

# Editing a gabor model (section 8 of the Gabor noise paper; cli_setup.sh analysed it): groups,
# then an edit of one group.
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

summary
