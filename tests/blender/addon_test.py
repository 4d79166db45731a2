"""The Blender add-on in Blender itself (docs/engines.md, "Blender"), run by run_addon_test.sh:

    blender -b --factory-startup --python-exit-code 1 -P addon_test.py -- \
        ADDON_ZIP STOCHTEX WORK_DIR EXEMPLAR_DIR

1. Installs the zip and enables the add-on, as a user does from the preferences.
2. Node group (analysis through the Python module), for each case of GROUP_CASES (an exemplar
   and the operator's Parameters: each kind of model the group evaluates): an Image Texture node
   with the exemplar (Color Space sRGB) on a plane, the operator, then a render of an
   orthographic view of the plane by Cycles (CPU) and by EEVEE (OpenGL: Mesa's llvmpipe under
   Xvfb here), each against `stochtex render` of the same region and seed, pixel for pixel.
   A linear-blend model is refused by the group and baked.
3. Bakes of grass_lawn_128: its tiling model (analysis and render through the command line)
   baked periodic to PNG and to OpenEXR, its texton model (through the module) to OpenEXR, each
   rendered by both engines as the add-on set it up, against `stochtex render --periodic`: the
   colour space of each file must be the one Blender reads it in (the EXR holds linear light,
   the PNG sRGB-encoded values).
   The .blend, saved and opened again without the add-on's files, renders the same: it holds
   the images packed.
4. Disables and removes the add-on.

Every render takes one sample per pixel, at the pixel's centre (Cycles: through a 0.01-pixel box
filter, so to 0.005 pixels; EEVEE: its first sample is the centre), of an Emission shader, so a
pixel's value is the texture's (scene-linear, saved to a 32-bit float OpenEXR without view
transform).
"""

import glob
import os
import shutil
import subprocess
import sys

import addon_utils
import bpy
import numpy

ZIP, STOCHTEX, WORK, EXEMPLAR_DIR = sys.argv[sys.argv.index("--") + 1:]
MODULE = "stochtex_addon"
SIDE = 64  # rendered pixels a side
SCALE = 4.0  # the node group's Scale: the plane's UV square holds 4 x 4 exemplar widths
ORIGIN = (160, 200)  # the rendered region's top-left corner, exemplar pixels
ENGINES = ("CYCLES", "BLENDER_EEVEE")
MAX_DIFFERENCE = {"CYCLES": 5e-3, "BLENDER_EEVEE": 5e-4}  # the node group's, reasons below
# The node group's cases: the exemplar, the operator's Parameters, what the case covers. The
# transport is named, so that the 3-D table stays covered whatever the default. The last case's
# .blend is saved and opened again: it has every kind of table the add-on makes in Blender.
GROUP_CASES = (
    ("grass_lawn_128.png", "transport=sliced", "the 3-D table as a 16-bit PNG"),
    ("water_caustics_256.png", "transport=sliced", "the 3-D table as a float OpenEXR"),
    ("grass_lawn_128.png", "transport=pca", "the pca transport: 1-D tables, colour basis, "
     "decoded from sRGB"),
    ("grass_lawn_128.png", "blend=variance", "the variance blend: no T^-1, decoded from sRGB"),
    ("nuts_grey_256.png", "sharpness=4 rotation=30 scale_jitter=0.5",
     "a grey model's 1-D table, the artist controls"),
)
BAKED_EXEMPLAR = os.path.join(EXEMPLAR_DIR, "grass_lawn_128.png")
BAKE_SIDE = 128  # grass_lawn_128's size: one bake pixel per rendered texture pixel below
BAKE_ORIGIN = (32, 40)
failures = []
renders = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


def read_exr(path):
    """A float image's pixels as stored, rows from the top (stochtex's order)."""
    image = bpy.data.images.load(path, check_existing=False)
    image.colorspace_settings.name = "Non-Color"
    width, height = image.size
    pixels = numpy.empty(width * height * 4, numpy.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1, :, :3]


def reference(model, name, size, origin=(0, 0), periodic=False):
    path = os.path.join(WORK, name + ".exr")
    subprocess.run([STOCHTEX, "render", model, "-o", path, "--size", "%dx%d" % size,
                    "--origin", "%d,%d" % origin, "--seed", "0"] +
                   (["--periodic"] if periodic else []), check=True, capture_output=True)
    return read_exr(path)


def scene_with_plane(exemplar):
    """The scene emptied (the add-on stays enabled), then a plane whose material shows the
    exemplar's Image Texture node (the active node) through an Emission shader."""
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.cameras, bpy.data.lights,
                       bpy.data.materials):
        for block in list(collection):
            collection.remove(block)
    scene = bpy.context.scene
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.eevee.taa_render_samples = 1
    scene.render.resolution_x = scene.render.resolution_y = SIDE
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    bpy.ops.mesh.primitive_plane_add(size=2.0)  # x, y in [-1, 1], UV (x + 1, y + 1) / 2
    plane = bpy.context.active_object
    material = bpy.data.materials.new("exemplar")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(exemplar)
    texture.image.colorspace_settings.name = "sRGB"
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(texture.outputs["Color"], emission.inputs["Color"])
    material.node_tree.links.new(emission.outputs[0], output.inputs["Surface"])
    nodes.active = texture
    plane.data.materials.append(material)
    return scene, material


def render_region(scene, engine, pixels_per_unit, origin):
    """The engine's render of the SIDE x SIDE region at `origin` (texture pixels, y down), where
    the plane's x in [-1, 1] spans 2 pixels_per_unit texture pixels."""
    scene.render.engine = engine
    camera_data = bpy.data.cameras.new("camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = SIDE / pixels_per_unit
    camera = bpy.data.objects.new("camera", camera_data)
    centre = [o + SIDE / 2.0 for o in origin]
    camera.location = (centre[0] / pixels_per_unit - 1.0, 1.0 - centre[1] / pixels_per_unit, 1.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    renders.append(os.path.join(WORK, "render_%d.exr" % len(renders)))
    path = renders[-1]
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    return read_exr(path)


def newest_model(method="tiling"):
    """The model file of `method` the operator wrote last: its folders are in TMPDIR (WORK/tmp)
    while the .blend is not saved, then in stochtex/ beside it (WORK/stochtex)."""
    return max(glob.glob(os.path.join(WORK, "*", "*", method + ".stx")), key=os.path.getmtime)


def run_operator(**options):
    result = bpy.ops.node.stochtex_analyse(**options)
    check(result == {"FINISHED"}, "the operator finished (%s)" % options)


# 1. Install and enable.
bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
bpy.ops.preferences.addon_enable(module=MODULE)
check(addon_utils.check(MODULE)[1], "the add-on is enabled")
check(hasattr(bpy.types, "NODE_OT_stochtex_analyse"), "its operator is registered")
preferences = bpy.context.preferences.addons[MODULE].preferences
preferences.command = STOCHTEX
# Mesa's llvmpipe filters anisotropically even a 1:1 view (Blender's default, 2x, blurred a
# plain image's render by 0.019 on average): the bakes' reads compare without it. The node group
# makes closest reads only, which no texture filter changes.
bpy.context.preferences.system.anisotropic_filter = "FILTER_0"

# 2. The node group, analysed by the Python module.
preferences.use = "module"
rendered = {}
for exemplar, parameters, covers in GROUP_CASES:
    label = "%s (%s: %s)" % (exemplar, parameters, covers)
    scene, material = scene_with_plane(os.path.join(EXEMPLAR_DIR, exemplar))
    run_operator(method="tiling", seed=0, parameters=parameters)
    groups = [n for n in material.node_tree.nodes if n.type == "GROUP"]
    check(len(groups) == 1 and groups[0].outputs["Color"].links,
          "%s: a node group feeds the emission" % label)
    model = newest_model()
    groups[0].inputs["Scale"].default_value = SCALE
    width = bpy.data.images[exemplar].size[0]
    expected = reference(model, "group_reference", (SIDE, SIDE), ORIGIN)
    # Scale jitter reads a patch up to 2^scale_jitter times as fast (the Cycles bound below).
    patch_scale = 2.0 ** float(dict(p.split("=") for p in parameters.split()).get(
        "scale_jitter", 0.0))
    for engine in ENGINES:
        rendered[engine] = render_region(scene, engine, width * SCALE / 2.0, ORIGIN)
        difference = numpy.abs(rendered[engine] - expected)
        print("%s, %s, node group against stochtex render: max %.2e, mean %.2e" %
              (engine, label, difference.max(), difference.mean()))
        # The group runs the fast variant's data: the Gaussianised exemplar as a 16-bit PNG and
        # T^-1 as a 16-bit PNG (grass) or float OpenEXR (water, the 1-D tables), which move the
        # values by at most 2.2e-5 from the CPU's (grass, measured in numpy with these files),
        # and its float node arithmetic. EEVEE samples each pixel's centre: measured max 2.2e-5
        # (grass), 1.1e-4 (water), 9.1e-6 (pca), 5.4e-7 (variance: no T^-1), 1.7e-4 (nuts, whose
        # T^-1 is steep between its dark ground and bright nuts: 2.7e-4 without the controls).
        # Cycles' 0.01-pixel filter moves each sample by up to 0.005 pixels, so a bilinear read
        # by up to 0.005 of a step between neighbouring texels (times the patch's scale), at most
        # 5e-3 for values in [0, 1]: measured max 2.6e-4 (grass, pca, variance: 2.2e-4 to
        # 2.6e-4), 1.8e-3 (water's sharp caustics), 3.8e-3 (nuts' edges; 3.1e-3 without the
        # controls). Means: Cycles 3.0e-5 to 5.3e-5 (nuts), EEVEE 5.7e-8 to 6.2e-6 (nuts).
        # What the bounds caught: one patch at a wrong offset in one triangle of the region gave
        # max 0.028 and mean 5e-5; a wrong vertex order, 0.27 and 0.04; EEVEE's mip-mapped reads
        # where the patches change (Linear image reads), 0.14 and 2.6e-3; a seed other than the
        # reference's, 0.25 and 0.04; pca's basis transposed, 0.41 and 0.047; its values not
        # decoded from sRGB, 0.29 and 0.25; its 1-D tables read one entry off, 0.032 and 3.3e-4;
        # nuts' sharpness left out, 0.88 and 0.10; its rotation and scale jitter left out, 1.0
        # and 0.48.
        bound = MAX_DIFFERENCE[engine] * (patch_scale if engine == "CYCLES" else 1.0)
        check(difference.max() < bound and difference.mean() < 1e-4,
              "%s, %s: the node group's render is stochtex render's region" % (engine, label))

# The .blend holds what the group reads: saved, its files deleted and opened again, it renders
# the same pixels (Cycles' render of the last case: the images are the same in both engines).
blend = os.path.join(WORK, "group.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
shutil.rmtree(os.path.dirname(newest_model()))
bpy.ops.wm.open_mainfile(filepath=blend)
again = render_region(bpy.context.scene, "CYCLES", width * SCALE / 2.0, ORIGIN)
check(numpy.array_equal(again, rendered["CYCLES"]),
      "the saved .blend renders the same without the files")

# What the operator refuses, or evaluates otherwise than asked, on a new plane. Parameters it
# refuses, each in one sentence: text that is not name=value pairs, and a parameter the method
# does not have (the library's sentence, through the module).
scene, material = scene_with_plane(BAKED_EXEMPLAR)
for parameters, sentence in (("transport", "the parameters are name=value pairs"),
                             ("colours=3", "colours")):
    try:
        bpy.ops.node.stochtex_analyse(method="tiling", parameters=parameters)
        message = "(none)"
    except RuntimeError as error:
        message = str(error).strip()
    print("Parameters %r: %s" % (parameters, message))
    check(sentence in message and len(message.splitlines()) == 1,
          "Parameters %r are refused in one sentence" % parameters)

# A linear-blend model: the group refuses it (a warning), the operator bakes it instead.
run_operator(method="tiling", seed=0, parameters="blend=linear", resolution=16)
check(not [n for n in material.node_tree.nodes if n.type == "GROUP"] and
      [n for n in material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image and
       n.image.name.startswith("stochtex tiling bake")],
      "a linear-blend model is baked, not evaluated by the node group")

# 3. Periodic bakes: tiling to PNG and to OpenEXR through the command line, texton (another
# method: a bake only) to OpenEXR through the module.
for method, file_format, use, bound in (("tiling", "PNG", "command_line", 5e-3),
                                        ("tiling", "EXR", "command_line", 1e-3),
                                        ("texton", "EXR", "module", 1e-3)):
    preferences.use = use
    scene, material = scene_with_plane(BAKED_EXEMPLAR)
    run_operator(method=method, bake=True, resolution=BAKE_SIDE, periodic=True,
                 file_format=file_format, seed=0)
    baked = [n for n in material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image and
             n.image.name.startswith("stochtex")][0].image
    check(baked.colorspace_settings.name == ("sRGB" if file_format == "PNG" else "Linear"),
          "the %s bake's Color Space is %s" % (file_format, baked.colorspace_settings.name))
    whole = reference(newest_model(method), "bake_reference", (BAKE_SIDE, BAKE_SIDE),
                      periodic=True)
    expected = whole[BAKE_ORIGIN[1]:BAKE_ORIGIN[1] + SIDE, BAKE_ORIGIN[0]:BAKE_ORIGIN[0] + SIDE]
    for engine in ENGINES:
        difference = numpy.abs(render_region(scene, engine, BAKE_SIDE / 2.0, BAKE_ORIGIN) -
                               expected)
        print("%s, %s %s bake against stochtex render --periodic: max %.2e, mean %.2e" %
              (engine, method, file_format, difference.max(), difference.mean()))
        # PNG: 8-bit sRGB-encoded values, half a level of 255 is at most 4.5e-3 in linear light
        # (the sRGB curve's slope is at most 2.3); measured max 3.2e-3 (Cycles), 4.1e-3 (EEVEE).
        # EXR: float; Cycles' filter jitter, max 1.9e-4, and EEVEE's 16-bit float textures, max
        # 4.9e-4 (texton: about the same). Encoded values read as linear light (the washed-out
        # EXR) are off by up to 0.29, linear light read as sRGB by as much.
        check(difference.max() < bound, "%s: the %s %s bake renders as stochtex renders it" %
              (engine, method, file_format))

# 4. Disable and remove.
bpy.ops.preferences.addon_disable(module=MODULE)
check(not hasattr(bpy.types, "NODE_OT_stochtex_analyse"), "disabled: the operator is gone")
installed = os.path.join(WORK, "scripts", "addons", MODULE)
check(os.path.isdir(installed), "the add-on was installed into Blender's user scripts")
try:
    bpy.ops.preferences.addon_remove(module=MODULE)
except RuntimeError as error:
    # Blender 3.4's operator removes the add-on, then redraws the Preferences area, which a
    # background Blender does not have (context.area is None): judged by what it removed.
    print("addon_remove: %s" % str(error).strip().splitlines()[-1])
check(not os.path.exists(installed), "removed: the add-on's folder is gone")
check(not any(m.__name__ == MODULE for m in addon_utils.modules(refresh=True)),
      "removed: Blender no longer lists the add-on")

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
