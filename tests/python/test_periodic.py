"""Tileable bakes (docs/render.md "Periodic renders"): Model.render(periodic=True) repeats with the
render, a chunk given the whole image's size is the same pixels, stochtex.dask.render(periodic=True)
is the single bake, and a texton mix is refused."""

import numpy
import pytest

import stochtex
import stochtex.dask


def wrap_and_largest_interior_step(image, axis):
    """The wrap step (last to first line) and the largest step between neighbouring lines."""
    steps = numpy.abs(image - numpy.roll(image, -1, axis=axis)).mean(axis=tuple(
        a for a in range(image.ndim) if a != axis))
    return steps[-1], steps[:-1].max()


def test_periodic_render_wraps_like_its_interior(texton_model):
    # Zoomed in, neighbouring pixels are close and a seam stands out.
    for periodic in (True, False):
        image = texton_model.render(90, 62, scale=0.5, seed=3, periodic=periodic)
        for axis in (0, 1):
            wrap, largest = wrap_and_largest_interior_step(image, axis)
            assert (wrap <= largest) == periodic, (periodic, axis, wrap, largest)


def test_chunks_of_a_bake_equal_the_whole(texton_model):
    whole = texton_model.render(90, 62, origin=(2, 3), scale=1.25, seed=6, periodic=True)
    chunk = texton_model.render(40, 30, origin=(2, 3), scale=1.25, seed=6, offset=(50, 32),
                                periodic=(90, 62))
    assert numpy.array_equal(chunk, whole[32:62, 50:90])
    # One period on, the same pixels.
    again = texton_model.render(90, 62, origin=(2, 3), scale=1.25, seed=6, offset=(90, -62),
                                periodic=(90, 62))
    assert numpy.array_equal(again, whole)
    lazy = stochtex.dask.render(texton_model, (62, 90), chunks=(25, 40), origin=(2, 3),
                                scale=1.25, seed=6, periodic=True)
    assert numpy.array_equal(lazy.compute(scheduler="sync"), whole)
    assert not numpy.array_equal(texton_model.render(90, 62, origin=(2, 3), scale=1.25, seed=6),
                                 whole)


def test_periodic_refusals(texton_model, exemplar):
    with pytest.raises(ValueError, match="periodic"):
        texton_model.render(8, 8, periodic=(0, 8))
    mixed = stochtex.mix(exemplar, exemplar, support=8, iterations=2, steps=2)
    with pytest.raises(ValueError, match="texton mix cannot render periodic"):
        mixed.render(8, 8, periodic=True)
    with pytest.raises(ValueError, match="texton mix cannot render periodic"):
        stochtex.dask.render(mixed, (8, 8), chunks=4, periodic=True)
