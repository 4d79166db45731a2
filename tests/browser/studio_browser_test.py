#!/usr/bin/python3
"""The studio in a real browser (docs/studio.md, "What the tests check").

Starts `stochtex studio --port 0`, opens its page in headless Chromium (SwiftShader's WebGL2),
uploads a shipped exemplar through the page's file input, then drops it on the drop zone (a drop
event carrying the file, as the browser makes for a file dragged from the desktop), and runs an
analysis with every method of the registry (`stochtex methods --json`) through its form. Each
method's model then shows in its own WebGL2 viewer; the test reads every viewer's float values
back at one view, zoomed out 16x, and compares them with `stochtex render` of the model the studio
serves (downloaded as .stx) at the same view and seed: value for value within the exported
shader's tolerance, and in variance. That the viewer draws every model as the CPU does at every
view and variant is browser_test.py's (export-web's page, the same viewer); this test checks that
the studio shows the model it serves, at the view and seed its controls set. It then moves every
slider of the gabor editor and checks the edited model against `stochtex edit` with the same
values, byte for byte, and its viewer against the CLI's render. The shader download's language
picker lists /api/languages and its link follows it. It fails on any JavaScript console error.

Usage: studio_browser_test.py STOCHTEX EXEMPLAR [--screenshots DIR]
Exit 77 (CTest's SKIP_RETURN_CODE) when chromium is not installed.
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
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as common  # noqa: E402 (the browser and comparison helpers)

# The viewers' side: browser_test's 128 (the page's `?size=`; a draw on SwiftShader costs about its
# pixel count), and the page's own 256 when the screenshot is taken.
SIZE = common.SIZE
SCREENSHOT_SIZE = 256
SEED = 7
# The compared view, browser_test's zoomed out 16x: the filtered draw (an unfiltered one fails the
# variance), and on SwiftShader gabor's cheaper view (every draw of 256^2 takes seconds).
ORIGIN, SCALE = common.VIEWS[-1]


def start_studio(stochtex):
    server = subprocess.Popen([stochtex, "studio", "--port", "0"], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    line = server.stdout.readline()
    prefix = "stochtex studio: serving "
    if not line.startswith(prefix):
        server.kill()
        raise RuntimeError(f"the studio did not start: {line!r} {server.stderr.read()}")
    return server, line[len(prefix):].strip().rstrip("/")


# Waits for the upload of the file `name` (the end of the scripts below): its name and size in the
# exemplar's line, and both pictures (the exemplar and its Gaussian version) loaded.
WAIT_UPLOAD = """
const started = performance.now();
(function wait() {
  const studio = window.stochtexStudio;
  if (studio.errors.length) return done('error: ' + studio.errors.join('; '));
  const info = document.getElementById('exemplar-info').textContent;
  const images = ['exemplar-image', 'gaussian-image'].map((id) => document.getElementById(id));
  if (info.startsWith(name + ':') && images.every((image) => image.complete && image.naturalWidth))
    return done(info);
  if (performance.now() - started > 60000) return done('error: the upload did not finish in 60 s');
  setTimeout(wait, 100);
})();
"""

# The upload of the file given to the page's file input.
UPLOADED = "const [name, done] = arguments;" + WAIT_UPLOAD

# Drops a file on the exemplar drop zone as the browser does for one dragged from the desktop: a
# dragover (the zone shows it), then a drop whose DataTransfer holds the file. Waits for the upload.
DROP = """
const [data, name, done] = arguments;
const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
const transfer = new DataTransfer();
transfer.items.add(new File([bytes], name, { type: 'image/png' }));
const zone = document.getElementById('drop-zone');
const drag = (type) => zone.dispatchEvent(
  new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }));
drag('dragover');
if (!zone.classList.contains('over')) return done('error: the zone does not show a dragover');
drag('drop');
if (zone.classList.contains('over')) return done('error: the zone still shows the drag');
""" + WAIT_UPLOAD


# Picks the method in the form (the picker lists /api/methods), runs its analysis and waits for its
# model in its viewer.
ANALYSE = """
const [method, done] = arguments;
const select = document.getElementById('method');
select.value = method;
if (select.value !== method) return done('error: the method picker does not list ' + method);
select.dispatchEvent(new Event('change'));
document.getElementById('analyse').click();
const studio = window.stochtexStudio;
const started = performance.now();
(function wait() {
  if (studio.errors.length) return done('error: ' + studio.errors.join('; '));
  if (studio.shown.has(method) && studio.group.viewers.get(method).manifest)
    return studio.loaded.then(() => done(studio.shown.get(method).model), (e) => done('error: ' + e));
  if (performance.now() - started > 240000) return done('error: the analysis took over 240 s');
  setTimeout(wait, 200);
})();
"""


# Every slider of the gabor editor: its position, and the `stochtex edit` option it stands for.
SLIDERS = [("rotate", "30", ["--rotate", "30"]),
           ("scale", "0.5", ["--scale", repr(2 ** 0.5)]),
           ("translate-x", "0.01", []),
           ("translate-y", "-0.02", ["--translate", "0.01,-0.02"]),
           ("magnitude", "1.5", ["--magnitude", "1.5"]),
           ("bandwidth", "1", ["--bandwidth", "2"])]

# Moves the given sliders of the gabor editor as a person would and waits for the edited model in
# the gabor viewer.
EDIT = """
const [sliders, done] = arguments;
const studio = window.stochtexStudio;
for (const [name, value] of sliders) {
  const slider = document.getElementById('edit-' + name);
  slider.value = value;
  slider.dispatchEvent(new Event('input'));
}
const started = performance.now();
(function wait() {
  if (studio.errors.length) return done('error: ' + studio.errors.join('; '));
  if (studio.editor.edited && !studio.editor.busy)
    return studio.loaded.then(() => done(studio.editor.edited), (e) => done('error: ' + e));
  if (performance.now() - started > 60000) return done('error: the edit took over 60 s');
  setTimeout(wait, 100);
})();
"""


def check_editor(driver, stochtex, url, original, original_cpu, work, size, failures):
    """Every slider moved: the edited model is `stochtex edit` of the original with the sliders'
    values, byte for byte; the gabor viewer shows it (equal to `stochtex render` of its .stx) and
    differs from the original's render `original_cpu` beyond that bound (the edit shows)."""
    # At the compared view, which the checks before left: the edit redraws only the gabor viewer.
    edited = driver.execute_async_script(EDIT, [[name, value] for name, value, _ in SLIDERS])
    if edited.startswith("error"):
        raise RuntimeError(f"gabor editor: {edited}")
    path = os.path.join(work, "gabor-edited.stx")
    urllib.request.urlretrieve(f"{url}/api/models/{edited}.stx", path)
    cli = os.path.join(work, "gabor-edited-cli.stx")
    subprocess.run([stochtex, "edit", original, "-o", cli] +
                   [word for _, _, option in SLIDERS for word in option], check=True)
    with open(path, "rb") as studio_file, open(cli, "rb") as cli_file:
        if studio_file.read() != cli_file.read():
            failures.append("gabor editor: the model the sliders made is not `stochtex edit "
                            "--rotate 30 --scale 1.414 --translate 0.01,-0.02 --magnitude 1.5 "
                            "--bandwidth 2` of the original")
    web = common.read_back(driver, "gabor")
    edited_cpu = common.cpu_render(stochtex, path, ORIGIN, SCALE, SEED, work, size)
    for name, cpu, close in [("edited", edited_cpu, True), ("original", original_cpu, False)]:
        bound = common.pixel_bound("gabor", "exact", SCALE, cpu)
        largest = max(abs(a - b) for a, b in zip(web[3], cpu[3]))
        print(f"gabor edited in the viewer against the {name} model's render: max |web - cpu| "
              f"{largest:.3g} (bound {bound:.3g})")
        if web[:3] != cpu[:3] or (largest <= bound) != close:
            failures.append(f"gabor editor: max |web - cpu of the {name} model| {largest:.3g} "
                            f"{'exceeds' if close else 'within'} {bound:.3g}")


def check_shader_link(driver, url, failures):
    """The shader export's language picker lists /api/languages, its default picked, and the
    download link follows the picked language."""
    with urllib.request.urlopen(f"{url}/api/languages") as answer:
        languages = json.load(answer)
    listed = driver.execute_script(
        "return [...document.getElementById('shader-language').options].map((o) => o.value);")
    if listed != [language["name"] for language in languages]:
        failures.append(f"shader export: the language picker lists {listed}, not /api/languages")
    default = next(language["name"] for language in languages if language["default"])
    for picked in [None, languages[-1]["name"]]:
        if picked:
            driver.execute_script("const select = document.getElementById('shader-language');"
                                  "select.value = arguments[0];"
                                  "select.dispatchEvent(new Event('change'));", picked)
        link = driver.execute_script("return document.getElementById('download-shader').href;")
        if not link.endswith(f"-exact-{picked or default}.zip"):
            failures.append(f"shader export: the link {link} is not the {picked or default} one")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("stochtex")
    parser.add_argument("exemplar")
    parser.add_argument("--screenshots", help="folder for the page's screenshot")
    args = parser.parse_args()
    if not shutil.which("chromium"):
        print("SKIP: chromium is not installed (scripts/install-deps.sh installs it)")
        return common.SKIP
    if not shutil.which("chromedriver"):
        print("FAIL: chromium is installed without chromedriver; run scripts/install-deps.sh")
        return 1

    from selenium.webdriver.common.by import By
    size = SCREENSHOT_SIZE if args.screenshots else SIZE
    start = time.time()
    failures = []
    server, url = start_studio(args.stochtex)
    driver = common.browser()
    try:
        with tempfile.TemporaryDirectory(prefix="stochtex_studio_browser_") as work:
            driver.set_window_size(1400, 1400)
            driver.get(f"{url}/?size={size}")
            # The file input is hidden in its drop zone: shown so that WebDriver may type in it.
            upload = driver.find_element(By.ID, "exemplar-file")
            driver.execute_script("arguments[0].style.display = 'block';", upload)
            upload.send_keys(os.path.abspath(args.exemplar))
            uploaded = driver.execute_async_script(UPLOADED, os.path.basename(args.exemplar))
            if uploaded.startswith("error"):
                raise RuntimeError(f"file input: {uploaded}")
            print(f"uploaded: {uploaded}")
            # The same exemplar dropped on the zone under another name: the models below are
            # analysed from the dropped upload.
            with open(args.exemplar, "rb") as file:
                data = base64.b64encode(file.read()).decode()
            dropped = driver.execute_async_script(DROP, data, "dropped.png")
            if dropped.startswith("error"):
                raise RuntimeError(f"drop: {dropped}")
            print(f"dropped: {dropped}")
            models = {}
            for method in common.registry_methods(args.stochtex):
                result = driver.execute_async_script(ANALYSE, method)
                if result.startswith("error"):
                    raise RuntimeError(f"{method}: {result}")
                path = os.path.join(work, f"{method}.stx")
                urllib.request.urlretrieve(f"{url}/api/models/{result}.stx", path)
                models[method] = path
                print(f"{method}: analysed and shown after {time.time() - start:.1f} s")
                if len(models) == 1:
                    # The seed and the view through the studio's controls once the first model
                    # shows: they reach its viewer, and each later viewer starts at them. Set
                    # after the last, they would redraw every viewer twice (seconds a draw here).
                    common.run_page(driver, "window.stochtexStudio.setSeed(arguments[0]);"
                                    "window.stochtexStudio.group.setView(arguments[1]);",
                                    SEED, {"x": ORIGIN[0], "y": ORIGIN[1], "scale": SCALE})
            check_shader_link(driver, url, failures)
            cpu_renders = {}
            for method, path in models.items():
                cpu_renders[method] = common.cpu_render(args.stochtex, path, ORIGIN, SCALE, SEED,
                                                        work, size)
                bound = common.pixel_bound(method, "exact", SCALE, cpu_renders[method])
                failures += common.compare(method, common.read_back(driver, method),
                                           cpu_renders[method], bound, SCALE)
            edit_start = time.time()
            check_editor(driver, args.stochtex, url, models["gabor"], cpu_renders["gabor"],
                         work, size, failures)
            print(f"gabor editor checked in {time.time() - edit_start:.1f} s")
            if args.screenshots:
                os.makedirs(args.screenshots, exist_ok=True)
                common.run_page(driver, "window.stochtexStudio.group.setView({x: 0, y: 0, scale: 1});"
                                "await window.stochtexStudio.loaded;"
                                "await new Promise((resolve) => requestAnimationFrame(resolve));")
                path = os.path.join(args.screenshots, "studio.png")
                driver.set_window_size(1300, 2400)
                section = driver.find_element(By.ID, "result-section")
                driver.execute_script("arguments[0].scrollIntoView();", section)
                section.screenshot(path)
                print(f"wrote {path}")
            for entry in driver.get_log("browser"):
                if entry["level"] == "SEVERE":
                    failures.append(f"console: {entry['message']}")
    finally:
        driver.quit()
        server.terminate()
        server.wait(timeout=30)
    print(f"took {time.time() - start:.1f} s")
    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
