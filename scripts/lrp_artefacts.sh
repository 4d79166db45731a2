#!/usr/bin/env bash
# docs/methods/lrp.md "Dots, streaks and swirl (issue 37)": measures the three lrp artefacts that
# issue 37 reported, beside the Gaussian reference (ADSN, `stochtex gaussian`), and writes the
# pictures into docs/images/lrp/artefacts_*.png. Prints:
#  - dots: concrete_cement_512 at scale 8, the samples of the first channel beyond 4 standard
#    deviations per 512^2 render (a Gaussian field: 16.6);
#  - streaks: water_caustics_256 at scale 8, the share of power within 2 bins of the f_y = 0 and
#    f_x = 0 lines, lrp with and without `deblur` against ADSN box-filtered from 4096^2;
#  - swirl: water and concrete at scale 1, the mean orientation coherence of the structure tensor
#    (9x9 box) for ADSN, texton and lrp at J = 50, 100, 200, with lrp's one-thread render time.
# Needs a built CLI in build/ and /usr/bin/python3 with numpy and PIL.
# Usage: [PICTURES=folder] bash scripts/lrp_artefacts.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
stochtex="$root/build/stochtex"
exemplars="$root/data/exemplars"
pictures="${PICTURES:-$root/docs/images/lrp}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$pictures"
quiet() { "$@" >/dev/null 2>&1; }

concrete="$exemplars/concrete_cement_512.png"
water="$exemplars/water_caustics_256.png"
quiet "$stochtex" analyze "$concrete" -m lrp -o "$work/concrete.stx"
quiet "$stochtex" analyze "$concrete" -m lrp -p cosines=100 -o "$work/concrete_J100.stx"
quiet "$stochtex" analyze "$concrete" -m texton -o "$work/concrete_texton.stx"
quiet "$stochtex" analyze "$water" -m lrp -o "$work/water.stx"
quiet "$stochtex" analyze "$water" -m lrp -p deblur=0 -o "$work/water_nodeblur.stx"
quiet "$stochtex" analyze "$water" -m texton -o "$work/water_texton.stx"
for cosines in 100 200; do
  quiet "$stochtex" analyze "$water" -m lrp -p cosines=$cosines -o "$work/water_J$cosines.stx"
done

for seed in 1 2 3 4; do
  quiet "$stochtex" render "$work/concrete.stx" -o "$work/dots_$seed.pfm" --size 512x512 \
    --seed $seed --scale 8
done
"$stochtex" render "$work/concrete.stx" -o "$pictures/artefacts_concrete_scale8.png" \
  --size 384x384 --seed 1 --scale 8 >/dev/null
for seed in 1 2 3; do
  for model in water water_nodeblur; do
    quiet "$stochtex" render "$work/$model.stx" -o "$work/streaks_${model}_$seed.png" \
      --size 512x512 --seed $seed --scale 8
  done
done
quiet "$stochtex" gaussian "$water" -o "$work/water_adsn_4096.png" --size 4096x4096 --seed 1
for texture in water concrete; do
  exemplar="$water"
  [ "$texture" = concrete ] && exemplar="$concrete"
  for seed in 1 2; do
    quiet "$stochtex" gaussian "$exemplar" -o "$work/swirl_${texture}_adsn_$seed.png" \
      --size 512x512 --seed $seed
    for model in "$texture" "${texture}_texton" "${texture}_J100" "${texture}_J200"; do
      [ -f "$work/$model.stx" ] || continue
      quiet "$stochtex" render "$work/$model.stx" -o "$work/swirl_${model}_$seed.png" \
        --size 512x512 --seed $seed
    done
  done
done
for model in water water_J100 water_J200; do
  start=$(date +%s.%N)
  quiet "$stochtex" render "$work/$model.stx" -o "$work/timing.pfm" --size 512x512 --threads 1
  echo "$model $(echo "$(date +%s.%N) - $start" | bc)" >>"$work/times.txt"
done

PYTHONPATH="$root/scripts" /usr/bin/python3 - "$work" "$pictures" <<'EOF'
import sys
import numpy as np
from PIL import Image
from pfm import read_pfm
work, pictures = sys.argv[1], sys.argv[2]

def grey(path):
    return np.asarray(Image.open(path).convert("L"), dtype=np.float64)

def box(x, k):
    c = np.cumsum(np.cumsum(np.pad(x, ((k // 2 + 1, k // 2), (k // 2 + 1, k // 2)), mode="wrap"), 0), 1)
    return (c[k:, k:] - c[:-k, k:] - c[k:, :-k] + c[:-k, :-k]) / (k * k)

def axis_shares(x):
    x = x - x.mean()
    n = x.shape[0]
    power = np.abs(np.fft.fft2(x)) ** 2
    power[0, 0] = 0
    fy = np.abs(np.fft.fftfreq(n))[:, None] * n
    fx = np.abs(np.fft.fftfreq(n))[None, :] * n
    total = power.sum()
    return power[(fy <= 2) & (fx > 2)].sum() / total, power[(fx <= 2) & (fy > 2)].sum() / total

def coherence(x):
    gy, gx = np.gradient(x)
    a, b, c = box(gx * gx, 9), box(gy * gy, 9), box(gx * gy, 9)
    return (np.sqrt((a - b) ** 2 + 4 * c * c) / (a + b + 1e-9)).mean()

print("dots: concrete at scale 8, samples beyond 4 standard deviations per 512^2 render (Gaussian: 16.6)")
counts = []
for seed in range(1, 5):
    x = read_pfm(f"{work}/dots_{seed}.pfm")[:, :, 0].astype(np.float64)
    counts.append(int((np.abs(x - x.mean()) > 4 * x.std()).sum()))
print("  lrp:", counts)

# ADSN box-filtered 8x8 in linear light, encoded again: what a zoomed-out Gaussian texture shows.
encoded = np.asarray(Image.open(f"{work}/water_adsn_4096.png").convert("RGB"), dtype=np.float64) / 255
linear = np.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)
boxed = linear.reshape(512, 8, 512, 8, 3).mean(axis=(1, 3))
boxed = np.where(boxed <= 0.0031308, boxed * 12.92, 1.055 * boxed ** (1 / 2.4) - 0.055)
reference = Image.fromarray((boxed * 255 + 0.5).astype(np.uint8))
reference.save(f"{work}/water_adsn_scale8.png")
print("streaks: water at scale 8, share of power on the f_y = 0 line (vertical streaks), on f_x = 0")
row, column = axis_shares(grey(f"{work}/water_adsn_scale8.png"))
print(f"  ADSN box-filtered: {row:.3f}, {column:.3f}")
for model, label in (("water", "lrp (deblur on, default)"), ("water_nodeblur", "lrp deblur=0")):
    shares = [axis_shares(grey(f"{work}/streaks_{model}_{seed}.png")) for seed in (1, 2, 3)]
    print(f"  {label}: " + ", ".join(f"{r:.3f}/{c:.3f}" for r, c in shares))

print("swirl: mean orientation coherence at scale 1 (seeds 1, 2)")
for texture in ("water", "concrete"):
    for model, label in (("adsn", "ADSN"), ("texton", "texton"), ("", "lrp J=50 (default)"),
                         ("J100", "lrp J=100"), ("J200", "lrp J=200")):
        name = f"{texture}_{model}" if model else texture
        try:
            values = [coherence(grey(f"{work}/swirl_{name}_{seed}.png")) for seed in (1, 2)]
        except FileNotFoundError:
            continue
        print(f"  {texture} {label}: " + ", ".join(f"{v:.3f}" for v in values))
for line in open(f"{work}/times.txt"):
    model, seconds = line.split()
    print(f"  one-thread 512^2 render of {model}: {float(seconds):.2f} s")

# Pictures: water at scale 8 (ADSN box-filtered | lrp | lrp deblur=0) and at scale 1 (ADSN | lrp
# J=50 | lrp J=100), 256x256 crops side by side.
def row_of(paths, crop=256):
    images = [Image.open(p).convert("RGB").crop((0, 0, crop, crop)) for p in paths]
    out = Image.new("RGB", (crop * len(images) + 8 * (len(images) - 1), crop), (255, 255, 255))
    for i, image in enumerate(images):
        out.paste(image, (i * (crop + 8), 0))
    return out
row_of([f"{work}/water_adsn_scale8.png", f"{work}/streaks_water_1.png",
        f"{work}/streaks_water_nodeblur_1.png"]).save(f"{pictures}/artefacts_water_scale8.png")
row_of([f"{work}/swirl_water_adsn_1.png", f"{work}/swirl_water_1.png",
        f"{work}/swirl_water_J100_1.png"]).save(f"{pictures}/artefacts_water_swirl.png")
EOF
