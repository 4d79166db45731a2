"""The tiling method's patch offsets, drawn as stochtex draws them, as a table for the node group.

Blender's shader nodes compute in float32 and have no integer multiply or bit operations, so the
node group cannot run stochtex's hash (pcg4d and pcg_hash on uint32, src/core/hash.hpp). It reads
each lattice vertex's offset from this table instead: the offsets of vertices (i, j) for
-size/2 <= i, j < size/2, drawn here by the same uint32 arithmetic as vertex_offset
(src/methods/tiling/evaluate.hpp), so within that range of vertices the node group places every
patch where `stochtex render` does. Beyond it, the table repeats: the offsets repeat every `size`
lattice vertices along each lattice axis (size x edge exemplar pixels).
"""

import numpy

_U32 = numpy.uint32
STREAM_OFFSETS = 0x85EBCA6B  # Stream::offsets


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


def vertex_offsets(size, seed, width, height):
    """(offset_x, offset_y), each size x size float32 indexed [row j][column i] for the table
    entry (i, j): vertex (i, j) for i, j < size / 2, else (i - size, j - size) (the vertices
    whose indices wrap onto the entry)."""
    entries = numpy.arange(size, dtype=numpy.int64)
    vertices = numpy.where(entries < size // 2, entries, entries - size)
    vertex_y, vertex_x = numpy.meshgrid(vertices, vertices, indexing="ij")
    key = cell_key(vertex_x, vertex_y, seed, STREAM_OFFSETS)
    # CounterRng: draw n is pcg_hash(key ^ pcg_hash(n)); floor(draw * side / 2^32).
    draws = [pcg_hash(key ^ pcg_hash(numpy.full_like(key, n))) for n in (0, 1)]
    return tuple(((draw.astype(numpy.uint64) * numpy.uint64(side)) >> numpy.uint64(32)).astype(
        numpy.float32) for draw, side in zip(draws, (width, height)))
