#!/usr/bin/env bash
# Materials (docs/materials.md): models of several maps, their renders, tiled maps, shader exports
# and meshes, and the refusals.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

rock=$textures/../materials/rock_sandstone
expect_ok "analyze a material" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map roughness="$rock/roughness.png" -m tiling -o "$models/material.stx" &&
  expect_file "the material model" "$models/material.stx"
expect_ok "info lists a material's maps" "$stochtex" info "$models/material.stx" &&
  if grep -q '^map       albedo (colour, 3 channels, srgb)' "$work/stdout" &&
    grep -q '^map       roughness (scalar, 1 channel, data)' "$work/stdout"; then pass; else
    fail "info lists a material's maps" "no map lines in: $(cat "$work/stdout")"
  fi
expect_json "info --json of a material" "$stochtex" info "$models/material.stx" --json &&
  if python3 -c 'import json,sys; d=json.load(sys.stdin); assert [m["name"] for m in d["maps"]] == ["albedo", "roughness"]' \
    <"$work/stdout"; then pass; else fail "info --json lists the maps" "no maps"; fi
expect_ok "render a material's maps" "$stochtex" render "$models/material.stx" \
  -o "$models/mat_{map}.png" --size 40x24 --seed 3 &&
  expect_file "the albedo map" "$models/mat_albedo.png" &&
  expect_file "the roughness map" "$models/mat_roughness.png"
# A material's maps are written all or none (issue 35). A file size limit (ulimit -f, in KiB;
# SIGXFSZ ignored, so the write fails with EFBIG as on a full disk) lets the 16 KiB roughness map
# through and stops the 48 KiB albedo map written after it; SIGHUP once the second map's temporary
# exists. Neither leaves a map.
expect_ok "analyze a material, roughness first" "$stochtex" analyze \
  --map roughness="$rock/roughness.png" --map albedo="$rock/albedo.png" -m tiling \
  -o "$models/rough_first.stx"
expect_error "render a material onto a full disk" 1 "full_albedo.pfm" \
  bash -c 'trap "" XFSZ; ulimit -f 32; exec "$@"' _ "$stochtex" render "$models/rough_first.stx" \
  -o "$out/full_{map}.pfm" --size 64x64
signal_during_write "SIGHUP after a material's first map" HUP "$out" 'hup_albedo.pfm.*.tmp' \
  "$stochtex" render "$models/rough_first.stx" -o "$out/hup_{map}.pfm" --size 4096x2048
find "$out" -mindepth 1 -delete
# A report is one output too: a picture that cannot be written ends it with nothing written.
expect_error "report onto a full disk" 1 "" \
  bash -c 'trap "" XFSZ; ulimit -f 2; exec "$@"' _ "$stochtex" report "$rock/roughness.png" \
  -o "$out/report" --methods tiling --size 64x64
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
large=$work/large
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
if ! gl_skipped 2 "a material's groups on tiling's gpu twin"; then
  expect_ok "a material's groups on tiling's gpu twin" "$stochtex" render "$models/relief.stx" \
    -o "$models/relief_gl_{map}.png" --size 8x8 --backend gl &&
    expect_file "the gl backend's tiling height map" "$models/relief_gl_height.png"
fi
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
if ! gl_skipped 2 "turned slopes on tiling's gpu twin"; then
  expect_ok "turned slopes on tiling's gpu twin" "$stochtex" render "$models/turned.stx" \
    -o "$models/turned_gl_{map}.png" --size 8x8 --backend gl &&
    expect_file "the gl backend's turned normal map" "$models/turned_gl_normal.png"
fi
expect_ok "tiling's height-aware blend" "$stochtex" analyze --map albedo="$rock/albedo.png" \
  --map height="$rock/height.png" -m tiling -p height_blend=0.1 -o "$models/height_blend.stx" &&
  if ! gl_skipped 2 "the height-aware blend on tiling's gpu twin"; then
    expect_ok "the height-aware blend on tiling's gpu twin" "$stochtex" render \
      "$models/height_blend.stx" -o "$models/height_blend_gl_{map}.png" --size 8x8 --backend gl &&
      expect_file "the gl backend's height-blended albedo" "$models/height_blend_gl_albedo.png"
  fi
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
  if ! gl_skipped 2 "render its maps on the gl backend"; then
    expect_ok "render its maps on the gl backend" "$stochtex" render "$models/rock.stx" \
      -o "$models/rock_{map}.png" --size 24x24 --backend gl &&
      expect_file "the gl backend's ao map" "$models/rock_ao.png"
  fi &&
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
    -o "$out/rock" --variant fast &&
  expect_error "export-shader --language godot of a material (no structs in Godot 3)" 2 \
    "which Godot 3's shading language does not have" "$stochtex" export-shader \
    "$models/rock.stx" -o "$out/rock_godot" --language godot
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
if ! gl_skipped 2 "render-mesh --backend gl of a material, uv"; then
  expect_ok "render-mesh --backend gl of a material, uv" "$stochtex" render-mesh \
    "$textures/../meshes/sphere.obj" --model "$models/rock.stx" -o "$models/rock_mesh_gl.pfm" \
    --size 24x16 --mapping uv --backend gl &&
    if head -c 3 "$models/rock_mesh_gl.pfm" | grep -q '^PF$'; then pass; else
      fail "render-mesh --backend gl of a material writes its colour map" "not a 3-channel PFM"
    fi
fi
expect_error "render-mesh --backend gl of a material, triplanar-linear" 1 "--mapping uv" \
  "$stochtex" render-mesh "$textures/../meshes/sphere.obj" --model "$models/rock.stx" \
  -o "$out/x.png" --size 16x16 --mapping triplanar-linear --backend gl
if ! gl_skipped 2 "render-mesh --backend gl of a tiling material"; then
  expect_ok "render-mesh --backend gl of a tiling material" "$stochtex" render-mesh \
    "$textures/../meshes/sphere.obj" --model "$models/material.stx" \
    -o "$models/material_mesh_gl.png" --size 16x16 --mapping uv --backend gl &&
    expect_file "the gl backend's tiling material on a mesh" "$models/material_mesh_gl.png"
fi

summary
