"""The tiling method's patch offsets, drawn as stochtex draws them, as a table for the node group.

Blender's shader nodes compute in float32 and have no integer multiply or bit operations, so the
node group cannot run stochtex's hash (pcg4d and pcg_hash on uint32, src/core/hash.hpp). It reads
each lattice vertex's offset from this table instead: the offsets of vertices (i, j) for
-size/2 <= i, j < size/2, drawn here by the same uint32 arithmetic as vertex_offset
(src/methods/tiling/evaluate.hpp), so within that range of vertices the node group places every
patch where `stochtex render` does. Beyond it, the table repeats: the offsets repeat every `size`
lattice vertices along each lattice axis (size x edge exemplar pixels). The artist controls'
rotation and scale jitter of each patch (patch_transform) come from a table drawn the same way.
"""

import numpy

_U32 = numpy.uint32
STREAM_OFFSETS = 0x85EBCA6B  # Stream::offsets
STREAM_TRANSFORMS = 0x27D4EB2F  # Stream::transforms


def pcg_hash(value):
    state = value * _U32(747796405) + _U32(2891336453)
    word = ((state >> ((state >> _U32(28)) + _U32(4))) ^ state) * _U32(277803737)
    return (word >> _U32(22)) ^ word


def pcg4d(x, y, z, w):
    v = [numpy.asarray(a, dtype=_U32) * _U32(1664525) + _U32(1013904223) for a in (x, y, z, w)]
    for round_ in range(2):
        if round_:
            v = [a ^ (a >> _U32(16)) for a in v]
        v[0] = v[0] + v[1] * v[3]
        v[1] = v[1] + v[2] * v[0]
        v[2] = v[2] + v[0] * v[1]
        v[3] = v[3] + v[1] * v[2]
    return v


def cell_key(x, y, seed, stream):
    """cell_key of int64 vertex coordinates (their low 32 bits, two's complement)."""
    x = numpy.asarray(x, dtype=numpy.int64).astype(_U32)
    y = numpy.asarray(y, dtype=numpy.int64).astype(_U32)
    return pcg4d(x, y, numpy.full_like(x, seed), numpy.full_like(x, stream))[0]


def _table_keys(size, seed, stream):
    """cell_key of the vertex of each table entry (i, j), size x size indexed [row j][column i]:
    vertex (i, j) for i, j < size / 2, else (i - size, j - size) (the vertices whose indices wrap
    onto the entry)."""
    entries = numpy.arange(size, dtype=numpy.int64)
    vertices = numpy.where(entries < size // 2, entries, entries - size)
    vertex_y, vertex_x = numpy.meshgrid(vertices, vertices, indexing="ij")
    return cell_key(vertex_x, vertex_y, seed, stream)


def _draw(key, n):
    """CounterRng's draw n: pcg_hash(key ^ pcg_hash(n))."""
    return pcg_hash(key ^ pcg_hash(numpy.full_like(key, n)))


def vertex_offsets(size, seed, width, height):
    """(offset_x, offset_y), each size x size float32 for the table entries of _table_keys: the
    patch offsets of vertex_offset, floor(draw * side / 2^32)."""
    key = _table_keys(size, seed, STREAM_OFFSETS)
    return tuple(((_draw(key, n).astype(numpy.uint64) * numpy.uint64(side)) >> numpy.uint64(32))
                 .astype(numpy.float32) for n, side in ((0, width), (1, height)))


def vertex_transforms(size, seed, max_angle, jitter):
    """(c, s), each size x size float32 for the table entries of _table_keys: each patch's
    matrix M = [[c, -s], [s, c]] of patch_transform (src/methods/tiling/evaluate.hpp), in
    float32 as there: an angle uniform in [-max_angle, max_angle] radians and a scale
    2^(jitter u), u uniform in [-1, 1], each from a draw's top 24 bits."""
    key = _table_keys(size, seed, STREAM_TRANSFORMS)
    angle_draw, scale_draw = ((_draw(key, n) >> _U32(8)).astype(numpy.float32) *
                              numpy.float32(1.0 / 16777216.0) for n in (0, 1))
    one, two = numpy.float32(1.0), numpy.float32(2.0)
    angle = numpy.float32(max_angle) * (two * angle_draw - one)
    scale = numpy.exp2(numpy.float32(jitter) * (two * scale_draw - one))
    return scale * numpy.cos(angle), scale * numpy.sin(angle)
