"""Renders of any size as dask arrays (docs/python.md): every chunk is one Model.render call with
the chunk's offset, so the assembled array is bit for bit the single render of the whole grid,
whatever the chunking, the workers or the machines that compute it."""

import dask.array
import numpy
from dask.array.core import normalize_chunks
from dask.base import tokenize
from dask.highlevelgraph import HighLevelGraph

from ._stochtex import Model


def _render_chunk(model, width, height, origin, scale, seed, threads, x0, y0):
    return model.render(width, height, origin=origin, scale=scale, seed=seed, threads=threads,
                        offset=(x0, y0))


def render(model, shape, chunks, origin=(0, 0), scale=1.0, seed=0, threads=1):
    """The (height, width) grid of Model.render as a lazy float32 dask array of
    height x width x channels, computed chunk by chunk.

    shape: (height, width), or (height, width, channels) with the model's channel count.
    chunks: dask chunks of the first two axes, e.g. 1024 or (1024, 2048); the channels are never
    split. threads: render threads per chunk (1 suits a cluster of single-threaded workers).
    The model is one node of the graph, sent pickled once to each worker that needs it."""
    if not isinstance(model, Model):
        raise TypeError("model must be a stochtex.Model, not " + type(model).__name__)
    shape = tuple(int(side) for side in shape)
    channels = model.channels
    if len(shape) == 3:
        if shape[2] != channels:
            raise ValueError(f"shape has {shape[2]} channels but the model has {channels}")
        shape = shape[:2]
    if len(shape) != 2 or min(shape) < 1:
        raise ValueError("shape must be (height, width) or (height, width, channels), sides >= 1")
    if isinstance(chunks, (int, numpy.integer)):
        chunks = (chunks, chunks)
    chunks = normalize_chunks(tuple(chunks)[:2] + (channels,), shape + (channels,),
                              dtype=numpy.float32)
    origin = (float(origin[0]), float(origin[1]))
    token = tokenize(model.__getstate__(), shape, chunks, origin, scale, seed)
    name = "stochtex-render-" + token
    model_key = "stochtex-model-" + token
    layer = {model_key: model}
    y0 = 0
    for i, height in enumerate(chunks[0]):
        x0 = 0
        for j, width in enumerate(chunks[1]):
            layer[(name, i, j, 0)] = (_render_chunk, model_key, width, height, origin,
                                      float(scale), int(seed), int(threads), x0, y0)
            x0 += width
        y0 += height
    graph = HighLevelGraph.from_collections(name, layer, dependencies=())
    return dask.array.Array(graph, name, chunks, dtype=numpy.float32)
