"""Renders of any size as dask arrays (docs/python.md): every chunk is one Model.render call with
the chunk's offset, so the assembled array is bit for bit the single render of the whole grid,
whatever the chunking, the workers or the machines that compute it."""

import operator

import dask.array
import numpy
from dask.array.core import normalize_chunks
from dask.base import tokenize
from dask.highlevelgraph import HighLevelGraph

from ._stochtex import Model


def _render_chunk(model, width, height, origin, scale, seed, threads, x0, y0, periodic):
    return model.render(width, height, origin=origin, scale=scale, seed=seed, threads=threads,
                        offset=(x0, y0), periodic=periodic)


def _render_maps_chunk(model, width, height, origin, scale, seed, threads, x0, y0, periodic):
    return model.render_maps(width, height, origin=origin, scale=scale, seed=seed,
                             threads=threads, offset=(x0, y0), periodic=periodic)


def _checked(model, shape, chunks, channels=None):
    """The (height, width) of `shape` and the dask chunks of a render of `channels` channels (the
    model's when None; a shape of 3 sides must name them)."""
    if not isinstance(model, Model):
        raise TypeError("model must be a stochtex.Model, not " + type(model).__name__)
    shape = tuple(int(side) for side in shape)
    if channels is None:
        channels = model.channels
        if len(shape) == 3:
            if shape[2] != channels:
                raise ValueError(f"shape has {shape[2]} channels but the model has {channels}")
            shape = shape[:2]
    if len(shape) != 2 or min(shape) < 1:
        raise ValueError("shape must be (height, width) or (height, width, channels), sides >= 1")
    if isinstance(chunks, (int, numpy.integer)):
        chunks = (chunks, chunks)
    return shape, normalize_chunks(tuple(chunks)[:2] + (channels,), shape + (channels,),
                                   dtype=numpy.float32)


def _check_arguments(function, origin, scale, seed, threads, periodic=False):
    """Refuses, as the graph is built, what every chunk would refuse when computed: `function`
    (Model.render or Model.render_maps) of one pixel checks the origin, scale, seed, threads and
    periodic (a model that cannot be periodic) by the rules of a whole render."""
    function(1, 1, origin=origin, scale=scale, seed=seed, threads=threads, periodic=periodic)


def _periodic(periodic, shape):
    """Each chunk's periodic argument: the whole grid's (width, height) for a tileable bake."""
    return (shape[1], shape[0]) if periodic else False


def _chunk_layer(name, function, model, token, chunks, origin, scale, seed, threads,
                 periodic=False):
    """The graph layer `name` of one `function` call per chunk of the first two axes, keyed
    (name, i, j, 0), with the model as one node of its own."""
    model_key = "stochtex-model-" + token
    layer = {model_key: model}
    origin = (float(origin[0]), float(origin[1]))
    y0 = 0
    for i, height in enumerate(chunks[0]):
        x0 = 0
        for j, width in enumerate(chunks[1]):
            layer[(name, i, j, 0)] = (function, model_key, width, height, origin, float(scale),
                                      int(seed), int(threads), x0, y0, periodic)
            x0 += width
        y0 += height
    return layer


def render(model, shape, chunks, origin=(0, 0), scale=1.0, seed=0, threads=1, periodic=False):
    """The (height, width) grid of Model.render as a lazy float32 dask array of
    height x width x channels, computed chunk by chunk.

    shape: (height, width), or (height, width, channels) with the model's channel count.
    chunks: dask chunks of the first two axes, e.g. 1024 or (1024, 2048); the channels are never
    split. threads: render threads per chunk (1 suits a cluster of single-threaded workers).
    The model is one node of the graph, sent pickled once to each worker that needs it.
    periodic=True: a tileable bake, the texture repeats with the whole (height, width) grid
    (Model.render's periodic, docs/render.md)."""
    shape, chunks = _checked(model, shape, chunks)
    _check_arguments(model.render, origin, scale, seed, threads, bool(periodic))
    token = tokenize(model.__getstate__(), shape, chunks, origin, scale, seed, bool(periodic))
    name = "stochtex-render-" + token
    layer = _chunk_layer(name, _render_chunk, model, token, chunks, origin, scale, seed, threads,
                         _periodic(periodic, shape))
    graph = HighLevelGraph.from_collections(name, layer, dependencies=())
    return dask.array.Array(graph, name, chunks, dtype=numpy.float32)


def render_maps(model, shape, chunks, origin=(0, 0), scale=1.0, seed=0, threads=1,
                periodic=False):
    """A material's maps of the (height, width) grid as Model.render_maps gives them, each a lazy
    float32 dask array of height x width x the map's channels: {name: array}, in the model's
    order (a normal map, derived from the height or not, as 3 channels of 0.5 + 0.5 n).

    Each chunk is one Model.render_maps call for all the maps (which renders its own one-pixel
    margin for a derived normal map), so every map is bit for bit that of the single render of the
    whole grid, whatever the chunking. shape, chunks, threads, periodic: as render()."""
    shape, chunks = _checked(model, shape, chunks, channels=1)
    if not model.maps:
        raise ValueError("the model is of one image, not a material: use stochtex.dask.render")
    _check_arguments(model.render_maps, origin, scale, seed, threads, bool(periodic))
    token = tokenize(model.__getstate__(), shape, chunks, origin, scale, seed, bool(periodic))
    name = "stochtex-render-maps-" + token
    layer = _chunk_layer(name, _render_maps_chunk, model, token, chunks, origin, scale, seed,
                         threads, _periodic(periodic, shape))
    maps = {}
    for entry in model.maps:
        channels = 3 if entry["kind"] == "normal" else entry["channels"]
        map_name = name + "-" + entry["name"]
        map_layer = {(map_name, i, j, 0): (operator.getitem, (name, i, j, 0), entry["name"])
                     for i in range(len(chunks[0])) for j in range(len(chunks[1]))}
        graph = HighLevelGraph({name: layer, map_name: map_layer},
                               {name: set(), map_name: {name}})
        maps[entry["name"]] = dask.array.Array(graph, map_name, chunks[:2] + ((channels,),),
                                               dtype=numpy.float32)
    return maps
