"""stochtex.dask: chunked renders equal the single render, stored to Zarr, computed on a
distributed cluster of worker processes (the models pickled to them)."""

import numpy
import pytest

import stochtex
import stochtex.dask

zarr = pytest.importorskip("zarr")


def test_chunks_equal_the_single_render(texton_model):
    whole = texton_model.render(100, 70, origin=(2, 3), scale=1.25, seed=6)
    lazy = stochtex.dask.render(texton_model, (70, 100), chunks=(32, 48), origin=(2, 3),
                                scale=1.25, seed=6)
    assert lazy.shape == (70, 100, 3) and lazy.dtype == numpy.float32
    assert lazy.numblocks == (3, 3, 1)
    assert numpy.array_equal(lazy.compute(scheduler="threads"), whole)
    assert numpy.array_equal(
        stochtex.dask.render(texton_model, (70, 100, 3), chunks=25, origin=(2, 3), scale=1.25,
                             seed=6).compute(scheduler="sync"), whole)
    with pytest.raises(ValueError, match="channels"):
        stochtex.dask.render(texton_model, (70, 100, 4), chunks=25)
    with pytest.raises(TypeError, match="stochtex.Model"):
        stochtex.dask.render("model", (70, 100), chunks=25)
    # What every chunk would refuse is refused as the graph is built, before any compute.
    for scale in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="scale"):
            stochtex.dask.render(texton_model, (70, 100), chunks=25, scale=scale)


def test_zarr_round_trip(texton_model, tmp_path):
    lazy = stochtex.dask.render(texton_model, (60, 90), chunks=32, seed=2)
    lazy.to_zarr(str(tmp_path / "texture.zarr"))
    stored = zarr.open(str(tmp_path / "texture.zarr"), mode="r")
    assert stored.chunks == (32, 32, 3)
    assert numpy.array_equal(stored[:], texton_model.render(90, 60, seed=2))


# (Debian 12's distributed starts tornado's event loop the deprecated way.)
@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_local_cluster_of_two_worker_processes(texton_model):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        lazy = stochtex.dask.render(texton_model, (96, 128), chunks=32, seed=3)
        computed = client.compute(lazy).result()
        assert len(client.scheduler_info()["workers"]) == 2
    assert numpy.array_equal(computed, texton_model.render(128, 96, seed=3))


def test_material_maps_in_chunks_equal_the_single_render(exemplar):
    # texton derives the normal map from its height: each chunk renders its own one-pixel margin,
    # so every map is bit for bit the whole grid's.
    height = exemplar[:, :, 0]
    gy, gx = numpy.gradient(height)
    n = numpy.stack([-gx * 4, gy * 4, numpy.ones_like(height)], axis=-1)
    n /= numpy.linalg.norm(n, axis=-1, keepdims=True)
    model = stochtex.analyze_material(
        {"albedo": exemplar, "normal": (0.5 + 0.5 * n).astype(numpy.float32), "height": height},
        "texton", iterations=5)
    assert any("from" in entry for entry in model.maps)
    whole = model.render_maps(100, 70, origin=(2, 3), scale=1.25, seed=6)
    lazy = stochtex.dask.render_maps(model, (70, 100), chunks=(32, 48), origin=(2, 3),
                                     scale=1.25, seed=6)
    assert list(lazy) == list(whole)
    for name, array in lazy.items():
        assert array.shape == whole[name].shape and array.numblocks == (3, 3, 1)
        assert numpy.array_equal(array.compute(scheduler="threads"), whole[name]), name
    with pytest.raises(ValueError, match="not a material"):
        stochtex.dask.render_maps(stochtex.analyze(exemplar, "texton", iterations=5), (8, 8), 4)
