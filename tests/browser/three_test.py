#!/usr/bin/python3
"""stochtex-three (web/three) in three.js from npm, in headless Chromium (docs/engines.md,
"three.js").

Installs the three.js that web/three/package.json pins (devDependencies) with npm into NPM_DIR
(once; later runs find it there), checks that `npm pack` packs the module, analyses five models
(a srgb and a data texton model of grass_lawn_128; tiling models of rock_sandstone's albedo,
srgb, and of its normal and height maps, data: the height's one channel makes one-channel
textures), writes them with `stochtex export-web`, serves them with three.js and the module,
and drives tests/browser/three/index.html in headless Chromium
(SwiftShader's WebGL2, as browser_test.py). On a 128 x 128 orthographic quad, seed 7, it compares
with `stochtex render` of the same region:

- the ShaderMaterial's values (a float render target): every model, both variants, at scale 1
  and zoomed out 16x: pixel for pixel where the shader is exact, in variance zoomed out where
  the hardware filters (the fast variant);
- what the canvas shows (three.js's sRGB output) of a srgb model: the CPU render's PNG bytes;
- the exports as the maps of a lit MeshStandardMaterial, against the same material with float
  DataTextures of the CPU renders, read texel for pixel: a srgb model's as `map`, a data model's
  with colorSpace SRGBColorSpace (decoded) as `map`, and the albedo and normal exports (two
  tiling libraries in one shader) as `map` and `normalMap` together.

It fails on any JavaScript console error. With --screenshots DIR it then renders the picture of
docs/engines.md (DIR/three.png).

Usage: three_test.py STOCHTEX SOURCE_DIR NPM_DIR [--screenshots DIR]
Exit 77 (CTest's SKIP_RETURN_CODE) when chromium or npm is not installed or npm cannot install
three.js (no network and none installed before).
"""

import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy

from browser_test import SKIP, browser, cpu_render, run_page, serve, srgb_encode

SIZE = 128  # the page's quad, in pixels (tests/browser/three/three_page.js)
SEED = 7
# (origin, scale): scale 1 off the origin, and zoomed out 16x.
VIEWS = [((-40.0, 24.0), 1.0), ((-1000.0, 512.0), 16.0)]

# Bounds (docs/engines.md, "three.js", has what was measured on Chromium 156's SwiftShader):
# - an exact shader's largest |three.js - CPU| per value, and the fast shader's at scale 1. The
#   browser test's bounds (browser_test.py, docs/studio.md): 1e-5 for exact shaders, 1/255 for
#   the fast path, times 5.8 for a srgb model's linear light (the decoding's largest slope). The
#   quad's p is interpolated from its uv and its footprint is dFdx(p) (the viewer's come from
#   gl_FragCoord and the scale): exact shaders measured at most 2.4e-6 here;
EXACT_BOUND = 1e-5
FAST_BOUND = 1.0 / 255.0
DECODING_SLOPE = 5.8
# - zoomed out 16x, |variance / CPU variance - 1| per channel: browser_test.py's bound;
VARIANCE_BOUND = 0.08 + 3 * 0.021
# - the canvas against the CPU render's PNG bytes: one level (rounding);
CANVAS_LEVELS = 1
# - a lit standard material with the export against the same material with the CPU render's
#   texture: the map's difference through the page's lighting. Measured by moving one channel of
#   the reference texture by 1e-3 and 1e-2: a shaded value moves by at most 0.68 times a map
#   channel's change (its own channel only), and by 1.42, 1.25 and 1.29 times a normal map's x,
#   y and z (all three move it: 3.96 together). Bound: twice that times the exact shader's bound
#   (linear light: times DECODING_SLOPE).
MAP_GAIN = 2 * 0.68
NORMAL_GAIN = 2 * 3.96


def install_three(source, npm_dir):
    """Installs the pinned three.js into npm_dir unless it is there. Returns None or why not."""
    with open(os.path.join(source, "web", "three", "package.json")) as file:
        version = json.load(file)["devDependencies"]["three"]
    installed = os.path.join(npm_dir, "node_modules", "three", "package.json")
    if os.path.exists(installed):
        with open(installed) as file:
            if json.load(file)["version"] == version:
                return None
    os.makedirs(npm_dir, exist_ok=True)
    with open(os.path.join(npm_dir, "package.json"), "w") as file:
        json.dump({"private": True, "dependencies": {"three": version}}, file)
    result = subprocess.run(["npm", "install", "--no-audit", "--no-fund", "--fetch-retries=1",
                             "--fetch-timeout=30000"], cwd=npm_dir, capture_output=True, text=True)
    if result.returncode != 0:
        reason = next((line for line in result.stderr.splitlines() if "Error" in line),
                      result.stderr.strip())
        return f"npm cannot install three@{version}: {reason}"
    print(f"installed three@{version} into {npm_dir}")
    return None


def check_package(source):
    """`npm pack` packs the module: its name and file."""
    listed = subprocess.run(["npm", "pack", "--dry-run", "--json"],
                            cwd=os.path.join(source, "web", "three"), check=True,
                            capture_output=True, text=True).stdout
    package = json.loads(listed)[0]
    files = {entry["path"] for entry in package["files"]}
    if package["name"] != "stochtex-three" or "stochtex-three.js" not in files:
        return [f"npm pack: {package['name']} with {sorted(files)}"]
    return []


def web_values(text):
    """The page's float RGBA (bottom row first) as a SIZE x SIZE x 4 array, top row first."""
    values = numpy.frombuffer(base64.b64decode(text), dtype="<f4").reshape(SIZE, SIZE, 4)
    return values[::-1]


def cpu_values(stochtex, model, view, work):
    width, height, channels, values = cpu_render(stochtex, model, view[0], view[1], SEED, work,
                                                 SIZE)
    return numpy.array(values, dtype=numpy.float64).reshape(height, width, channels)


def srgb_decode(values):
    values = numpy.clip(values, 0.0, 1.0)
    return numpy.where(values <= 0.04045, values / 12.92, ((values + 0.055) / 1.055) ** 2.4)


def reference_texels(values):
    """A CPU render (top row first, 3 channels) as the page's DataTexture: RGBA float32, bottom row
    first, alpha 1."""
    rgba = numpy.ones((SIZE, SIZE, 4), dtype="<f4")
    rgba[..., :3] = values
    return base64.b64encode(rgba[::-1].tobytes()).decode()


def call(driver, function, *arguments):
    """window.stochtexThree[function](...arguments), awaited; its result."""
    result = driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        f"window.stochtexThree.{function}(...[...arguments].slice(0, -1))"
        ".then((r) => done({r}), (e) => done({e: String(e)}));", *arguments)
    if "e" in result:
        raise RuntimeError(f"{function}: {result['e']}")
    return result["r"]


def compare(what, web, cpu, bound, scale):
    """Failures of `web` against `cpu` (its channels; a grey model shows as r = g = b): the largest
    difference within `bound` (None: not compared) and, zoomed out, the variances within
    VARIANCE_BOUND."""
    channels = cpu.shape[2]
    web = web[..., :channels]
    largest = float(numpy.abs(web - cpu).max())
    ratio = float(numpy.abs(web.reshape(-1, channels).var(0) / cpu.reshape(-1, channels).var(0)
                            - 1).max())
    shown = "-" if bound is None else f"{bound:.3g}"
    print(f"{what:34} scale {scale:3g}: max |three - cpu| {largest:.3g} (bound {shown}), "
          f"|variance / cpu's - 1| {ratio:.3g}")
    failures = []
    if bound is not None and not largest <= bound:
        failures.append(f"{what} scale {scale:g}: max |three - cpu| {largest:.3g} > {bound:.3g}")
    if scale > 1 and not ratio <= VARIANCE_BOUND:
        failures.append(f"{what} scale {scale:g}: variance off by {ratio:.3g} > "
                        f"{VARIANCE_BOUND:.3g}")
    return failures


def check_shaders(driver, stochtex, models, work):
    """The ShaderMaterial of every model and variant against `stochtex render`."""
    failures = []
    for view in VIEWS:
        for name, (path, linear) in models.items():
            cpu = cpu_values(stochtex, path, view, work)
            for variant in ["exact", "fast"]:
                web = web_values(call(driver, "shader", f"/site/models/{name}/{variant}",
                                      {"x": view[0][0], "y": view[0][1], "scale": view[1]}, SEED))
                bound = EXACT_BOUND if variant == "exact" else (FAST_BOUND if view[1] == 1
                                                                 else None)
                if bound is not None and linear:
                    bound *= DECODING_SLOPE
                failures += compare(f"ShaderMaterial {name} {variant}", web, cpu, bound, view[1])
    return failures


def check_canvas(driver, stochtex, path, name, work):
    """The canvas (three.js's sRGB output) of a srgb model against the CPU render's PNG bytes:
    its linear light encoded."""
    view = VIEWS[0]
    shown = numpy.frombuffer(base64.b64decode(
        call(driver, "canvas", f"/site/models/{name}/exact",
             {"x": view[0][0], "y": view[0][1], "scale": view[1]}, SEED)),
        dtype=numpy.uint8).reshape(SIZE, SIZE, 4)[::-1, :, :3].astype(int)
    cpu = cpu_values(stochtex, path, view, work)
    expected = numpy.vectorize(lambda v: round(255 * srgb_encode(v)))(cpu)
    largest = int(numpy.abs(shown - expected).max())
    print(f"canvas {name:27} scale   1: max |shown - encoded cpu| {largest} levels of 255 "
          f"(bound {CANVAS_LEVELS})")
    return [] if largest <= CANVAS_LEVELS else [f"canvas {name}: {largest} levels off"]


def check_standard(driver, stochtex, slots, work):
    """Exports as the maps of a lit MeshStandardMaterial against the CPU renders as textures.
    slots: {slot: (name, model, colour)}, colour 'linear' (a srgb model), 'srgb' (a data model of
    a photo: colorSpace SRGBColorSpace, its reference decoded) or 'data'."""
    view = {"x": VIEWS[0][0][0], "y": VIEWS[0][0][1], "scale": VIEWS[0][1]}
    urls, colour_spaces, texels = {}, {}, {}
    bound = 0.0
    for slot, (name, path, colour) in slots.items():
        cpu = cpu_values(stochtex, path, VIEWS[0], work)
        urls[slot] = f"/site/models/{name}/exact"
        if colour == "srgb":
            colour_spaces[slot] = "srgb"
        texels[slot] = reference_texels(srgb_decode(cpu) if colour == "srgb" else cpu)
        bound += EXACT_BOUND * (NORMAL_GAIN if slot == "normalMap" else MAP_GAIN) * \
            (1 if colour == "data" else DECODING_SLOPE)
    web = web_values(call(driver, "standard", urls, view, SEED, colour_spaces))
    reference = web_values(call(driver, "reference", texels))
    what = " + ".join(f"{slot} {name}" for slot, (name, _, _) in slots.items())
    largest = float(numpy.abs(web[..., :3] - reference[..., :3]).max())
    print(f"MeshStandardMaterial {what:27}: max |export - CPU texture| {largest:.3g} (bound "
          f"{bound:.3g}; shaded values {reference[..., :3].min():.3g} to "
          f"{reference[..., :3].max():.3g})")
    return [] if largest <= bound else [f"{what}: {largest:.3g} > {bound:.3g}"]


def check_linear_stays_linear(driver):
    """A srgb model's export (linear light) refuses to be decoded again."""
    try:
        call(driver, "shader", "/site/models/albedo/exact", {"x": 0, "y": 0, "scale": 1}, SEED,
             "srgb")
    except RuntimeError as error:
        if "returns linear light" in str(error):
            return []
        return [f"colorSpace srgb on a linear export: {error}"]
    return ["colorSpace srgb on a linear export was accepted (its light would be decoded twice)"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("stochtex")
    parser.add_argument("source", help="the repository (web/three, tests/browser/three, data)")
    parser.add_argument("npm_dir", help="where npm installs three.js (a build folder)")
    parser.add_argument("--screenshots", help="folder for docs/engines.md's picture")
    args = parser.parse_args()
    if not shutil.which("chromium"):
        print("SKIP: chromium is not installed (scripts/install-deps.sh installs it)")
        return SKIP
    if not shutil.which("chromedriver"):
        print("FAIL: chromium is installed without chromedriver; run scripts/install-deps.sh")
        return 1
    if not shutil.which("npm"):
        print("SKIP: npm is not installed (scripts/install-deps.sh installs it)")
        return SKIP
    start = time.time()
    why_not = install_three(args.source, args.npm_dir)
    if why_not:
        print(f"SKIP: {why_not}")
        return SKIP
    failures = check_package(args.source)
    exemplars = os.path.join(args.source, "data", "exemplars")
    rock = os.path.join(args.source, "data", "materials", "rock_sandstone")
    with tempfile.TemporaryDirectory(prefix="stochtex_three_") as work:
        # name: (exemplar, method, colour space)
        analyses = {"grass": (os.path.join(exemplars, "grass_lawn_128.png"), "texton", "srgb"),
                    "grass_data": (os.path.join(exemplars, "grass_lawn_128.png"), "texton",
                                   "data"),
                    "albedo": (os.path.join(rock, "albedo.png"), "tiling", "srgb"),
                    "normal": (os.path.join(rock, "normal.png"), "tiling", "data"),
                    "height": (os.path.join(rock, "height.png"), "tiling", "data")}
        models = {}
        for name, (exemplar, method, colour) in analyses.items():
            path = os.path.join(work, f"{name}.stx")
            subprocess.run([args.stochtex, "analyze", exemplar, "-m", method, "-o", path,
                            "--colour-space", colour], check=True, capture_output=True)
            models[name] = (path, colour == "srgb")
        site = os.path.join(work, "root", "site")
        subprocess.run([args.stochtex, "export-web", *(path for path, _ in models.values()), "-o",
                        site], check=True, capture_output=True)
        root = os.path.dirname(site)
        os.symlink(os.path.join(os.path.abspath(args.npm_dir), "node_modules", "three"),
                   os.path.join(root, "three"))
        os.symlink(os.path.join(args.source, "web", "three"), os.path.join(root, "stochtex-three"))
        os.symlink(os.path.join(args.source, "tests", "browser", "three"),
                   os.path.join(root, "page"))
        server = serve(root)
        driver = browser()
        try:
            driver.get(f"http://127.0.0.1:{server.server_address[1]}/page/index.html")
            run_page(driver, "while (!window.stochtexThree) "
                     "await new Promise((resolve) => setTimeout(resolve, 20));")
            print(f"page loaded after {time.time() - start:.1f} s")
            shaders = {name: model for name, model in models.items() if name != "grass_data"}
            failures += check_shaders(driver, args.stochtex, shaders, work)
            failures += check_canvas(driver, args.stochtex, models["albedo"][0], "albedo", work)
            failures += check_linear_stays_linear(driver)
            albedo = ("albedo", models["albedo"][0], "linear")
            for slots in [{"map": albedo},
                          {"map": ("grass_data", models["grass_data"][0], "srgb")},
                          {"map": albedo, "normalMap": ("normal", models["normal"][0], "data")}]:
                failures += check_standard(driver, args.stochtex, slots, work)
            if args.screenshots:
                os.makedirs(args.screenshots, exist_ok=True)
                url = call(driver, "picture", "/site/models/albedo/exact",
                           "/site/models/normal/exact", 768, 432)
                picture = os.path.join(args.screenshots, "three.png")
                with open(picture, "wb") as file:
                    file.write(base64.b64decode(url.split(",", 1)[1]))
                print(f"wrote {picture}")
            for entry in driver.get_log("browser"):
                if entry["level"] == "SEVERE":
                    failures.append(f"console: {entry['message']}")
        finally:
            driver.quit()
            server.shutdown()
    print(f"took {time.time() - start:.1f} s")
    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
