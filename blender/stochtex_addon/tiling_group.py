"""A node group that evaluates a stochtex tiling model from Blender's native shader nodes.

It is the fast variant of `stochtex export-shader` (src/methods/tiling/hardware.glsl and
evaluate.glsl, read there for each step) written in math and Image Texture nodes, so that it runs
in EEVEE and Cycles on any device (tested: Cycles on the CPU, EEVEE on Mesa's llvmpipe):

1. p = (u W, (1 - v) H) Scale: the group's Vector (a UV) in exemplar pixels, with the image's
   orientation (UV (0, 1) is the exemplar's top-left pixel, as the Image Texture node shows it).
2. The triangle lattice (tiling_lattice_at, tiling_patches): p in skewed units of the edge, its
   cell, the three vertices of its triangle and their barycentric weights, sharpened when the
   model's sharpness is not 1 (sharpen_weights: the weights to that power, renormalised).
3. Each vertex's patch offset from the offsets table (offsets.py: stochtex's own draws within
   256 x 256 vertices around the origin; Blender's float nodes cannot run its uint32 hash), with
   rotation or scale jitter each patch's matrix from a second table drawn the same way and the
   patch moved by it about its vertex (patch_shift), then the exemplar `tiling_exemplar` at
   wrap(p) + offset, bilinear and periodic.
4. The variance-preserving blend of eq. (13) around the blend mean (the histogram blend's
   Gaussianised exemplar, or the variance blend's exemplar itself, which then is the result).
5. T^-1 of level 0 (tiling_inverse_at_level), histogram blend only: eq. (22) with the
   Abramowitz-Stegun erf of evaluate.glsl, then either the 3-D table of `tiling_lut` (its first
   32 slices), trilinear (the sliced transport of colour), or each channel's 1-D table of
   `tiling_tables`, linear, followed by the colour basis and mean (the pca transport of colour:
   its principal axes; a grey model: one table).

Every image read is a closest read (bilinear and trilinear are blended by hand): EEVEE mip-maps an
image read with linear interpolation by the screen derivatives of its coordinates, which jump where
the patches change (the triangle edges) and in the tables' coordinates, and the reads there took a
coarse level (measured: lines of error up to 0.14 along the edges). So the group point-samples as
Cycles does, in both engines, and the samples per pixel (Cycles' samples, EEVEE's render samples)
average it into the filtered texture; zoomed far out a render of few samples aliases. The fast
variant's derivatives (the patches' mip level, scale jitter's level per patch, T^-1's prefiltered
levels) have no counterpart in Blender's shader nodes, which give no screen derivatives.

The group's output is the model's render: linear light for a model of sRGB or linear colour
(scene-linear Rec. 709 in Blender; a srgb model whose tables hold encoded values, the pca transport
and the variance blend, is decoded after step 5 as the export does), the values as they are for a
model of data; a grey model's value in all three channels.
"""

import os
import re

import bpy
import numpy

from . import offsets

# The export's constants the group uses (tiling_glsl() in src/methods/tiling/gl_data.cpp).
_CONSTANTS = ("TILING_CHANNELS", "TILING_WIDTH", "TILING_HEIGHT", "TILING_EDGE",
              "TILING_ROTATION", "TILING_SCALE_JITTER", "TILING_SHARPNESS", "TILING_TRANSFORMED",
              "TILING_BLEND", "TILING_BLEND_MEAN", "TILING_LEVELS", "TILING_COLOUR_LUT",
              "TILING_HAS_ALPHA", "TILING_COLOUR_CHANNELS", "TILING_LUT_SIZE",
              "TILING_TABLE_SIZE", "TILING_COLOUR_BASIS", "TILING_COLOUR_MEAN",
              "TILING_LEVEL_TABLES", "TILING_TEXTURE_SCALE", "TILING_GAUSSIAN_MEAN",
              "TILING_ERF_SCALE", "TILING_INVERSE_SQRT3")
OFFSET_TABLE_SIZE = 256
HISTOGRAM_BLEND, VARIANCE_BLEND = 0, 1  # TILING_BLEND (kBlends, src/methods/tiling/params.hpp)


class Unsupported(Exception):
    """A tiling model the node group does not evaluate (the operator bakes those instead)."""


def _glsl_value(text):
    if text in ("true", "false"):
        return text == "true"
    listed = re.fullmatch(r"(?:b?vec4|float\[\]|int\[\])\((.*)\)", text)
    if listed:
        return tuple(_glsl_value(x.strip()) for x in listed.group(1).split(","))
    try:
        return int(text.rstrip("u"), 0)
    except ValueError:
        return float(text)


def read_constants(glsl):
    """The model's constants from the fast export's `stochtex_tiling.glsl` (arrays as tuples),
    and STOCHTEX_DECODE: the channels decoded from sRGB after evaluation (a srgb model whose
    tables hold its encoded values, docs/design.md §14), none where the export has no decoding."""
    found = {}
    for name in _CONSTANTS + ("STOCHTEX_DECODE",):
        match = re.search(r"^const \w+ %s(?:\[\d+\])? = ([^;]+);" % name, glsl, re.MULTILINE)
        if match:
            found[name] = _glsl_value(match.group(1).strip())
        elif name == "STOCHTEX_DECODE":
            found[name] = (False,) * 4
        else:
            raise Unsupported("the export has no %s" % name)
    return found


def check_supported(constants, texture_names):
    """The export's data files by name: `tiling_exemplar`, and for the histogram blend T^-1's
    `tiling_lut` (a 16-bit PNG, or a float OpenEXR where a table's values leave [0, 1]) or
    `tiling_tables` (OpenEXR); the decoding's `decoded` and `removed`, which the group does not
    read (it decodes point samples, exactly). Raises Unsupported, one sentence, for what the
    group does not evaluate."""
    c = constants
    if c["TILING_CHANNELS"] not in (1, 3) or c["TILING_HAS_ALPHA"]:
        raise Unsupported("the node group evaluates grey and colour (RGB) models, without alpha")
    if c["TILING_BLEND"] not in (HISTOGRAM_BLEND, VARIANCE_BLEND):
        raise Unsupported("the node group evaluates the histogram and variance blends, not the "
                          "linear one")
    expected = ["tiling_exemplar"]
    if c["TILING_BLEND"] == HISTOGRAM_BLEND:
        expected.append("tiling_lut" if c["TILING_COLOUR_LUT"] else "tiling_tables")
    if any(c["STOCHTEX_DECODE"]):
        expected += ["decoded", "removed"]
    files = {os.path.splitext(name)[0]: name for name in texture_names}
    if sorted(files) != sorted(expected):
        raise Unsupported("the export's data files are not the ones the node group reads")
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

    def dot(self, a, b):
        return self.node("ShaderNodeVectorMath", [(0, a), (1, b)],
                         operation="DOT_PRODUCT").outputs["Value"]

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


def _float_image(name, red, green):
    """A float image of Non-Color data, packed (a generated image lives in the .blend only when
    packed, as OpenEXR): pixel (i, j), j from the bottom as Blender stores rows, holds red[j][i]
    and green[j][i]."""
    height, width = red.shape
    image = bpy.data.images.new(name, width, height, alpha=False, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    pixels = numpy.zeros((height, width, 4), numpy.float32)
    pixels[..., 0] = red
    pixels[..., 1] = green
    pixels[..., 3] = 1.0
    image.pixels.foreach_set(pixels.ravel())
    image.pack()
    return image


def offsets_image(name, seed, width, height):
    """The offsets table (offsets.py): entry (i, j) holds its vertex's patch offset in exemplar
    pixels."""
    return _float_image(name, *offsets.vertex_offsets(OFFSET_TABLE_SIZE, seed, width, height))


def transforms_image(name, seed, constants):
    """The artist controls' table (offsets.py), for a model with rotation or scale jitter: entry
    (i, j) holds its vertex's patch matrix [[c, -s], [s, c]] as c and s."""
    return _float_image(name, *offsets.vertex_transforms(
        OFFSET_TABLE_SIZE, seed, constants["TILING_ROTATION"], constants["TILING_SCALE_JITTER"]))


def tables_image(name, path, constants):
    """The 1-D tables of T^-1 of level 0 from the export's `tiling_tables.exr` (one float array,
    4 floats a texel, 1024 texels a row from the top: pack_rgba in src/gl/glsl_text.hpp), for
    closest reads: row c holds channel c's table, texel i its entries i and i + 1 (the two ends
    of cell i's linear interpolation)."""
    packed = bpy.data.images.load(path, check_existing=False)
    packed.colorspace_settings.name = "Non-Color"
    width, height = packed.size
    values = numpy.empty(width * height * 4, numpy.float32)
    packed.pixels.foreach_get(values)
    bpy.data.images.remove(packed)
    values = values.reshape(height, width * 4)[::-1].ravel()
    size, count = constants["TILING_TABLE_SIZE"], constants["TILING_COLOUR_CHANNELS"]
    first = constants["TILING_LEVEL_TABLES"][0]
    tables = values[first:first + count * size].reshape(count, size)
    return _float_image(name, tables, numpy.concatenate((tables[:, 1:], tables[:, -1:]), axis=1))


def _table_coordinate(build, constants, g, cells):
    """tiling_table_coordinate: the cell and fraction of g in a table of `cells` entries, eq. (22)
    with the Abramowitz-Stegun erf."""
    c = constants
    standard = build.math("MULTIPLY", build.math("SUBTRACT", g, c["TILING_GAUSSIAN_MEAN"]),
                          c["TILING_ERF_SCALE"])
    # x = (1/2 + erf / 2) cells - 1/2, clamped to [0, cells - 1].
    half = 0.5 * cells
    x = build.math("MULTIPLY_ADD", _erf(build, standard), half, half - 0.5)
    x = build.math("MINIMUM", build.math("MAXIMUM", x, 0.0), cells - 1.0)
    cell = build.math("MINIMUM", build.math("FLOOR", x), cells - 2.0)
    return cell, build.math("SUBTRACT", x, cell)


def _inverse_lut(build, constants, g, lut):
    """T^-1 through the 3-D table (the sliced transport): column = red's cell, row = (blue's cell)
    cells + green's cell from the top of the image (level 0's slices), 8 closest reads blended
    trilinearly."""
    cells = constants["TILING_LUT_SIZE"]
    first, fraction = zip(*(_table_coordinate(build, constants, channel, cells)
                            for channel in build.separate(g)))
    rows = float(cells * cells * constants["TILING_LEVELS"])
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
    return build.mix(fraction[2], along_y[0], along_y[1])


def _inverse_tables(build, constants, g, tables):
    """T^-1 through each channel's 1-D table (a closest read of its cell's two entries, then
    linear), then the colour basis and mean: the principal axes of the pca transport, a grey
    model's 1 x 1 identity."""
    c = constants
    size, count = c["TILING_TABLE_SIZE"], c["TILING_COLOUR_CHANNELS"]
    decorrelated = []
    for channel, value in enumerate(build.separate(g)[:count]):
        cell, fraction = _table_coordinate(build, c, value, size)
        at = build.combine(build.math("DIVIDE", build.math("ADD", cell, 0.5), float(size)),
                           (channel + 0.5) / count)
        low, high, _ = build.separate(build.image(tables, at, "Closest", "EXTEND"))
        decorrelated.append(build.math("MULTIPLY_ADD", fraction,
                                       build.math("SUBTRACT", high, low), low))
    basis, mean = c["TILING_COLOUR_BASIS"], c["TILING_COLOUR_MEAN"]
    if count == 1:
        grey = build.math("MULTIPLY_ADD", decorrelated[0], basis[0], mean[0])
        return build.combine(grey, grey, grey)
    axes = build.combine(*decorrelated)
    return build.combine(*(build.math("ADD", build.dot(axes, basis[3 * row:3 * row + 3]),
                                      mean[row]) for row in range(3)))


def _srgb_decode(build, v):
    """stochtex_srgb_decode: v / 12.92 up to 0.04045, else ((v + 0.055) / 1.055)^2.4."""
    linear = build.math("MULTIPLY", v, 1.0 / 12.92)
    curve = build.math("POWER", build.math("MULTIPLY", build.math("ADD", v, 0.055), 1.0 / 1.055),
                       2.4)
    on_curve = build.math("GREATER_THAN", v, 0.04045)
    return build.math("MULTIPLY_ADD", on_curve, build.math("SUBTRACT", curve, linear), linear)


def build_group(name, constants, images):
    """The node group: inputs Vector (a UV) and Scale (as a Mapping node's scale on the Image
    Texture: 2 shows the texture's features half as large), output Color. `images` holds the
    export's images and the tables made here by name, Non-Color data: "exemplar", "offsets",
    "transforms" (rotation or scale jitter), and T^-1's "lut" or "tables" (histogram blend)."""
    c = constants
    width, height = float(c["TILING_WIDTH"]), float(c["TILING_HEIGHT"])
    edge = c["TILING_EDGE"]
    inverse_sqrt3 = c["TILING_INVERSE_SQRT3"]
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
    if c["TILING_SHARPNESS"] != 1.0:
        powered = [build.math("POWER", weight, c["TILING_SHARPNESS"]) for weight in weights]
        total = build.math("ADD", build.math("ADD", powered[0], powered[1]), powered[2])
        weights = [build.math("DIVIDE", weight, total) for weight in powered]
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
            build.image(images["offsets"], entry, "Closest", "REPEAT"))
        x, y = build.math("ADD", wx, offset_x), build.math("ADD", wy, offset_y)
        if c["TILING_TRANSFORMED"]:
            # patch_shift: M (p - vertex) - (p - vertex), p - vertex from the skewed units.
            cosine, sine, _ = build.separate(
                build.image(images["transforms"], entry, "Closest", "REPEAT"))
            from_x, from_y = build.math("SUBTRACT", fx, dx), build.math("SUBTRACT", fy, dy)
            local_x = build.math("MULTIPLY", build.math("MULTIPLY_ADD", from_y, 0.5, from_x),
                                 edge)
            local_y = build.math("MULTIPLY", from_y, edge * 1.5 * inverse_sqrt3)
            cosine = build.math("SUBTRACT", cosine, 1.0)
            x = build.math("ADD", x, build.math("SUBTRACT", build.math("MULTIPLY", cosine, local_x),
                                                build.math("MULTIPLY", sine, local_y)))
            y = build.math("ADD", y, build.math("ADD", build.math("MULTIPLY", sine, local_x),
                                                build.math("MULTIPLY", cosine, local_y)))
        stored = _bilinear(build, images["exemplar"], x, y, width, height)
        gaussian = build.vector_math("MULTIPLY_ADD", stored, (texture_scale,) * 3,
                                     (stored_offset,) * 3)
        term = build.scale(gaussian, weight)
        blended = term if blended is None else build.vector_math("ADD", blended, term)
        square = build.math("MULTIPLY", weight, weight)
        weight_squares = square if weight_squares is None else build.math(
            "ADD", weight_squares, square)
    # A grey exemplar reads as (v, v, v): its mean in every channel.
    mean = tuple(c["TILING_BLEND_MEAN"][:3]) if c["TILING_CHANNELS"] == 3 else (
        c["TILING_BLEND_MEAN"][0],) * 3
    colour = build.vector_math("ADD", build.scale(build.vector_math("SUBTRACT", blended, mean),
                                                  build.math("INVERSE_SQRT", weight_squares)),
                               mean)
    # 5. T^-1 (tiling_inverse): the identity for the variance blend.
    if c["TILING_BLEND"] == HISTOGRAM_BLEND:
        colour = (_inverse_lut(build, c, colour, images["lut"]) if c["TILING_COLOUR_LUT"] else
                  _inverse_tables(build, c, colour, images["tables"]))
    # Linear light from sRGB-encoded values (stochtex_linear_light): a point sample's, decoded
    # exactly (a grey model's one value is in every channel).
    decode = c["STOCHTEX_DECODE"][:3] if c["TILING_CHANNELS"] == 3 else (
        c["STOCHTEX_DECODE"][0],) * 3
    if any(decode):
        colour = build.combine(*(_srgb_decode(build, value) if decoded else value
                                 for value, decoded in zip(build.separate(colour), decode)))
    group_output = build.node("NodeGroupOutput", [(0, colour)])
    group_output.is_active_output = True
    build.lay_out()
    return tree
