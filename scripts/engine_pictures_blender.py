"""Blender's side of scripts/engine_pictures_blender.sh (docs/engines.md, "Blender").

    blender -b --factory-startup -P engine_pictures_blender.py -- scene ZIP STOCHTEX EXEMPLAR OUT
        installs the add-on, builds the scene (a plane showing the exemplar 4 x 4 times), saves
        OUT/scene.blend, runs the operator (node group) and renders with Cycles the plane as the
        Image Texture node shows it (OUT/image_texture.png) and as the node group does
        (OUT/node_group.png), then saves OUT/stochtex.blend;
    blender --factory-startup OUT/stochtex.blend -P engine_pictures_blender.py -- screenshot OUT
        (with a window: under Xvfb) takes a screenshot of the Shading workspace, the viewport in
        Material Preview above the Shader Editor, into OUT/screenshot.png.
"""

import os
import sys

import bpy

MODE, *ARGUMENTS = sys.argv[sys.argv.index("--") + 1:]
REPEATS = 4.0  # exemplar widths across the plane
SIDE = 384  # rendered pixels a side


def scene(zip_path, stochtex, exemplar, out):
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="stochtex_addon")
    bpy.context.preferences.addons["stochtex_addon"].preferences.command = stochtex
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    plane = bpy.context.active_object
    material = bpy.data.materials.new("cobblestone")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    # A diffuse surface: a node small enough for the screenshot's Shader Editor to read.
    bsdf = tree.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.location = (-150.0, 300.0)
    tree.nodes["Material Output"].location = (50.0, 300.0)
    tree.links.new(bsdf.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    coordinates = tree.nodes.new("ShaderNodeTexCoord")
    coordinates.location = (-900.0, 300.0)
    repeat = tree.nodes.new("ShaderNodeVectorMath")
    repeat.operation = "SCALE"
    repeat.inputs["Scale"].default_value = REPEATS
    repeat.location = (-700.0, 300.0)
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(exemplar)
    texture.location = (-450.0, 300.0)
    tree.links.new(coordinates.outputs["UV"], repeat.inputs[0])
    tree.links.new(repeat.outputs[0], texture.inputs["Vector"])
    tree.links.new(texture.outputs["Color"], bsdf.inputs["Color"])
    tree.nodes.active = texture
    plane.data.materials.append(material)

    render = bpy.context.scene.render
    render.engine = "CYCLES"
    bpy.context.scene.cycles.samples = 16
    bpy.context.scene.cycles.use_denoising = False
    render.resolution_x = render.resolution_y = SIDE
    render.threads_mode = "FIXED"
    render.threads = 2
    bpy.context.scene.view_settings.view_transform = "Standard"
    camera_data = bpy.data.cameras.new("camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = 2.0
    camera = bpy.data.objects.new("camera", camera_data)
    camera.location = (0.0, 0.0, 2.0)
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    bpy.data.worlds["World"].node_tree.nodes["Background"].inputs["Strength"].default_value = 3.0
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "scene.blend"))

    render.filepath = os.path.join(out, "image_texture.png")
    bpy.ops.render.render(write_still=True)
    result = bpy.ops.node.stochtex_analyse(method="tiling", seed=1)
    assert result == {"FINISHED"}, result
    # The node group's Vector takes what fed the Image Texture node's (the UV scaled 4 times).
    render.filepath = os.path.join(out, "node_group.png")
    bpy.ops.render.render(write_still=True)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "stochtex.blend"))


def screenshot(out):
    """The Shading workspace once its viewport has compiled the material's shaders: the photo
    (top left), the node group's Gaussianised exemplar (bottom left), the viewport in Material
    Preview (EEVEE) and the Shader Editor."""
    window = bpy.context.window_manager.windows[0]
    window.workspace = bpy.data.workspaces["Shading"]
    photo = next(i for i in bpy.data.images if i.name.startswith("cobblestone"))
    gaussian = next(i for i in bpy.data.images if i.filepath.endswith("tiling_exemplar.png"))

    def arrange():
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                space = area.spaces.active
                space.shading.type = "MATERIAL"
                space.overlay.show_overlays = False
                space.region_3d.view_perspective = "ORTHO"
                space.region_3d.view_rotation = (1.0, 0.0, 0.0, 0.0)  # from the top
                space.region_3d.view_location = (0.0, 0.0, 0.0)
                space.region_3d.view_distance = 1.4
            elif area.type in ("FILE_BROWSER", "IMAGE_EDITOR"):
                top = area.type == "FILE_BROWSER"
                area.type = "IMAGE_EDITOR"
                area.spaces.active.image = photo if top else gaussian
        return None

    def frame_nodes():
        # Once drawn: a node's size is known only then.
        area = next(a for a in window.screen.areas if a.type == "NODE_EDITOR")
        region = next(r for r in area.regions if r.type == "WINDOW")
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.node.view_all()
            # view_all leaves a wide margin around nodes this few: 10 steps of 7.5% each.
            for _ in range(10):
                bpy.ops.view2d.zoom_in()
        return None

    def shoot():
        bpy.ops.screen.screenshot(filepath=os.path.join(out, "screenshot.png"))
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(arrange, first_interval=1.0)
    # llvmpipe compiles the group's EEVEE shader in several seconds.
    bpy.app.timers.register(frame_nodes, first_interval=35.0)
    bpy.app.timers.register(shoot, first_interval=40.0)


if MODE == "scene":
    scene(*ARGUMENTS)
else:
    screenshot(*ARGUMENTS)
