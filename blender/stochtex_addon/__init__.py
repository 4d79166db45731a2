"""stochtex for Blender: turn an Image Texture node into a texture that never repeats
(docs/engines.md, "Blender").

In the Shader Editor, select an Image Texture node and run "Stochtex: analyse image texture"
(sidebar, Stochtex tab, or the Node menu). The image is analysed as its Color Space says (sRGB,
Linear or Non-Color), then either

- tiling: a node group of native nodes (math nodes and closest Image Texture reads, which every
  Blender device runs) that evaluates histogram-preserving tiling and blending (stochtex's fast
  shader variant) in EEVEE and Cycles; or
- any method (or tiling when asked): a bake, an image rendered by stochtex at a chosen
  resolution, periodic when asked so that it repeats without a seam.

The node's Color output is rewired to the result; the Image Texture node stays, unlinked.
"""

bl_info = {
    "name": "stochtex",
    "author": "stochtex",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Shader Editor > Sidebar > Stochtex; Node > Stochtex: analyse image texture",
    "description": "Textures by example that never repeat: analyse an Image Texture node's "
                   "image with stochtex, then a tiling node group or a bake",
    "category": "Node",
}

import os
import tempfile

import bpy
import numpy

from . import backend, tiling_group

METHODS = [("tiling", "Tiling", "Histogram-preserving tiling and blending (Heitz & Neyret 2018): "
            "a node group, or a bake"),
           ("texton", "Texton noise", "Galerne et al. 2017: a bake"),
           ("lrp", "Local random-phase noise", "Gilet et al. 2014: a bake"),
           ("gabor", "Gabor noise", "Galerne et al. 2012: a bake")]


class StochtexPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    use: bpy.props.EnumProperty(
        name="Use", default="auto",
        items=[("auto", "Automatic", "The Python module where it imports, else the command"),
               ("module", "Python module", "import stochtex (scripts/install-python.sh)"),
               ("command_line", "Command line", "The stochtex command")])
    command: bpy.props.StringProperty(
        name="stochtex command", subtype="FILE_PATH",
        description="The stochtex executable; empty: `stochtex` on PATH. The tiling node group "
                    "always needs it (export-shader)")

    def draw(self, context):
        self.layout.prop(self, "use")
        self.layout.prop(self, "command")


class ExemplarSource:
    """A Blender image as stochtex analyses it: the module takes its pixels, the command line
    its file."""

    def __init__(self, image, folder):
        self.image = image
        self.folder = folder

    def colour(self, from_pixels):
        """What the values are ("srgb", "linear", "data"), from the image's Color Space. Blender
        gives a float image's pixels in scene-linear light (Rec. 709 primaries, stochtex's linear),
        a byte image's as stored."""
        name = self.image.colorspace_settings.name
        if name in ("Non-Color", "Raw"):
            return "data"
        if name not in ("sRGB", "Linear"):
            raise backend.StochtexError(
                "the image's Color Space is %s: stochtex analyses sRGB, Linear and Non-Color "
                "images" % name)
        if from_pixels and self.image.is_float:
            return "linear"
        return "srgb" if name == "sRGB" else "linear"

    def array(self):
        image = self.image
        width, height = image.size
        if width == 0 or height == 0:
            raise backend.StochtexError("the image '%s' has no pixels (is its file missing?)"
                                        % image.name)
        pixels = numpy.empty(width * height * 4, numpy.float32)
        image.pixels.foreach_get(pixels)
        # Blender's rows start at the bottom; stochtex's (and the file's) at the top.
        pixels = pixels.reshape(height, width, 4)[::-1]
        channels = image.depth // (32 if image.is_float else 8)
        pixels = pixels[..., {1: [0], 2: [0, 3], 3: [0, 1, 2], 4: [0, 1, 2, 3]}[channels]]
        if image.is_float:
            return numpy.ascontiguousarray(pixels)
        # A byte image's pixels are its bytes / 255: the uint8 array is the file's values.
        return numpy.rint(pixels * 255.0).astype(numpy.uint8)

    def file(self):
        image = self.image
        if image.packed_file:
            extension = os.path.splitext(image.filepath)[1] or ".png"
            path = os.path.join(self.folder, "exemplar" + extension)
            with open(path, "wb") as out:
                out.write(image.packed_file.data)
            return path
        path = bpy.path.abspath(image.filepath, library=image.library)
        if image.source != "FILE" or not os.path.isfile(path):
            raise backend.StochtexError("the image '%s' is not a file (save or pack it first)"
                                        % image.name)
        return path


def active_image_node(context):
    """The node tree and its active node where that node is an Image Texture with an image."""
    space = context.space_data
    tree = space.edit_tree if space and space.type == "NODE_EDITOR" else None
    if tree is None:
        obj = context.active_object
        material = obj.active_material if obj else None
        tree = material.node_tree if material and material.use_nodes else None
    node = tree.nodes.active if tree else None
    if node is None or node.type != "TEX_IMAGE" or node.image is None:
        return tree, None
    return tree, node


def data_folder(image_name):
    """A new folder for the model and the exported files: beside the saved .blend (stochtex/),
    else in the temporary folder. Every image the add-on makes is also packed into the .blend."""
    if bpy.data.filepath:
        parent = os.path.join(os.path.dirname(bpy.data.filepath), "stochtex")
        os.makedirs(parent, exist_ok=True)
    else:
        parent = None
    safe = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in image_name)
    return tempfile.mkdtemp(prefix=safe + "-", dir=parent)


def load_image(path, colour_space):
    image = bpy.data.images.load(path, check_existing=False)
    image.colorspace_settings.name = colour_space
    image.pack()
    return image


def rewire(tree, old, colour_output, vector_input):
    """Feeds `vector_input` what fed the old node's Vector (else the UV) and moves every link of
    the old node's Color to `colour_output`; the old node stays, unlinked."""
    feeding = [link.from_socket for link in old.inputs["Vector"].links]
    if not feeding:
        coordinates = tree.nodes.new("ShaderNodeTexCoord")
        coordinates.location = (old.location.x - 600.0, old.location.y)
        feeding = [coordinates.outputs["UV"]]
    tree.links.new(feeding[0], vector_input)
    for link in list(old.outputs["Color"].links):
        tree.links.new(colour_output, link.to_socket)
    for link in list(old.inputs["Vector"].links) + list(old.outputs["Alpha"].links):
        tree.links.remove(link)
    old.label = "stochtex source"


class NODE_OT_stochtex_analyse(bpy.types.Operator):
    """Analyse the active Image Texture node's image with stochtex, then replace the node's
    output with a node group (tiling) or a bake"""

    bl_idname = "node.stochtex_analyse"
    bl_label = "Stochtex: analyse image texture"
    bl_options = {"REGISTER", "UNDO"}

    method: bpy.props.EnumProperty(name="Method", items=METHODS, default="tiling")
    bake: bpy.props.BoolProperty(
        name="Bake", default=False,
        description="Tiling: bake an image instead of the node group (the other methods always "
                    "bake)")
    resolution: bpy.props.IntProperty(name="Resolution", default=1024, min=16, max=16384,
                                      description="The bake's width and height in pixels")
    periodic: bpy.props.BoolProperty(
        name="Periodic", default=True,
        description="Bake an image that repeats with its size without a seam "
                    "(stochtex render --periodic)")
    file_format: bpy.props.EnumProperty(
        name="Format", default="PNG",
        items=[("PNG", "PNG", "8 bits; colour sRGB-encoded (Color Space sRGB)"),
               ("EXR", "OpenEXR", "32-bit float; colour in linear light (Color Space Linear)")])
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0, max=2**31 - 1,
                                description="The random pattern (render --seed)")
    parameters: bpy.props.StringProperty(
        name="Parameters", default="",
        description="The method's parameters as name=value separated by spaces, as `stochtex "
                    "analyze -p` takes them (`stochtex methods` lists them), e.g. "
                    "transport=pca sharpness=2; empty: the defaults")

    @classmethod
    def poll(cls, context):
        return active_image_node(context)[1] is not None

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "method")
        layout.prop(self, "parameters")
        if self.method == "tiling":
            layout.prop(self, "bake")
        column = layout.column()
        column.enabled = self.bake or self.method != "tiling"
        for name in ("resolution", "periodic", "file_format"):
            column.prop(self, name)
        layout.prop(self, "seed")

    def execute(self, context):
        tree, node = active_image_node(context)
        preferences = context.preferences.addons[__package__].preferences
        try:
            parameters = backend.parse_parameters(self.parameters)
            stochtex = backend.Backend(preferences.use, preferences.command)
            folder = data_folder(node.image.name)
            source = ExemplarSource(node.image, folder)
            model_path = os.path.join(folder, self.method + ".stx")
            route, colour = stochtex.analyse(source, self.method, parameters, model_path)
            if self.method == "tiling" and not self.bake:
                try:
                    result = self.node_group(tree, node, stochtex, model_path, folder)
                except tiling_group.Unsupported as refusal:
                    self.report({"WARNING"}, "stochtex: %s: baking instead" % refusal)
                    result = self.baked(tree, node, stochtex, model_path, folder, colour)
            else:
                result = self.baked(tree, node, stochtex, model_path, folder, colour)
        except backend.StochtexError as error:
            self.report({"ERROR"}, "stochtex: %s" % error)
            return {"CANCELLED"}
        for other in tree.nodes:
            other.select = False
        result.select = True
        tree.nodes.active = result
        self.report({"INFO"}, "stochtex: %s of '%s' (%s, analysed by the %s), files in %s" % (
            self.method, node.image.name, colour, route, folder))
        return {"FINISHED"}

    def node_group(self, tree, node, stochtex, model_path, folder):
        export = os.path.join(folder, "fast")
        stochtex.export_fast(model_path, export)
        with open(os.path.join(export, "stochtex_tiling.glsl")) as glsl:
            constants = tiling_group.read_constants(glsl.read())
        files = tiling_group.check_supported(
            constants, [f for f in os.listdir(export) if f.endswith((".png", ".exr"))])
        name = "stochtex tiling: %s" % node.image.name
        images = {"exemplar": load_image(os.path.join(export, files["tiling_exemplar"]),
                                         "Non-Color"),
                  "offsets": tiling_group.offsets_image(name + " offsets", self.seed,
                                                        constants["TILING_WIDTH"],
                                                        constants["TILING_HEIGHT"])}
        if "tiling_lut" in files:
            images["lut"] = load_image(os.path.join(export, files["tiling_lut"]), "Non-Color")
        if "tiling_tables" in files:
            images["tables"] = tiling_group.tables_image(
                name + " tables", os.path.join(export, files["tiling_tables"]), constants)
        if constants["TILING_TRANSFORMED"]:
            images["transforms"] = tiling_group.transforms_image(name + " transforms", self.seed,
                                                                 constants)
        for image in images.values():
            # EEVEE would otherwise hold the float data as 16-bit floats on the GPU.
            image.use_half_precision = False
        group = tree.nodes.new("ShaderNodeGroup")
        group.node_tree = tiling_group.build_group(name, constants, images)
        group.location = node.location
        group.width = node.width  # wide enough to show the group's name
        node.location.y += 320.0
        rewire(tree, node, group.outputs["Color"], group.inputs["Vector"])
        return group

    def baked(self, tree, node, stochtex, model_path, folder, colour):
        extension = ".png" if self.file_format == "PNG" else ".exr"
        path = os.path.join(folder, "bake" + extension)
        stochtex.bake(model_path, path, self.resolution, self.resolution, self.seed, self.periodic)
        # What the file holds (backend.bake) and how Blender must read it (docs/colour.md).
        if colour == "data":
            colour_space = "Non-Color"
        else:
            colour_space = "sRGB" if extension == ".png" else "Linear"
        image = load_image(path, colour_space)
        image.name = "stochtex %s bake: %s" % (self.method, node.image.name)
        texture = tree.nodes.new("ShaderNodeTexImage")
        texture.image = image
        texture.interpolation = node.interpolation
        texture.location = node.location
        # One bake pixel is one exemplar pixel: the UV is scaled so that the texture keeps the
        # original image's texel size, and the bake repeats every resolution / width of UV.
        scaling = tree.nodes.new("ShaderNodeVectorMath")
        scaling.operation = "MULTIPLY"
        width, height = node.image.size
        scaling.inputs[1].default_value = (width / self.resolution, height / self.resolution, 1.0)
        scaling.location = (node.location.x - 200.0, node.location.y)
        tree.links.new(scaling.outputs[0], texture.inputs["Vector"])
        node.location.y += 320.0
        rewire(tree, node, texture.outputs["Color"], scaling.inputs[0])
        return texture


class NODE_PT_stochtex(bpy.types.Panel):
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "Stochtex"
    bl_label = "stochtex"

    @classmethod
    def poll(cls, context):
        return context.space_data.tree_type == "ShaderNodeTree"

    def draw(self, context):
        node = active_image_node(context)[1]
        if node is None:
            self.layout.label(text="Select an Image Texture node")
        else:
            self.layout.label(text="%s (%s)" % (node.image.name,
                                                 node.image.colorspace_settings.name))
        self.layout.operator(NODE_OT_stochtex_analyse.bl_idname)


def menu_entry(self, context):
    if context.space_data.tree_type == "ShaderNodeTree":
        self.layout.operator(NODE_OT_stochtex_analyse.bl_idname)


CLASSES = (StochtexPreferences, NODE_OT_stochtex_analyse, NODE_PT_stochtex)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.NODE_MT_node.append(menu_entry)


def unregister():
    bpy.types.NODE_MT_node.remove(menu_entry)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
