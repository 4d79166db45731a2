#!/usr/bin/python3
"""The web viewer in a real browser (docs/studio.md, "Browser parity").

Analyses a small shipped exemplar with every method (and a texton mixing model), writes them with
`stochtex export-web`, serves the folder over HTTP and loads the page in headless Chromium
(SwiftShader's WebGL2). For each model and variant it reads the viewer's float values back
(viewer.readPixels through the page's window.stochtexPage) and compares them with `stochtex
render` of the same model, view and seed: pixel for pixel where the shader is the CPU's to float
rounding, in variance when zoomed out 16x (the filtered render's), and it fails on any JavaScript
console error.

Usage: browser_test.py STOCHTEX EXEMPLAR [--screenshots DIR] [--measure]
Exit 77 (CTest's SKIP_RETURN_CODE) when chromium is not installed.
"""

import argparse
import base64
import functools
import http.server
import json
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
MODELS = ["texton", "tiling", "lrp", "gabor", "texton_mix"]

# Largest |web - CPU| per value where the web shader is the CPU's evaluator (every exact variant
# but gabor's, and lrp's and texton_mix's fast ones, which are their exact ones): measured on
# SwiftShader (docs/studio.md), the renderers' parity bound 1e-4 (docs/shaders.md).
EXACT_BOUND = 1e-4


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


def cpu_render(stochtex, model, origin, scale, seed, folder):
    path = os.path.join(folder, f"{os.path.basename(model)}_{scale:g}_{seed}.pfm")
    subprocess.run([stochtex, "render", model, "-o", path, "--size", f"{SIZE}x{SIZE}",
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
const [name, done] = arguments;
try {
  const r = window.stochtexPage.viewers.get(name).readPixels();
  const bytes = new Uint8Array(r.data.buffer);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  done([r.width, r.height, r.channels, btoa(text)]);
} catch (error) { done(['error', String(error)]); }
"""


def read_back(driver, name):
    result = driver.execute_async_script(READ_BACK, name)
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

    start = time.time()
    failures = []
    with tempfile.TemporaryDirectory(prefix="stochtex_browser_") as work:
        models = {}
        for method in MODELS:
            path = os.path.join(work, f"{method}.stx")
            if method == "texton_mix":
                command = [args.stochtex, "mix", args.exemplar, args.second or args.exemplar,
                           "-o", path, "--steps", "3", "--ramp", "0,128", "-p", "support=64"]
            else:
                command = [args.stochtex, "analyze", args.exemplar, "-m", method, "-o", path]
            subprocess.run(command, check=True, capture_output=True)
            models[method] = path
        site = os.path.join(work, "site")
        subprocess.run([args.stochtex, "export-web", *models.values(), "-o", site], check=True,
                       capture_output=True)
        server = serve(site)
        driver = browser()
        try:
            url = f"http://127.0.0.1:{server.server_address[1]}/index.html?size={SIZE}"
            driver.get(url)
            run_page(driver, "await window.stochtexPage.ready;")
            print(f"page loaded in {time.time() - start:.1f} s")
            for variant in ["exact", "fast"]:
                run_page(driver, f"await window.stochtexPage.setVariant('{variant}');")
                for origin, scale in VIEWS:
                    run_page(driver, "window.stochtexPage.setSeed(arguments[0]);"
                             "window.stochtexPage.setView(arguments[1]);",
                             SEED, {"x": origin[0], "y": origin[1], "scale": scale})
                    for method, path in models.items():
                        manifest_path = os.path.join(site, "models", method, variant,
                                                     "manifest.json")
                        with open(manifest_path) as file:
                            manifest = json.load(file)
                        web = read_back(driver, method)
                        cpu = cpu_render(args.stochtex, path, origin, scale, SEED, work)
                        if web[:3] != cpu[:3]:
                            failures.append(f"{method} {variant}: web {web[:3]} != cpu {cpu[:3]}")
                            continue
                        largest = max(abs(a - b) for a, b in zip(web[3], cpu[3]))
                        web_var = variances(web[3], web[2])
                        cpu_var = variances(cpu[3], cpu[2])
                        ratio = max(abs(w / c - 1) for w, c in zip(web_var, cpu_var))
                        print(f"{method:10} {variant:5} ({manifest['shader_variant']:5}) "
                              f"scale {scale:4g}: max |web - cpu| {largest:.3g}, "
                              f"variance ratio - 1 {ratio:.3g}")
            if args.screenshots:
                os.makedirs(args.screenshots, exist_ok=True)
                driver.save_screenshot(os.path.join(args.screenshots, "export_web.png"))
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
