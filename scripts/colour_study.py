#!/usr/bin/env python3
"""Where should a model live, in the photo's encoded values or in linear light? (issue 36)

For each sRGB photo of data/exemplars and each method, at its defaults:
  encoded  the model of the file's values, as stochtex analyses today;
  linear   the model of the values decoded to linear light (the sRGB transfer function,
           IEC 61966-2-1), its renders encoded again before they are measured.
Both are measured against the file as it is, with the measures of docs/fidelity.md (the spectral
error of a 1024² render over compare's ADSN sample's, seeds 1 and 2; the colour covariance
error), and zoomed out: the mean of a 64² render at scale 32 against the photo's mean in linear
light, encoded (what a camera, a supersampled render or an engine's sRGB mip-mapping shows), in
8-bit levels, the largest over the channels.

usage (from the repository root, after a build):
  PYTHONPATH=build/python /usr/bin/python3 scripts/colour_study.py [EXEMPLAR.png ...] > table.md
"""

import sys
from pathlib import Path

import numpy as np
import stochtex

# The sRGB photos of data/exemplars: the fidelity set (docs/fidelity.md) without its height and
# roughness maps, which are data, and the high-contrast photos the issue measured.
DEFAULT = [
    "concrete_cement_512", "grass_lawn_256", "grass_lawn_128", "brushed_aluminium_grey_256",
    "rock_sandstone_512", "wood_planks_256", "metal_grey_256", "moss_ground_512",
    "nuts_grey_256", "water_caustics_256", "cobblestone_512",
]
METHODS = ["texton", "lrp", "gabor", "tiling"]
SIZE = 1024


def decode(encoded):
    """sRGB-encoded values in [0, 1] to linear light."""
    v = np.clip(encoded, 0.0, 1.0).astype(np.float64)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4).astype(np.float32)


def encode(linear):
    """Linear light to sRGB-encoded values in [0, 1]."""
    v = np.clip(linear, 0.0, 1.0).astype(np.float64)
    return np.where(v <= 0.0031308, v * 12.92, 1.055 * v ** (1 / 2.4) - 0.055).astype(np.float32)


def measure(exemplar, method, linear):
    """The fidelity measures and the zoomed-out mean error of one design."""
    model = stochtex.analyze(decode(exemplar) if linear else exemplar, method)
    shown = encode if linear else (lambda values: values)
    ratios, covariances = [], []
    for seed in (1, 2):
        render = shown(model.render(SIZE, SIZE, seed=seed))
        numbers = stochtex.compare(exemplar, render)
        ratios.append(numbers["spectral_error"] / numbers["spectral_error_adsn"])
        covariances.append(numbers["covariance_error"])
    far = model.render(64, 64, scale=32.0, seed=1)
    far_mean = encode(far.reshape(-1, far.shape[-1]).mean(axis=0)) if linear else \
        far.reshape(-1, far.shape[-1]).mean(axis=0)
    truth = encode(decode(exemplar).reshape(-1, exemplar.shape[-1]).mean(axis=0))
    zoom = 255.0 * float(np.max(np.abs(far_mean - truth)))
    return ratios, covariances, zoom


def main():
    names = sys.argv[1:] or [f"data/exemplars/{name}.png" for name in DEFAULT]
    print("| exemplar | method | spectral / ADSN's, encoded | linear | covariance error, encoded "
          "| linear | zoomed-out mean error (8-bit levels), encoded | linear |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        exemplar = stochtex.read_image(name)
        for method in METHODS:
            rows = [measure(exemplar, method, linear) for linear in (False, True)]
            cells = [" / ".join(f"{r:.2f}" for r in rows[k][0]) for k in (0, 1)]
            cells += [" / ".join(f"{c:.3f}" for c in rows[k][1]) for k in (0, 1)]
            cells += [f"{rows[k][2]:.1f}" for k in (0, 1)]
            print(f"| {Path(name).stem} | {method} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
