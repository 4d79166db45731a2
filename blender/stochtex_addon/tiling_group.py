"""A node group that evaluates a stochtex tiling model from Blender's native shader nodes.

It is the fast variant of `stochtex export-shader` (src/methods/tiling/hardware.glsl and
evaluate.glsl, read there for each step) written in math and Image Texture nodes, so that it runs
in EEVEE and Cycles on any device (tested: Cycles on the CPU, EEVEE on Mesa's llvmpipe):

1. p = (u W, (1 - v) H) Scale: the group's Vector (a UV) in exemplar pixels, with the image's
   orientation (UV (0, 1) is the exemplar's top-left pixel, as the Image Texture node shows it).
2. The triangle lattice (tiling_lattice_at, tiling_patches): p in skewed units of the edge, its
   cell, the three vertices of its triangle and their barycentric weights.
3. Each vertex's patch offset from the offsets table (offsets.py: stochtex's own draws within
   256 x 256 vertices around the origin; Blender's float nodes cannot run its uint32 hash), then
   the Gaussianised exemplar `tiling_exemplar.png` at wrap(p) + offset, bilinear and periodic.
4. The variance-preserving blend of eq. (13) around the blend mean.
5. T^-1 of level 0 (tiling_inverse_at_level): eq. (22) with the Abramowitz-Stegun erf of
   evaluate.glsl, then the 3-D table of `tiling_lut` (its first 32 slices), trilinear.

Every image read is a closest read (bilinear and trilinear are blended by hand): EEVEE mip-maps an
image read with linear interpolation by the screen derivatives of its coordinates, which jump where
the patches change (the triangle edges) and in the table's coordinates, and the reads there took a
coarse level (measured: lines of error up to 0.14 along the edges). So the group point-samples as
Cycles does, in both engines, and the samples per pixel (Cycles' samples, EEVEE's render samples)
average it into the filtered texture; zoomed far out a render of few samples aliases. The fast
variant's derivatives (the patches' mip level, T^-1's prefiltered levels) have no counterpart in
Blender's shader nodes, which give no screen derivatives.

The group's output is the model's render: linear light for a model of sRGB or linear colour
(scene-linear Rec. 709 in Blender), the values as they are for a model of data.
"""

import os
import re

import bpy
import numpy

from . import offsets

# The export's constants the group uses (tiling_glsl() in src/methods/tiling/gl_data.cpp).
_CONSTANTS = ("TILING_CHANNELS", "TILING_WIDTH", "TILING_HEIGHT", "TILING_EDGE",
              "TILING_TRANSFORMED", "TILING_SHARPNESS", "TILING_BLEND", "TILING_BLEND_MEAN",
              "TILING_LEVELS", "TILING_COLOUR_LUT", "TILING_LUT_SIZE",
              "TILING_TEXTURE_SCALE", "TILING_GAUSSIAN_MEAN", "TILING_ERF_SCALE",
              "TILING_INVERSE_SQRT3")
OFFSET_TABLE_SIZE = 256


class Unsupported(Exception):
    """A tiling model the node group does not evaluate (the operator bakes those instead)."""


def _glsl_value(text):
    if text in ("true", "false"):
        return text == "true"
    vector = re.fullmatch(r"vec4\((.*)\)", text)
    if vector:
        return tuple(float(x) for x in vector.group(1).split(","))
    try:
        return int(text.rstrip("u"), 0)
    except ValueError:
        return float(text)


def read_constants(glsl):
    """The model's constants from the fast export's `stochtex_tiling.glsl`."""
    found = {}
    for name in _CONSTANTS:
        match = re.search(r"^const \w+ %s = ([^;]+);" % name, glsl, re.MULTILINE)
        if not match:
            raise Unsupported("the export has no %s" % name)
        found[name] = _glsl_value(match.group(1).strip())
    return found


def check_supported(constants, texture_names):
    """The export's data files by name (`tiling_exemplar`, `tiling_lut`: a 16-bit PNG, or a
    float OpenEXR where a table's values leave [0, 1]); raises Unsupported, one sentence, for what
    the group does not evaluate."""
    if constants["TILING_CHANNELS"] != 3 or not constants["TILING_COLOUR_LUT"]:
        raise Unsupported("the node group evaluates colour (RGB) models with the 3-D table "
                          "(the default sliced transport)")
    if constants["TILING_BLEND"] != 0:
        raise Unsupported("the node group evaluates the histogram blend only")
    if constants["TILING_TRANSFORMED"] or constants["TILING_SHARPNESS"] != 1.0:
        raise Unsupported("the node group has no artist controls (rotation, scale jitter, "
                          "sharpness)")
    files = {os.path.splitext(name)[0]: name for name in texture_names}
    if sorted(files) != ["tiling_exemplar", "tiling_lut"]:
        raise Unsupported("the export's data files are not the two the node group reads")
    return files


class _Builder:
    """Creates nodes in `tree`; each input is given a socket (linked) or a constant."""

    def __init__(self, tree):
        self.tree = tree

    def node(self, kind, inputs=(), **properties):
        """A node of `kind` with `properties`; `inputs` pairs an input (index or identifier)
        with its value."""
        node = self.tree.nodes.new(kind)
        for name, value in properties.items():
            setattr(node, name, value)
        by_identifier = {socket.identifier: socket for socket in node.inputs}
        for key, value in inputs:
            socket = node.inputs[key] if isinstance(key, int) else by_identifier[key]
            if isinstance(value, bpy.types.NodeSocket):
                self.tree.links.new(value, socket)
            else:
                socket.default_value = value
        return node

    def math(self, operation, *values):
        return self.node("ShaderNodeMath", enumerate(values), operation=operation).outputs[0]

    def vector_math(self, operation, *values):
        return self.node("ShaderNodeVectorMath", enumerate(values),
                         operation=operation).outputs[0]

    def scale(self, vector, factor):
        return self.node("ShaderNodeVectorMath", [(0, vector), (3, factor)],
                         operation="SCALE").outputs[0]

    def combine(self, x, y, z=0.0):
        return self.node("ShaderNodeCombineXYZ", enumerate((x, y, z))).outputs[0]

    def separate(self, vector):
        return tuple(self.node("ShaderNodeSeparateXYZ", [(0, vector)]).outputs)

    def image(self, image, vector, interpolation, extension):
        return self.node("ShaderNodeTexImage", [(0, vector)], image=image,
                         interpolation=interpolation, extension=extension).outputs["Color"]

    def mix(self, factor, a, b):
        node = self.node("ShaderNodeMix", [("Factor_Float", factor), ("A_Color", a),
                                           ("B_Color", b)], data_type="RGBA", clamp_factor=False)
        return next(s for s in node.outputs if s.identifier == "Result_Color")

    def lay_out(self):
        """Columns by the longest path from the group's inputs, so the graph reads left to
        right."""
        feeding = {node.name: [] for node in self.tree.nodes}
        for link in self.tree.links:
            feeding[link.to_node.name].append(link.from_node)
        column = {}

        def depth(node):
            if node.name not in column:
                column[node.name] = 1 + max((depth(n) for n in feeding[node.name]), default=-1)
            return column[node.name]

        rows = {}
        for node in self.tree.nodes:
            x = depth(node)
            node.location = (x * 220.0, -rows.get(x, 0) * 200.0)
            rows[x] = rows.get(x, 0) + 1


def _erf(build, x):
    """Abramowitz & Stegun 7.1.26, as tiling_erf in evaluate.glsl (to 1.5e-7)."""
    t = build.math("DIVIDE", 1.0,
                   build.math("MULTIPLY_ADD", build.math("ABSOLUTE", x), 0.3275911, 1.0))
    poly = build.math("MULTIPLY_ADD", t, 1.061405429, -1.453152027)
    for coefficient in (1.421413741, -0.284496736, 0.254829592):
        poly = build.math("MULTIPLY_ADD", poly, t, coefficient)
    poly = build.math("MULTIPLY", poly, t)
    gaussian = build.math("EXPONENT", build.math("MULTIPLY", build.math("MULTIPLY", x, x), -1.0))
    magnitude = build.math("SUBTRACT", 1.0, build.math("MULTIPLY", poly, gaussian))
    return build.math("MULTIPLY", build.math("SIGN", x), magnitude)


def _bilinear(build, image, x, y, width, height):
    """The periodic bilinear read of `image` at (x, y) exemplar pixels (fetch_bilinear: texel i
    covers [i, i + 1)), from 4 closest reads."""
    # Texel centres at i + 1/2: the corner texel and the fraction past its centre.
    x, y = build.math("SUBTRACT", x, 0.5), build.math("SUBTRACT", y, 0.5)
    corner_x, corner_y = build.math("FLOOR", x), build.math("FLOOR", y)
    fraction_x = build.math("SUBTRACT", x, corner_x)
    fraction_y = build.math("SUBTRACT", y, corner_y)
    corner = build.combine(build.math("DIVIDE", build.math("ADD", corner_x, 0.5), width),
                           build.math("SUBTRACT", 1.0, build.math(
                               "DIVIDE", build.math("ADD", corner_y, 0.5), height)))
    taps = [[build.image(image, build.vector_math("ADD", corner, (dx / width, -dy / height, 0.0)),
                         "Closest", "REPEAT") for dx in (0, 1)] for dy in (0, 1)]
    return build.mix(fraction_y, build.mix(fraction_x, *taps[0]), build.mix(fraction_x, *taps[1]))


def offsets_image(name, seed, width, height):
    """The offsets table (offsets.py) as a float image: pixel (i, j) (j from the bottom, as
    Blender stores rows) holds entry (i, j)'s offset in exemplar pixels in red and green."""
    size = OFFSET_TABLE_SIZE
    offset_x, offset_y = offsets.vertex_offsets(size, seed, width, height)
    image = bpy.data.images.new(name, size, size, alpha=False, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    pixels = numpy.zeros((size, size, 4), numpy.float32)
    pixels[..., 0] = offset_x
    pixels[..., 1] = offset_y
    pixels[..., 3] = 1.0
    image.pixels.foreach_set(pixels.ravel())
    image.pack()  # a generated image lives in the .blend only when packed (as OpenEXR)
    return image


def build_group(name, constants, exemplar, lut, offset_table):
    """The node group: inputs Vector (a UV) and Scale (as a Mapping node's scale on the Image
    Texture: 2 shows the texture's features half as large), output Color. `exemplar`, `lut` and
    `offset_table` are the export's images and the offsets table, as Non-Color data."""
    c = constants
    width, height = float(c["TILING_WIDTH"]), float(c["TILING_HEIGHT"])
    edge = c["TILING_EDGE"]
    inverse_sqrt3 = c["TILING_INVERSE_SQRT3"]
    cells = c["TILING_LUT_SIZE"]
    table = float(OFFSET_TABLE_SIZE)

    tree = bpy.data.node_groups.new(name, "ShaderNodeTree")
    tree.inputs.new("NodeSocketVector", "Vector")
    scale_input = tree.inputs.new("NodeSocketFloat", "Scale")
    scale_input.default_value = 1.0
    scale_input.min_value = 1e-6
    tree.outputs.new("NodeSocketColor", "Color")
    build = _Builder(tree)
    group_input = build.node("NodeGroupInput")
    vector, scale = group_input.outputs["Vector"], group_input.outputs["Scale"]

    # 1. p in exemplar pixels.
    u, v, _ = build.separate(vector)
    px = build.math("MULTIPLY", build.math("MULTIPLY", u, width), scale)
    py = build.math("MULTIPLY", build.math("MULTIPLY", build.math("SUBTRACT", 1.0, v), height),
                    scale)
    # 2. The lattice: skewed coordinates, cell, the triangle's vertices and weights. k = 1 in the
    # upper triangle (f.x + f.y >= 1), whose vertices are (1, 1), (0, 1), (1, 0).
    sx = build.math("DIVIDE", build.math("MULTIPLY_ADD", py, -inverse_sqrt3, px), edge)
    sy = build.math("DIVIDE", build.math("MULTIPLY", py, 2.0 * inverse_sqrt3), edge)
    cx, cy = build.math("FLOOR", sx), build.math("FLOOR", sy)
    fx, fy = build.math("SUBTRACT", sx, cx), build.math("SUBTRACT", sy, cy)
    fsum = build.math("ADD", fx, fy)
    k = build.math("SUBTRACT", 1.0, build.math("LESS_THAN", fsum, 1.0))
    not_k = build.math("SUBTRACT", 1.0, k)
    vertices = [(k, k), (not_k, k), (k, not_k)]
    weights = [build.math("ABSOLUTE", build.math("SUBTRACT", 1.0, fsum)),
               build.math("ABSOLUTE", build.math("SUBTRACT", k, fx)),
               build.math("ABSOLUTE", build.math("SUBTRACT", k, fy))]
    # p modulo the exemplar's period (wrap_position), then each patch at wrap(p) + offset.
    wx = build.math("SUBTRACT", px, build.math("MULTIPLY", build.math(
        "FLOOR", build.math("DIVIDE", px, width)), width))
    wy = build.math("SUBTRACT", py, build.math("MULTIPLY", build.math(
        "FLOOR", build.math("DIVIDE", py, height)), height))
    # 3-4. The patches blended by eq. (13).
    texture_scale = c["TILING_TEXTURE_SCALE"]
    stored_offset = 0.5 - 0.5 * texture_scale  # the file holds (g - 1/2) / scale + 1/2
    blended = None
    weight_squares = None
    for (dx, dy), weight in zip(vertices, weights):
        vertex_x, vertex_y = build.math("ADD", cx, dx), build.math("ADD", cy, dy)
        entry = build.combine(build.math("DIVIDE", build.math("ADD", vertex_x, 0.5), table),
                              build.math("DIVIDE", build.math("ADD", vertex_y, 0.5), table))
        offset_x, offset_y, _ = build.separate(
            build.image(offset_table, entry, "Closest", "REPEAT"))
        stored = _bilinear(build, exemplar, build.math("ADD", wx, offset_x),
                           build.math("ADD", wy, offset_y), width, height)
        gaussian = build.vector_math("MULTIPLY_ADD", stored, (texture_scale,) * 3,
                                     (stored_offset,) * 3)
        term = build.scale(gaussian, weight)
        blended = term if blended is None else build.vector_math("ADD", blended, term)
        square = build.math("MULTIPLY", weight, weight)
        weight_squares = square if weight_squares is None else build.math(
            "ADD", weight_squares, square)
    mean = tuple(c["TILING_BLEND_MEAN"][:3])
    g = build.vector_math("ADD", build.scale(build.vector_math("SUBTRACT", blended, mean),
                                             build.math("INVERSE_SQRT", weight_squares)), mean)
    # 5. T^-1: each channel's table coordinate (eq. 22, tiling_table_coordinate), ...
    half = 0.5 * cells
    first, fraction = [], []
    for channel in build.separate(g):
        standard = build.math("MULTIPLY",
                              build.math("SUBTRACT", channel, c["TILING_GAUSSIAN_MEAN"]),
                              c["TILING_ERF_SCALE"])
        # x = (1/2 + erf / 2) cells - 1/2, clamped to [0, cells - 1].
        x = build.math("MULTIPLY_ADD", _erf(build, standard), half, half - 0.5)
        x = build.math("MINIMUM", build.math("MAXIMUM", x, 0.0), cells - 1.0)
        cell = build.math("MINIMUM", build.math("FLOOR", x), cells - 2.0)
        first.append(cell)
        fraction.append(build.math("SUBTRACT", x, cell))
    # ... then the 3-D table: column = red's cell, row = (blue's cell) cells + green's cell from
    # the top of the image (level 0's slices), 8 closest reads blended trilinearly.
    rows = float(cells * cells * c["TILING_LEVELS"])
    row = build.math("MULTIPLY_ADD", first[2], float(cells), first[1])
    corner = build.combine(
        build.math("DIVIDE", build.math("ADD", first[0], 0.5), float(cells)),
        build.math("SUBTRACT", 1.0, build.math("DIVIDE", build.math("ADD", row, 0.5), rows)))
    taps = {}
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                at = build.vector_math("ADD", corner,
                                       (dx / cells, -(dz * cells + dy) / rows, 0.0))
                taps[dx, dy, dz] = build.image(lut, at, "Closest", "EXTEND")
    along_y = {}
    for dz in (0, 1):
        along_x = [build.mix(fraction[0], taps[0, dy, dz], taps[1, dy, dz]) for dy in (0, 1)]
        along_y[dz] = build.mix(fraction[1], along_x[0], along_x[1])
    colour = build.mix(fraction[2], along_y[0], along_y[1])
    group_output = build.node("NodeGroupOutput", [(0, colour)])
    group_output.is_active_output = True
    build.lay_out()
    return tree
