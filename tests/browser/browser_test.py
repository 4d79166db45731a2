#!/usr/bin/python3
"""The web viewer in a real browser (docs/studio.md, "Browser parity").

Analyses a small shipped exemplar with every method of the registry (`stochtex methods --json`)
and makes a texton mixing model, writes them with `stochtex export-web`, serves the folder over
HTTP and loads the page in headless Chromium (SwiftShader's WebGL2). For each model and variant
it checks that the viewer loaded that variant's export, reads the viewer's float values back
(viewer.readPixels through the page's window.stochtexPage) and compares them with `stochtex
render` of the same model, view and seed: pixel for pixel where the shader is the CPU's to float
rounding, in variance when zoomed out 16x (the filtered render's). A texton model of the srgb
colour space is among them: its values are linear light, and the canvas must show them
sRGB-encoded (a data model's as they are). It checks the wheel and drag and a shader that does
not compile, and fails on any JavaScript console error.

Usage: browser_test.py STOCHTEX EXEMPLAR [--second EXEMPLAR] [--screenshots DIR] [--measure]
Exit 77 (CTest's SKIP_RETURN_CODE) when chromium is not installed.
"""

import argparse
import base64
import functools
import http.server
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time

SKIP = 77
SIZE = 128  # canvas side: SwiftShader on two shared cores is slow
SEED = 7
# (origin, scale) of the compared views: scale 1 off the origin, and zoomed out 16x.
VIEWS = [((-40.0, 24.0), 1.0), ((-1000.0, 512.0), 16.0)]
# The manifest's fields that name a variant and do not change what the viewer draws.
VARIANT_LABELS = ("variant", "shader_variant", "note")

# The bounds, from what was measured on Chromium 156's SwiftShader here (docs/studio.md, "Browser
# parity", has the numbers):
# - where the web shader is the CPU's evaluator (every exact variant but gabor's, and lrp's and
#   texton_mix's fast ones, which are their exact ones), largest |web - CPU| per value: measured
#   at most 1.0e-6 (lrp) on this page's 128^2 views and 3.0e-6 (texton, lrp) at scale 1 on the
#   studio's 256^2 canvases, bound ten times the first, three times the second;
EXACT_BOUND = 1e-5
# - gabor's float-only shader (both variants: its exact one needs doubles): the tolerance
#   docs/shaders.md gives it, 1e-3 of the image's standard deviation (the smallest channel's, of
#   the CPU render at that view): bound 3.8e-5 at scale 1 and 7.2e-6 at 16, measured 2.2e-6 and
#   5.4e-7 (on the studio's 256^2 canvases bound 3.8e-5 and 7.3e-6, measured 5.1e-6 and 1.0e-6);
GABOR_DEVIATIONS = 1e-3
# - texton's and tiling's fast variant at scale 1: the fast path's bound (docs/shaders.md), 1/255;
#   measured 4.1e-5 and 3.1e-4 with the web export's half-float textures;
FAST_BOUND = 1.0 / 255.0
# - every model zoomed out 16x: |variance / CPU variance - 1| per channel. The estimator's own
#   noise (128^2 CPU renders at scale 16, 8 seeds) is at most 2.1 % (relative standard deviation),
#   hardware trilinear filtering raises texton's variance by up to 8 % (docs/shaders.md); bound
#   8 % + 3 x 2.1 %. Measured: texton 6.0 %, tiling 1.7 % (fast), below 1e-6 where exact. An
#   unfiltered render's variance there is 13 to 35 times the filtered one, so a viewer that did
#   not filter (shimmering when zoomed out) fails.
VARIANCE_BOUND = 0.08 + 3 * 0.021
# - a srgb model's values (linear light): the decoding's largest slope over its table's means
#   -1 to 2, 2.4 / 1.055 ((2 + 0.055) / 1.055)^1.4, times the bound of its data model;
DECODING_SLOPE = 5.8
# - what the canvas shows against the values read back: the sRGB encoding of a srgb model's
#   linear light, a data model's values as they are, up to float rounding of the shader's pow.
DISPLAY_BOUND = 1e-5


def pixel_bound(method, shader_variant, scale, cpu):
    """The bound on |web - CPU| per value for the CPU render `cpu` (parse_pfm's tuple), or None
    where only the variance is compared. A srgb model (`<method>_srgb`) returns linear light: the
    decoding multiplies a difference by at most DECODING_SLOPE."""
    if method.endswith("_srgb"):
        bound = pixel_bound(method.removesuffix("_srgb"), shader_variant, scale, cpu)
        return None if bound is None else DECODING_SLOPE * bound
    if method == "gabor":
        return GABOR_DEVIATIONS * math.sqrt(min(variances(cpu[3], cpu[2])))
    if shader_variant == "exact" or method not in ("texton", "tiling"):
        return EXACT_BOUND
    return FAST_BOUND if scale == 1 else None


def registry_methods(stochtex):
    """The names of the registry's methods (`stochtex methods --json`), in its order: the tests
    check every method the binary has, a new one included."""
    listed = subprocess.run([stochtex, "methods", "--json"], check=True, capture_output=True,
                            text=True).stdout
    return [method["name"] for method in json.loads(listed)]


def compare(what, web, cpu, bound, scale):
    """The failures of the viewer's values `web` (read_back's tuple) against the CPU render `cpu`
    (parse_pfm's): the size and channels, the largest |web - cpu| against `bound` (None: not
    compared) and, zoomed out (scale > 1), the variance within VARIANCE_BOUND of the CPU's."""
    if web[:3] != cpu[:3]:
        return [f"{what}: web {web[:3]} != cpu {cpu[:3]}"]
    largest = max(abs(a - b) for a, b in zip(web[3], cpu[3]))
    ratio = max(abs(w / c - 1) for w, c in zip(variances(web[3], web[2]),
                                               variances(cpu[3], cpu[2])))
    print(f"{what:32} scale {scale:4g}: max |web - cpu| {largest:.3g} "
          f"(bound {bound if bound is None else f'{bound:.3g}'}), "
          f"|variance / cpu's - 1| {ratio:.3g}")
    failures = []
    if bound is not None and not largest <= bound:
        failures.append(f"{what} scale {scale:g}: max |web - cpu| {largest:.3g} exceeds "
                        f"{bound:.3g}")
    if scale > 1 and not ratio <= VARIANCE_BOUND:
        failures.append(f"{what} scale {scale:g}: variance off the CPU's by {ratio:.3g}, beyond "
                        f"{VARIANCE_BOUND:.3g}")
    return failures


def parse_pfm(data):
    """A PFM file's pixels, top row first: (width, height, channels, floats)."""
    fields = []
    position = 0
    while len(fields) < 4:
        while data[position:position + 1].isspace():
            position += 1
        start = position
        while not data[position:position + 1].isspace():
            position += 1
        fields.append(data[start:position].decode())
    position += 1
    channels = 3 if fields[0] == "PF" else 1
    width, height = int(fields[1]), int(fields[2])
    order = "<" if float(fields[3]) < 0 else ">"
    values = struct.unpack(f"{order}{width * height * channels}f", data[position:])
    row = width * channels
    rows = [values[(height - 1 - j) * row:(height - j) * row] for j in range(height)]
    return width, height, channels, [v for r in rows for v in r]


def cpu_render(stochtex, model, origin, scale, seed, folder, size=SIZE):
    path = os.path.join(folder, f"{os.path.basename(model)}_{scale:g}_{seed}.pfm")
    subprocess.run([stochtex, "render", model, "-o", path, "--size", f"{size}x{size}",
                    "--origin", f"{origin[0]:g},{origin[1]:g}", "--scale", f"{scale:g}",
                    "--seed", str(seed)], check=True, capture_output=True)
    with open(path, "rb") as file:
        return parse_pfm(file.read())


def variances(values, channels):
    result = []
    for c in range(channels):
        column = values[c::channels]
        mean = sum(column) / len(column)
        result.append(sum((v - mean) ** 2 for v in column) / len(column))
    return result


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def serve(folder):
    handler = functools.partial(QuietHandler, directory=folder)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    options = Options()
    options.binary_location = shutil.which("chromium")
    for argument in ["--headless=new", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                     "--no-sandbox", "--window-size=1400,700", "--hide-scrollbars"]:
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(options=options, service=Service(shutil.which("chromedriver")))
    driver.set_script_timeout(300)
    return driver


READ_BACK = """
const [name, display, done] = arguments;
try {
  const r = (window.stochtexPage || window.stochtexStudio.group).viewers.get(name)
      .readPixels({display});
  const bytes = new Uint8Array(r.data.buffer);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  done([r.width, r.height, r.channels, btoa(text)]);
} catch (error) { done(['error', String(error)]); }
"""


def read_back(driver, name, display=False):
    """The viewer's values of model `name` (display: what its canvas shows), as floats."""
    result = driver.execute_async_script(READ_BACK, name, display)
    if result[0] == "error":
        raise RuntimeError(f"{name}: readPixels failed: {result[1]}")
    width, height, channels, text = result
    raw = base64.b64decode(text)
    return width, height, channels, list(struct.unpack(f"<{len(raw) // 4}f", raw))


def run_page(driver, script, *arguments):
    result = driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        f"(async () => {{ {script} }})().then(() => done(null), (e) => done(String(e)));",
        *arguments)
    if result is not None:
        raise RuntimeError(result)


def read_manifest(site, name, variant):
    with open(os.path.join(site, "models", name, variant, "manifest.json")) as file:
        return json.load(file)


def same_files(site, name, first, second):
    """Whether the model's `first` and `second` exports are one shader and data: the same files,
    byte for byte, and manifests that differ only in VARIANT_LABELS. The viewer draws both the
    same (it reads those labels only for its messages), so the values of one stand for both
    (lrp's, gabor's and texton_mix's fast exports are their exact ones)."""
    folders = [os.path.join(site, "models", name, variant) for variant in (first, second)]
    names = sorted(os.listdir(folders[0]))
    if names != sorted(os.listdir(folders[1])):
        return False
    for file_name in names:
        if file_name == "manifest.json":
            kept = [{key: value for key, value in read_manifest(site, name, variant).items()
                     if key not in VARIANT_LABELS} for variant in (first, second)]
            if kept[0] != kept[1]:
                return False
            continue
        contents = []
        for folder in folders:
            with open(os.path.join(folder, file_name), "rb") as file:
                contents.append(file.read())
        if contents[0] != contents[1]:
            return False
    return True


def check_loaded(driver, site, variant):
    """Every viewer holds its model's `variant` manifest (as export-web wrote it): the page shows
    the variant that its values are compared as."""
    loaded = driver.execute_script(
        "return Object.fromEntries([...window.stochtexPage.viewers].map("
        "([name, viewer]) => [name, viewer.manifest]));")
    return [f"{name} {variant}: the viewer holds the manifest of the "
            f"{(manifest or {}).get('variant')} export, not of {variant}'s"
            for name, manifest in loaded.items() if manifest != read_manifest(site, name, variant)]


# The wheel zooms about the cursor, a drag pans, and every viewer of the page follows. Both start
# from the view the comparisons left: a view set here would redraw every viewer once more.
WHEEL = """
const page = window.stochtexPage;
const [first, second] = [...page.viewers.values()];
const before = first.getView();
const canvas = document.querySelector('canvas');
const box = canvas.getBoundingClientRect();
const event = new WheelEvent('wheel', {clientX: Math.round(box.left) + 40,
                                       clientY: Math.round(box.top) + 90, deltaY: 500,
                                       bubbles: true, cancelable: true});
// The cursor in canvas pixels, as the event carries it.
const px = (event.clientX - box.left) * canvas.width / box.width;
const py = (event.clientY - box.top) * canvas.height / box.height;
canvas.dispatchEvent(event);
const view = first.getView();
const other = second.getView();
return [before.x + before.scale * px, before.y + before.scale * py,
        view.x + view.scale * px, view.y + view.scale * py, before.scale,
        [view.x, view.y, view.scale], [other.x, other.y, other.scale]];
"""


def srgb_encode(value):
    value = min(max(value, 0.0), 1.0)
    return value * 12.92 if value <= 0.0031308 else 1.055 * value ** (1 / 2.4) - 0.055


def check_display(driver, names):
    """The canvas of each model of `names` against its values read back: encoded for a srgb
    model (`<method>_srgb`), as they are otherwise (colour channels; 1 or 2 channels show the
    first as grey)."""
    failures = []
    for name in names:
        width, height, channels, raw = read_back(driver, name)
        shown = read_back(driver, name, display=True)[3]
        encode = srgb_encode if name.endswith("_srgb") else (lambda v: v)
        compared = 3 if channels >= 3 else 1
        largest = max(abs(shown[i * channels + c] - encode(raw[i * channels + c]))
                      for i in range(width * height) for c in range(compared))
        print(f"{name} display: max |shown - expected| {largest:.3g} (bound {DISPLAY_BOUND:g})")
        if not largest <= DISPLAY_BOUND:
            failures.append(f"{name}: the canvas shows values {largest:.3g} off "
                            f"{'the sRGB encoding of ' if encode is srgb_encode else ''}its values")
    return failures


def check_interaction(driver):
    x, y, new_x, new_y, old_scale, view, other = driver.execute_script(WHEEL)
    failures = []
    if abs(view[2] - old_scale * math.exp(1.0)) > 1e-9 * old_scale:
        failures.append(f"wheel: scale {view[2]} after a 500-pixel wheel step from {old_scale}, "
                        f"not e times that")
    if abs(new_x - x) > 1e-6 or abs(new_y - y) > 1e-6:
        failures.append(f"wheel: the point under the cursor moved from ({x}, {y}) to "
                        f"({new_x}, {new_y})")
    if other != view:
        failures.append(f"wheel: the other viewers are at {other}, not {view}")
    # A real drag (WebDriver's pointer actions) of (30, 20) pixels pans every viewer by
    # -scale x that.
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    canvas = driver.find_element(By.CSS_SELECTOR, "canvas")
    ActionChains(driver).move_to_element(canvas).click_and_hold().move_by_offset(30, 20) \
        .release().perform()
    views = driver.execute_script(
        "return [...window.stochtexPage.viewers.values()].map((v) => v.getView());")
    expected = {"x": view[0] - view[2] * 30, "y": view[1] - view[2] * 20, "scale": view[2]}
    if any(abs(v[k] - expected[k]) > 1e-9 * max(1, abs(expected[k])) for v in views
           for k in expected):
        failures.append(f"drag: the viewers are at {views}, not {expected}")
    return failures


# A shader that does not compile: load() rejects with the driver's log.
BROKEN = """
const done = arguments[arguments.length - 1];
import('./viewer/viewer.js').then(async ({createViewer}) => {
  const viewer = createViewer(document.createElement('canvas'));
  try {
    await viewer.load('broken');
    done('loaded');
  } catch (error) {
    done(error instanceof Error ? error.message : 'not an Error: ' + String(error));
  }
});
"""


def check_compile_error(driver, site):
    broken = os.path.join(site, "broken")
    shutil.copytree(os.path.join(site, "models", "lrp", "exact"), broken)
    with open(os.path.join(broken, "shader.essl"), "a") as file:
        file.write("\nvec4 broken() { return undefined_name; }\n")
    message = driver.execute_async_script(BROKEN)
    if "does not compile" not in message or "undefined_name" not in message:
        return [f"a broken shader gave '{message}', not the compile error with its log"]
    print(f"broken shader: {message.splitlines()[0][:100]}")
    return []


def take_screenshots(driver, url, folder):
    """The page at 256-pixel canvases: the exact shaders at scale 1 and zoomed out 16x."""
    os.makedirs(folder, exist_ok=True)
    driver.set_window_size(1480, 720)
    driver.get(url.replace(f"size={SIZE}", "size=256"))
    run_page(driver, "await window.stochtexPage.ready;")
    for name, view in [("export_web.png", {"x": 0, "y": 0, "scale": 1}),
                       ("export_web_zoomed_out.png", {"x": 0, "y": 0, "scale": 16})]:
        run_page(driver, "window.stochtexPage.setSeed(7);"
                 "window.stochtexPage.setView(arguments[0]);"
                 "await new Promise((resolve) => requestAnimationFrame(resolve));"
                 # Each canvas's drawing finished (a one-pixel read waits for it): SwiftShader
                 # takes seconds for the exact gabor and lrp, longer than the screenshot waits.
                 "for (const canvas of document.querySelectorAll('canvas')) {"
                 "  const gl = canvas.getContext('webgl2');"
                 "  if (gl) gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE,"
                 "                        new Uint8Array(4));"
                 "}", view)
        driver.save_screenshot(os.path.join(folder, name))
        print(f"wrote {os.path.join(folder, name)}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("stochtex")
    parser.add_argument("exemplar")
    parser.add_argument("--second", help="texton_mix's second exemplar")
    parser.add_argument("--screenshots", help="folder for the page's screenshots")
    parser.add_argument("--measure", action="store_true", help="print every measured number")
    args = parser.parse_args()
    if not shutil.which("chromium"):
        print("SKIP: chromium is not installed (scripts/install-deps.sh installs it)")
        return SKIP
    if not shutil.which("chromedriver"):
        print("FAIL: chromium is installed without chromedriver; run scripts/install-deps.sh")
        return 1
    try:
        import selenium  # noqa: F401 (only checked here, imported where used)
    except ImportError:
        print("FAIL: chromium is installed without python3-selenium; run scripts/install-deps.sh")
        return 1

    start = time.time()
    failures = []
    with tempfile.TemporaryDirectory(prefix="stochtex_browser_") as work:
        models = {}
        for method in registry_methods(args.stochtex) + ["texton_mix"]:
            path = os.path.join(work, f"{method}.stx")
            # Models of data (the exemplar's values), each viewer's against the CPU's; the srgb
            # model below checks the viewer's colour.
            if method == "texton_mix":
                command = [args.stochtex, "mix", args.exemplar, args.second or args.exemplar,
                           "-o", path, "--steps", "3", "--ramp", "0,128", "-p", "support=64",
                           "--colour-space", "data"]
            else:
                command = [args.stochtex, "analyze", args.exemplar, "-m", method, "-o", path,
                           "--colour-space", "data"]
            subprocess.run(command, check=True, capture_output=True)
            models[method] = path
        # A srgb model (docs/design.md §14): its shader returns linear light, which the viewer
        # encodes for the canvas.
        path = os.path.join(work, "texton_srgb.stx")
        subprocess.run([args.stochtex, "analyze", args.exemplar, "-m", "texton", "--colour-space",
                        "srgb", "-o", path], check=True, capture_output=True)
        models["texton_srgb"] = path
        site = os.path.join(work, "site")
        subprocess.run([args.stochtex, "export-web", *models.values(), "-o", site], check=True,
                       capture_output=True)
        server = serve(site)
        driver = browser()
        try:
            url = f"http://127.0.0.1:{server.server_address[1]}/index.html?size={SIZE}"
            driver.get(url)
            # Every setView and setSeed redraws every loaded viewer, and on SwiftShader a draw
            # takes up to seconds (gabor's): the seed and the first view are set while the page
            # loads its models, so that its first draw is at them, and each variant's views are
            # compared starting at the one the page is at.
            view = VIEWS[0]
            run_page(driver, "window.stochtexPage.setSeed(arguments[0]);"
                     "window.stochtexPage.setView(arguments[1]);"
                     "await window.stochtexPage.ready;",
                     SEED, {"x": view[0][0], "y": view[0][1], "scale": view[1]})
            print(f"page loaded in {time.time() - start:.1f} s")
            # The CPU's renders, by model and view: every variant is compared with the same one.
            cpu_renders = {}
            for variant in ["exact", "fast"]:
                if variant != "exact":  # the page starts with the exact shaders
                    run_page(driver, f"await window.stochtexPage.setVariant('{variant}');")
                failures += check_loaded(driver, site, variant)
                compared = {method: path for method, path in models.items()
                            if variant == "exact" or not same_files(site, method, "exact", variant)}
                for method in models:
                    if method not in compared:
                        print(f"{method} {variant}: the exact export's shader and data, compared")
                for origin, scale in sorted(VIEWS, key=lambda other: other != view):
                    if (origin, scale) != view:
                        view = (origin, scale)
                        run_page(driver, "window.stochtexPage.setView(arguments[0]);",
                                 {"x": origin[0], "y": origin[1], "scale": scale})
                    for method, path in compared.items():
                        manifest = read_manifest(site, method, variant)
                        what = f"{method} {variant} ({manifest['shader_variant']} shader)"
                        if (path, view) not in cpu_renders:
                            cpu_renders[path, view] = cpu_render(args.stochtex, path, origin,
                                                                 scale, SEED, work)
                        cpu = cpu_renders[path, view]
                        bound = pixel_bound(method, manifest["shader_variant"], scale, cpu)
                        failures += compare(what, read_back(driver, method), cpu, bound, scale)
            failures += check_display(driver, ["texton_srgb", "texton"])
            failures += check_interaction(driver)
            failures += check_compile_error(driver, site)
            if args.screenshots:
                take_screenshots(driver, url, args.screenshots)
            log = driver.get_log("browser")
            for entry in log:
                if entry["level"] == "SEVERE":
                    failures.append(f"console: {entry['message']}")
                elif args.measure:
                    print(f"console {entry['level']}: {entry['message']}")
        finally:
            driver.quit()
            server.shutdown()
    print(f"took {time.time() - start:.1f} s")
    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
