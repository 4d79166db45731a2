#!/usr/bin/python3
"""`stochtex export-shader --language godot` in Godot 3 itself (docs/engines.md, "Godot").

Analyses a small shipped exemplar with each method (texton, tiling and lrp exact; texton,
tiling and gabor fast; a data model; a texton mix of it with a second exemplar, `stochtex mix`,
whose fast variant is its exact one), exports the shaders for Godot and puts the exports into a
Godot project, as a user copies them into theirs: Godot's editor imports the data files with the
exported `.import` settings, then the project runs headless under Xvfb (Mesa llvmpipe) and
renders, in viewports of known size,

- each export's own scene (its ColorRect and canvas_item shader) as `stochtex render` draws it,
  8-bit sRGB-encoded colour: compared with the CPU render's PNG values, which checks the colour
  space end to end;
- the same function writing each value's float32 bytes (a canvas shader made from the exported
  one, its fragment() replaced): compared with the CPU render's floats;
- the spatial shader on a quad in a 3-D viewport, which must compile.

Godot's output must hold no shader error. The numbers measured are printed (`--measure` prints
them for every view, docs/engines.md gives them).

Usage: godot_test.py STOCHTEX EXEMPLAR SECOND_EXEMPLAR [--keep DIR] [--measure]
Exit 77 (CTest's SKIP_RETURN_CODE) when godot3 or xvfb-run is not installed.
"""

import argparse
import json
import math
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time

SKIP = 77
SIZE = 32  # render side: llvmpipe on two shared cores (the bits viewport is 4 x 32 wide)
SEED = 7

# Each case: an analysis of the exemplar, an export variant, and the views compared: (origin,
# scale). Scale 1 is a point sample; scale 4 filters each pixel's footprint.
CASES = [
    {"name": "tiling_exact", "method": "tiling", "params": [], "variant": "exact"},
    {"name": "tiling_fast", "method": "tiling", "params": [], "variant": "fast"},
    {"name": "tiling_data", "method": "tiling", "params": [], "variant": "exact",
     "colour_space": "data"},
    {"name": "texton_exact", "method": "texton", "params": ["support=16", "iterations=10"],
     "variant": "exact"},
    {"name": "texton_fast", "method": "texton", "params": ["support=16", "iterations=10"],
     "variant": "fast"},
    {"name": "lrp_exact", "method": "lrp", "params": ["cosines=8"], "variant": "exact"},
    {"name": "gabor_fast", "method": "gabor", "params": ["impulses=64", "iterations=20"],
     "variant": "fast"},
    # `stochtex mix EXEMPLAR SECOND_EXEMPLAR`: the ramp puts both views between the two (rho 0.04
    # to 0.16 in the far view, 0.96 to 0.99 in the near one), 5 textons.
    {"name": "texton_mix", "method": "texton_mix", "params": ["support=16", "iterations=10"],
     "mix": ["--steps", "5", "--ramp", "-1040,0"], "variant": "exact"},
]
# Off the origin at scale 1; far off it, zoomed out 4x.
VIEWS = [((-40.0, 24.0), 1.0), ((-1000.0, 512.0), 4.0)]

# The bounds, and what was measured with Debian 12's Godot 3.2.3 on Mesa 22.3 llvmpipe (docs/
# engines.md, "Godot", has the numbers):
# - where the shader is the CPU's evaluator (the exact variants, lrp's fast one), largest
#   |Godot - CPU| per value: the renderers' parity bound (docs/shaders.md), 1e-4, which leaves room
#   for GPU drivers that fuse multiply-adds; measured at most 2.0e-6 (lrp at scale 4);
EXACT_BOUND = 1e-4
# - gabor's float-only shader: 1e-3 of the image's smallest channel deviation (docs/shaders.md),
#   here 1.8e-5 at scale 1 and 8.3e-6 at 4; measured 1.1e-6 and 2.7e-6;
GABOR_DEVIATIONS = 1e-3
# - texton's and tiling's fast variants at scale 1: the fast path's bound of the other languages
#   (docs/shaders.md), 1/255; Godot reads their data as half floats: measured 2.2e-4 (texton) and
#   6.9e-4 (tiling);
FAST_BOUND = 1.0 / 255.0
# - zoomed out (scale 4), where the fast variants equal the CPU in distribution only: each
#   channel's mean within 1/255 (measured 4e-4) and its deviation within 10 % (measured 2.5 %;
#   docs/shaders.md gives 2 to 8 % more variance from hardware trilinear filtering);
FAST_MEAN_BOUND = 1.0 / 255.0
FAST_DEVIATION_BOUND = 0.10
# - the scene's 8-bit colour against the bytes of the PNG `stochtex render` writes: at most one
#   step (rounding of values that sit on a step's edge): measured 0 for the exact variants, 1 for
#   the fast ones.
COLOUR_STEPS = 1

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "browser"))
from browser_test import parse_pfm  # noqa: E402  (the one PFM reader of the engine tests)


def run(command, **options):
    return subprocess.run(command, check=True, capture_output=True, text=True, **options)


def srgb_encode(value):
    """core/srgb.hpp's encoding, and the PNG writer's clamp and rounding."""
    encoded = value * 12.92 if value <= 0.0031308 else 1.055 * value ** (1.0 / 2.4) - 0.055
    return round(min(max(encoded, 0.0), 1.0) * 255.0)


def deviation(values):
    mean = sum(values) / len(values)
    return mean, math.sqrt(sum((v - mean) ** 2 for v in values) / len(values))


BITS_FRAGMENT = """
void fragment() {
    // Pixel (4 i + c, j) holds the float32 bytes of channel c of render pixel (i, j).
    vec2 cell = floor(UV * vec2(4.0 * stochtex_size.x, stochtex_size.y));
    float column = floor(cell.x / 4.0);
    float channel = cell.x - 4.0 * column;
    vec2 p = stochtex_origin + stochtex_scale * (vec2(column, cell.y) + vec2(0.5, 0.5));
    vec4 value = FUNCTION(p, vec2(stochtex_scale, 0.0), vec2(0.0, stochtex_scale),
                          uint(stochtex_seed));
    float v = value.x;
    if (channel == 1.0) {
        v = value.y;
    } else if (channel == 2.0) {
        v = value.z;
    } else if (channel == 3.0) {
        v = value.w;
    }
    uint bits = floatBitsToUint(v);
    COLOR = vec4(float(bits & uint(255)), float((bits >> uint(8)) & uint(255)),
                 float((bits >> uint(16)) & uint(255)), float(bits >> uint(24))) / 255.0;
}
"""

MAIN_SCRIPT = """extends Node
# Renders each case's views in viewports of their size, then writes each viewport's RGBA8 bytes.

func _viewport(width, height):
    var view = Viewport.new()
    view.size = Vector2(width, height)
    # Transparent before the usage: Godot 3.2 makes the render target when the usage changes,
    # RGBA8 if it is transparent then, else RGB10_A2 (whose alpha keeps 2 bits).
    view.transparent_bg = true
    view.usage = Viewport.USAGE_2D
    view.render_target_v_flip = true
    view.render_target_update_mode = Viewport.UPDATE_ALWAYS
    add_child(view)
    return view

func _set_view(material, view):
    material.set_shader_param("stochtex_size", Vector2(view.size, view.size))
    material.set_shader_param("stochtex_origin", Vector2(view.origin[0], view.origin[1]))
    material.set_shader_param("stochtex_scale", view.scale)
    material.set_shader_param("stochtex_seed", view.seed)

func _ready():
    var file = File.new()
    file.open("res://cases.json", File.READ)
    var cases = parse_json(file.get_as_text())
    file.close()
    var outputs = []
    for item in cases:
        for view in item.views:
            # The export's own scene, as a user opens it, its shader parameters set to the view.
            var colour_view = _viewport(view.size, view.size)
            var rect = load("res://" + item.folder + "/" + item.scene).instance()
            rect.rect_size = Vector2(view.size, view.size)
            rect.material = rect.material.duplicate()
            _set_view(rect.material, view)
            colour_view.add_child(rect)
            outputs.append([colour_view, view.name + "_colour.rgba"])
            # The same function writing its floats' bytes.
            var bits_view = _viewport(4 * view.size, view.size)
            var bits = ColorRect.new()
            bits.rect_size = Vector2(4 * view.size, view.size)
            bits.material = ShaderMaterial.new()
            bits.material.shader = load("res://" + item.folder + "/bits.shader")
            for texture in item.textures:
                bits.material.set_shader_param(texture[0], load("res://" + item.folder + "/" + texture[1]))
            _set_view(bits.material, view)
            bits_view.add_child(bits)
            outputs.append([bits_view, view.name + "_bits.rgba"])
        # The spatial shader on a quad facing an orthographic camera: it must compile and draw.
        var world_view = Viewport.new()
        world_view.size = Vector2(64, 64)
        world_view.own_world = true
        world_view.render_target_v_flip = true
        world_view.render_target_update_mode = Viewport.UPDATE_ALWAYS
        add_child(world_view)
        var camera = Camera.new()
        camera.projection = Camera.PROJECTION_ORTHOGONAL
        camera.size = 1.0
        camera.translation = Vector3(0, 0, 1)
        world_view.add_child(camera)
        var quad = MeshInstance.new()
        quad.mesh = QuadMesh.new()
        var material = ShaderMaterial.new()
        material.shader = load("res://" + item.folder + "/" + item.spatial)
        for texture in item.textures:
            material.set_shader_param(texture[0], load("res://" + item.folder + "/" + texture[1]))
        quad.material_override = material
        world_view.add_child(quad)
        var light = DirectionalLight.new()
        world_view.add_child(light)
        outputs.append([world_view, item.name + "_spatial.rgba"])
    for i in range(3):
        yield(VisualServer, "frame_post_draw")
    for output in outputs:
        var image = output[0].get_texture().get_data()
        image.convert(Image.FORMAT_RGBA8)
        var out = File.new()
        out.open("res://out/" + output[1], File.WRITE)
        out.store_buffer(image.get_data())
        out.close()
    print("stochtex: wrote ", outputs.size(), " images")
    get_tree().quit()
"""

PROJECT = """config_version=4

[application]

config/name="stochtex export test"
run/main_scene="res://main.tscn"

[display]

window/size/width=64
window/size/height=64

[rendering]

quality/driver/driver_name="GLES3"
"""

MAIN_SCENE = """[gd_scene load_steps=2 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[node name="main" type="Node"]
script = ExtResource( 1 )
"""


def godot(arguments, project, log, timeout, done=None):
    """Godot 3 under a virtual X display, its output in `log`: (exit status, seconds). It ends
    when Godot does, or when `done()` (polled) is true, or after `timeout` seconds (Godot keeps
    running after a script error): then its process group (xvfb-run, Xvfb and Godot, started
    here) is ended and the status is None."""
    started = time.monotonic()
    with open(log, "w") as output:
        process = subprocess.Popen(["xvfb-run", "-a", "godot3", "--path", project] + arguments,
                                   stdout=output, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        code = None
        while time.monotonic() - started < timeout:
            code = process.poll()
            if code is not None or (done is not None and done()):
                break
            time.sleep(0.2)
        if code is None:
            os.killpg(process.pid, signal.SIGTERM)
            process.wait()
    return code, time.monotonic() - started


def imported(project, folders):
    """The data files of `folders` whose import is not finished: the editor writes a file's
    imported copies, then its .import file naming them, then the .md5 file beside them, last."""
    missing = []
    for folder in folders:
        for name in os.listdir(os.path.join(project, folder)):
            if not name.endswith(".import"):
                continue
            with open(os.path.join(project, folder, name)) as f:
                paths = [line.split('"')[1] for line in f if line.startswith("path")]
            # .import/<file>-<hash>.stex (or .<format>.tex3d) and .import/<file>-<hash>.md5
            stems = [p[len("res://"):p.rindex("-") + 1] + p[p.rindex("-") + 1:].split(".")[0]
                     for p in paths]
            finished = paths and all(
                os.path.exists(os.path.join(project, p[len("res://"):])) for p in paths) and all(
                os.path.exists(os.path.join(project, stem + ".md5")) for stem in stems)
            if not finished:
                missing.append(f"{folder}/{name[:-len('.import')]}")
    return missing


def shader_errors(log):
    with open(log) as f:
        text = f.read()
    return [line for line in text.splitlines()
            if "SHADER ERROR" in line or "Compilation Failed" in line or "): error:" in line]


def make_project(args, folder):
    """Analyses, exports and renders on the CPU; writes the Godot project. Returns the cases
    with their CPU renders."""
    project = os.path.join(folder, "project")
    os.makedirs(os.path.join(project, "out"))
    for name, text in (("project.godot", PROJECT), ("main.tscn", MAIN_SCENE),
                       ("main.gd", MAIN_SCRIPT.replace("    ", "\t"))):
        with open(os.path.join(project, name), "w") as f:
            f.write(text)
    cases = []
    for case in CASES:
        model = os.path.join(folder, case["name"] + ".stx")
        if "mix" in case:
            command = [args.stochtex, "mix", args.exemplar, args.second_exemplar, "-o",
                       model] + case["mix"]
        else:
            command = [args.stochtex, "analyze", args.exemplar, "--method", case["method"],
                       "-o", model]
        for parameter in case["params"]:
            command += ["-p", parameter]
        if "colour_space" in case:
            command += ["--colour-space", case["colour_space"]]
        run(command)
        export = os.path.join(project, case["name"])
        run([args.stochtex, "export-shader", model, "-o", export, "--variant", case["variant"],
             "--language", "godot"])
        method = case["method"]
        with open(os.path.join(export, f"stochtex_{method}_canvas.shader")) as f:
            canvas = f.read()
        # The bits shader: the canvas shader's uniforms and functions, another fragment().
        body = canvas[:canvas.index("\nvoid fragment()")]
        body = body.replace("shader_type canvas_item;",
                            "shader_type canvas_item;\nrender_mode blend_disabled;")
        with open(os.path.join(export, "bits.shader"), "w") as f:
            f.write(body + BITS_FRAGMENT.replace("FUNCTION", f"stochtex_{method}"))
        # Each data file (x.png or x.exr, with x.png.import) is the texture stochtex_x.
        textures = [[f"stochtex_{name.split('.')[0]}", name[:-len(".import")]]
                    for name in sorted(os.listdir(export)) if name.endswith(".import")]
        views = []
        for k, (origin, scale) in enumerate(VIEWS):
            name = f"{case['name']}_{k}"
            pfm = os.path.join(folder, name + ".pfm")
            run([args.stochtex, "render", model, "-o", pfm, "--size", f"{SIZE}x{SIZE}",
                 "--origin", f"{origin[0]:g},{origin[1]:g}", "--scale", f"{scale:g}",
                 "--seed", str(SEED)])
            with open(pfm, "rb") as f:
                cpu = parse_pfm(f.read())
            views.append({"name": name, "size": SIZE, "origin": list(origin), "scale": scale,
                          "seed": SEED, "cpu": cpu})
        cases.append({"name": case["name"], "method": method, "variant": case["variant"],
                      "srgb": case.get("colour_space") != "data", "folder": case["name"],
                      "scene": f"stochtex_{method}.tscn",
                      "spatial": f"stochtex_{method}.shader",
                      "textures": textures,
                      "views": views})
    with open(os.path.join(project, "cases.json"), "w") as f:
        json.dump([{k: v for k, v in c.items() if k != "views"} |
                   {"views": [{k: v for k, v in view.items() if k != "cpu"}
                              for view in c["views"]]} for c in cases], f)
    return project, cases


def read_rgba(path, width, height):
    with open(path, "rb") as f:
        data = f.read()
    if len(data) != width * height * 4:
        raise RuntimeError(f"{path}: {len(data)} bytes, expected {width}x{height} RGBA")
    return data


def compare(case, view, project, measure):
    """The failures of one view: Godot's floats and colours against the CPU render's."""
    failures = []
    width, height, channels, cpu = view["cpu"]
    bits = read_rgba(os.path.join(project, "out", view["name"] + "_bits.rgba"), 4 * width,
                     height)
    godot_values = [struct.unpack("<f", bits[4 * (4 * i + c):4 * (4 * i + c) + 4])[0]
                    for i in range(width * height) for c in range(channels)]
    worst = max(abs(g - c) for g, c in zip(godot_values, cpu))
    label = f"{view['name']} (scale {view['scale']:g})"
    exact = case["variant"] == "exact" or case["method"] == "lrp"
    if case["method"] == "gabor":
        bound = GABOR_DEVIATIONS * min(deviation(cpu[c::channels])[1] for c in range(channels))
    elif exact:
        bound = EXACT_BOUND
    else:
        bound = FAST_BOUND if view["scale"] == 1.0 else None
    line = f"{label}: largest |Godot - CPU| {worst:.3g}"
    if bound is not None and not worst <= bound:
        failures.append(f"{line}, above {bound:.3g}")
    if bound is None:
        for c in range(channels):
            g_mean, g_dev = deviation(godot_values[c::channels])
            c_mean, c_dev = deviation(cpu[c::channels])
            line += f"; channel {c} mean {g_mean:.4f} (CPU {c_mean:.4f}), deviation {g_dev:.4f}" \
                    f" (CPU {c_dev:.4f})"
            if abs(g_mean - c_mean) > FAST_MEAN_BOUND or abs(g_dev / c_dev - 1) > \
                    FAST_DEVIATION_BOUND:
                failures.append(f"{label}: channel {c}'s mean or deviation off: {line}")
    # The scene's 8-bit colour: the bytes of the PNG that `stochtex render` writes of the same
    # values (sRGB-encoded linear light for a srgb model, the values as they are for a data
    # model), up to rounding: of Godot's own values, and for the exact variants of the CPU's.
    colour = read_rgba(os.path.join(project, "out", view["name"] + "_colour.rgba"), width,
                       height)

    def png_byte(value):
        return srgb_encode(value) if case["srgb"] else round(min(max(value, 0.0), 1.0) * 255.0)

    steps = cpu_steps = 0
    for i in range(width * height):
        for c in range(3):
            k = i * channels + (c if channels >= 3 else 0)
            steps = max(steps, abs(colour[4 * i + c] - png_byte(godot_values[k])))
            cpu_steps = max(cpu_steps, abs(colour[4 * i + c] - png_byte(cpu[k])))
    line += f"; scene colour within {steps} of 255 of Godot's values, {cpu_steps} of the CPU PNG's"
    if steps > COLOUR_STEPS:
        failures.append(f"{label}: the scene's colour is {steps} steps from its values")
    if exact and cpu_steps > COLOUR_STEPS:
        failures.append(f"{label}: the scene's colour is {cpu_steps} steps from the CPU PNG's")
    if measure:
        print(line)
    return failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("stochtex")
    parser.add_argument("exemplar")
    parser.add_argument("second_exemplar", help="texton_mix's second exemplar")
    parser.add_argument("--keep", help="folder to keep the project in")
    parser.add_argument("--measure", action="store_true")
    args = parser.parse_args()
    if shutil.which("godot3") is None or shutil.which("xvfb-run") is None:
        print("godot_test: skipped: godot3 and xvfb-run are not installed "
              "(scripts/install-deps.sh installs them)")
        return SKIP
    started = time.monotonic()
    folder = args.keep or tempfile.mkdtemp(prefix="stochtex_godot_")
    try:
        project, cases = make_project(args, folder)
        prepared = time.monotonic()
        # The editor imports the data files with the exported .import settings. Godot 3.2.3's
        # editor has no "import and quit" (--quit may end it before its scan thread has
        # imported, and it crashes on quitting after an import), so it runs until every file is
        # imported, then it is ended.
        folders = [case["folder"] for case in cases]
        _, import_seconds = godot(["--editor"], project, os.path.join(folder, "import.log"), 120,
                                  lambda: not imported(project, folders))
        failures = [f"{name} was not imported" for name in imported(project, folders)]
        code, run_seconds = godot([], project, os.path.join(folder, "run.log"), 180)
        if code != 0:
            failures.append(f"Godot exited with {code} (None: stopped after 180 s; run.log)")
        for log in ("import.log", "run.log"):
            failures += [f"{log}: {line}" for line in shader_errors(os.path.join(folder, log))]
        if not failures:
            for case in cases:
                for view in case["views"]:
                    failures += compare(case, view, project, args.measure)
                spatial = read_rgba(os.path.join(project, "out", case["name"] + "_spatial.rgba"),
                                    64, 64)
                if len(set(spatial[4 * i:4 * i + 3] for i in range(64 * 64))) < 16:
                    failures.append(f"{case['name']}: the spatial shader drew no texture")
        print(f"godot_test: {len(cases)} exports, CPU side {prepared - started:.1f} s, "
              f"editor import {import_seconds:.1f} s, run {run_seconds:.1f} s")
        for failure in failures:
            print("FAIL:", failure)
        return 1 if failures else 0
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
