"""Pictures and numbers of docs/materials.md: the shipped rock_sandstone material analysed with
every method through the Python module, each method's albedo, normal and height maps rendered at
256x256 (seed 1), the albedo lit by the rendered normal map, and per method, from a 512x512 render
of seed 1, the largest error of the rendered N x N correlation matrix against the exemplar's
(normal maps as their two slopes), the 1-D Wasserstein distance of the slope magnitude's histogram
and the normals' largest length error. Usage: python3 scripts/materials_figures.py BUILD_DIR OUT_DIR"""

import sys
import time

import numpy
from PIL import Image

build, out = sys.argv[1], sys.argv[2]
sys.path.insert(0, build + "/python")
import stochtex  # noqa: E402

root = __file__.rsplit("/scripts/", 1)[0]
folder = root + "/data/materials/rock_sandstone/"
names = ["albedo", "normal", "roughness", "height", "ao"]
maps = {name: numpy.asarray(Image.open(folder + name + ".png")) for name in names}
SIZE = 512
PICTURE = 256
LIGHT = numpy.array([-0.5, 0.5, 0.7]) / numpy.linalg.norm([-0.5, 0.5, 0.7])


def save(array, name):
    Image.fromarray(numpy.clip(numpy.rint(array * 255.0), 0, 255).astype(numpy.uint8).squeeze()
                    ).save(f"{out}/{name}.png")


def lit(albedo, normal):
    """The albedo under a directional light from the upper left, Lambert, normal encoded 0.5+0.5n."""
    n = normal * 2.0 - 1.0
    shade = numpy.clip(n @ LIGHT, 0.0, 1.0)[:, :, None]
    return albedo * (0.25 + 0.75 * shade)


def slopes(normal):
    n = normal * 2.0 - 1.0
    return numpy.stack([-n[..., 0] / n[..., 2], -n[..., 1] / n[..., 2]], axis=2)


def channels(parts):
    """A material's maps side by side, the normal map as its two slopes (the model's channels)."""
    return numpy.concatenate([slopes(parts[n]) if n == "normal" else parts[n].reshape(
        parts[n].shape[0], parts[n].shape[1], -1) for n in names], axis=2).reshape(-1, 8)


def quantile_distance(a, b):
    """The mean absolute difference of the quantiles at (k + 1/2) / n, n the smaller size."""
    a, b = numpy.sort(a), numpy.sort(b)
    n = min(a.size, b.size)
    k = numpy.arange(n)
    return numpy.mean(numpy.abs(a[(2 * k + 1) * a.size // (2 * n)] - b[(2 * k + 1) * b.size // (2 * n)]))


exemplar = {n: maps[n].astype(numpy.float64) / 255.0 for n in names}
target = numpy.corrcoef(channels(exemplar).T)
target_slope = numpy.linalg.norm(slopes(exemplar["normal"]), axis=2).ravel()
save(exemplar["albedo"], "rock_albedo")
save(exemplar["normal"], "rock_normal")
save(exemplar["height"], "rock_height")
save(lit(exemplar["albedo"], exemplar["normal"]), "rock_lit")
print("| method | analysis (s) | largest correlation error | slope histogram W1 | "
      "normal length error |")
print("|---|---|---|---|---|")
# Each method at its defaults, then tiling with its artist controls: every patch turned and scaled
# (its normal map's slopes with it) and the height-aware blend.
CONTROLS = {"rotation": 180, "scale_jitter": 0.5, "height_blend": 0.1}
for label, method, params in [("texton", "texton", {}), ("tiling", "tiling", {}),
                              ("lrp", "lrp", {}), ("gabor", "gabor", {}),
                              ("tiling_controls", "tiling", CONTROLS)]:
    start = time.perf_counter()
    model = stochtex.analyze_material(maps, method, **params)
    seconds = time.perf_counter() - start
    # The albedo (sRGB) encoded as its PNG and the exemplar hold it, for the pictures and the
    # correlations with the other maps.
    parts = model.render_maps(SIZE, SIZE, seed=1, encoded=True)
    picture = {name: part[:PICTURE, :PICTURE] for name, part in parts.items()}
    save(picture["albedo"], f"{label}_albedo")
    save(picture["normal"], f"{label}_normal")
    save(picture["height"], f"{label}_height")
    save(lit(picture["albedo"], picture["normal"]), f"{label}_lit")
    error = numpy.abs(numpy.corrcoef(channels(parts).T) - target).max()
    slope = numpy.linalg.norm(slopes(parts["normal"]), axis=2).ravel()
    length = numpy.abs(numpy.linalg.norm(parts["normal"] * 2.0 - 1.0, axis=2) - 1.0).max()
    print(f"| {label.replace('_', ' ')} | {seconds:.1f} | {error:.3f} | "
          f"{quantile_distance(slope, target_slope):.3f} | {length:.1e} |")
