#!/usr/bin/env bash
# Meshes (docs/meshes.md): render-mesh with every mapping and method, on the CPU and the gl
# backend, its determinism and its refusals of bad meshes and options.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

meshes=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../data/meshes" && pwd)
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
  gl_skipped 2 "render-mesh $mesh --backend gl" && continue
  expect_ok "render-mesh $mesh --backend gl" "$stochtex" render-mesh "$meshes/$mesh.obj" \
    --model "$tiling_model" -o "$models/mesh_gl_$mesh.png" --size 40x32 --mapping triplanar \
    --backend gl && expect_file "render-mesh $mesh --backend gl writes the image" \
    "$models/mesh_gl_$mesh.png"
done
for method in $methods; do
  gl_skipped 1 "render-mesh $method uv --backend gl" && continue
  expect_ok "render-mesh $method uv --backend gl" "$stochtex" render-mesh "$meshes/sphere.obj" \
    --model "$models/every_$method.stx" -o "$models/mesh_gl_${method}_uv.pfm" --size 40x32 \
    --mapping uv --texture-scale 300 --backend gl
done
for method in texton gabor; do
  gl_skipped 2 "render-mesh $method surface and triplanar-linear --backend gl" && continue
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
expect_error "render-mesh --texture-scale nan" 2 "--texture-scale" "$stochtex" render-mesh \
  "$meshes/scan.obj" --model "$tiling_model" -o "$out/x.png" --texture-scale nan
# A pure function of its arguments: threads change nothing, the seed and the camera do.
for threads in 1 3; do
  expect_ok "render-mesh, $threads threads" "$stochtex" render-mesh "$meshes/torus.obj" \
    --model "$tiling_model" -o "$models/mesh_t$threads.pfm" --size 50x40 --seed 4 \
    --threads "$threads" --camera 0.5,2,3,0,0,0
done
if cmp -s "$models/mesh_t1.pfm" "$models/mesh_t3.pfm"; then pass; else
  fail "render-mesh, 1 and 3 threads" "the renders differ"
fi

# --periodic (--mapping uv): the texture repeats every uv unit. A strip whose u runs from 0 to 1
# twice (a wrap seam at x = 1, where u jumps back to 0, as on a UV sphere's meridian) seen head-on
# from in front of the seam, which lies between the middle columns: the seam's step over the mean
# step between the other neighbouring columns (0.29 exemplar pixels a pixel: zoomed in, a seam
# stands out). Measured with every_tiling over seeds 1 to 8: default 3.31 to 4.89, --periodic 0.52
# to 0.78 (tests/unit/mesh_test.cpp measures every method and a material).
python3 - "$inputs/strip.obj" <<'EOF'
import sys
lines = []
for half in range(2):
    for corner in range(4):
        x, y = half + corner % 2, corner // 2
        lines += ["v %d %d 0" % (x, y), "vt %d %d" % (x - half, y)]
for a in (1, 5):
    lines += ["f %d/%d %d/%d %d/%d" % (a, a, a + 1, a + 1, a + 3, a + 3),
              "f %d/%d %d/%d %d/%d" % (a, a, a + 3, a + 3, a + 2, a + 2)]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
EOF
camera=1,0.5,0.1717,1,0.5,0 # eye and target: 0.25 mesh units across the picture
strip=(--model "$tiling_model" --mapping uv --size 128x64 --texture-scale 150.5 --camera "$camera")
# The seam's step over the interior's, from a PFM of the strip.
seam_step() {
  python3 - "$1" <<'EOF'
import struct, sys
data = open(sys.argv[1], "rb").read()
header = data.split(b"\n", 3)
width, height = map(int, header[1].split())
channels = 3 if header[0] == b"PF" else 1
order = "<" if float(header[2]) < 0 else ">"
count = width * height * channels
values = struct.unpack(order + "f" * count, header[3][: 4 * count])
at = lambda x, y, c: values[(y * width + x) * channels + c]
steps = [sum(abs(at(x + 1, y, c) - at(x, y, c)) for y in range(height) for c in range(channels))
         for x in range(width - 1)]
seam = steps[width // 2 - 1]
print("%.3f" % (seam / ((sum(steps) - seam) / (len(steps) - 1))))
EOF
}
for seed in 1 2; do
  expect_ok "render-mesh strip, seed $seed" "$stochtex" render-mesh "$inputs/strip.obj" \
    "${strip[@]}" --seed "$seed" -o "$models/strip_$seed.pfm" &&
    if grep -q "note: .*strip.obj.* uv wrap seam.*--periodic" "$work/stderr"; then pass; else
      fail "render-mesh notes the uv wrap seam" "stderr: $(cat "$work/stderr")"
    fi
  expect_ok "render-mesh strip --periodic, seed $seed" "$stochtex" render-mesh \
    "$inputs/strip.obj" "${strip[@]}" --seed "$seed" -o "$models/strip_periodic_$seed.pfm" \
    --periodic &&
    if grep -q "note:" "$work/stderr"; then
      fail "render-mesh --periodic notes no seam" "stderr: $(cat "$work/stderr")"
    else pass; fi
  step=$(seam_step "$models/strip_$seed.pfm")
  if python3 -c "import sys; sys.exit(not $step > 1.75)"; then pass; else
    fail "the default strip steps at its seam, seed $seed" "seam step $step"
  fi
  step=$(seam_step "$models/strip_periodic_$seed.pfm")
  if python3 -c "import sys; sys.exit(not $step < 1.75)"; then pass; else
    fail "the --periodic strip steps as its interior, seed $seed" "seam step $step"
  fi
done
# Refused before the mesh is read: another mapping than uv, the gl backend (a texton mix and an
# lrp structure component: tests/cli/cli_periodic.sh).
expect_error "render-mesh --periodic --mapping triplanar-linear" 2 "needs the uv mapping" \
  "$stochtex" render-mesh "$inputs/missing.obj" --model "$tiling_model" -o "$out/x.png" --periodic
expect_error "render-mesh --periodic --backend gl" 2 "--backend cpu" \
  "$stochtex" render-mesh "$inputs/missing.obj" --model "$tiling_model" -o "$out/x.png" \
  --mapping uv --periodic --backend gl

# A UV sphere's pole rows hold triangles of zero area (two corners at the pole): they are skipped
# as renderers skip them, with a warning that counts them, and the rest renders.
python3 - "$inputs/pole.obj" <<'EOF'
import math, sys
rows, columns = 6, 8
lines = []
for i in range(rows + 1):
    for j in range(columns + 1):
        theta, phi = math.pi * i / rows, 2 * math.pi * j / columns
        lines.append("v %.6f %.6f %.6f" % (math.sin(theta) * math.cos(phi), math.cos(theta),
                                           math.sin(theta) * math.sin(phi)))
for i in range(rows):
    for j in range(columns):
        a, b = i * (columns + 1) + j + 1, (i + 1) * (columns + 1) + j + 1
        lines += ["f %d %d %d" % (a, b, b + 1), "f %d %d %d" % (a, b + 1, a + 1)]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
EOF
expect_ok "render-mesh of a UV sphere with degenerate pole triangles" "$stochtex" render-mesh \
  "$inputs/pole.obj" --model "$tiling_model" -o "$models/pole.png" --size 48x48 &&
  if grep -q "warning: .*pole.obj.*skipped 16 degenerate triangle" "$work/stderr"; then pass; else
    fail "render-mesh counts the skipped triangles" "stderr: $(cat "$work/stderr")"
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

summary
