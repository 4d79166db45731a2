"""The Python module as a user meets it (docs/python.md)."""

import os
import pickle
import signal
import subprocess
import threading
import time

import numpy
import pytest

import stochtex
from conftest import read_pfm, run_python, smooth_noise, write_pfm


def test_dtypes_and_views_analyse_like_float32(exemplar):
    as_uint8 = numpy.round(exemplar * 255).astype(numpy.uint8)
    from_uint8 = stochtex.analyze(as_uint8, "tiling", seed=3)
    from_float = stochtex.analyze(as_uint8.astype(numpy.float32) / numpy.float32(255), "tiling",
                                  seed=3)
    assert pickle.dumps(from_uint8) == pickle.dumps(from_float)
    as_uint16 = numpy.round(exemplar * 65535).astype(numpy.uint16)
    from_uint16 = stochtex.analyze(as_uint16, "tiling", seed=3)
    assert from_uint16.channels == 3
    # A non-contiguous view analyses like its contiguous copy.
    view = exemplar[::2, ::-1]
    assert not view.flags["C_CONTIGUOUS"]
    assert pickle.dumps(stochtex.analyze(view, "tiling")) == pickle.dumps(
        stochtex.analyze(numpy.ascontiguousarray(view), "tiling"))
    grey = stochtex.analyze(exemplar[:, :, 0], "tiling")
    assert grey.channels == 1


@pytest.mark.parametrize("array, error, words", [
    (numpy.zeros((8, 8), numpy.float64), TypeError, "float64"),
    (numpy.zeros((8, 8), numpy.int32), TypeError, "uint8, uint16 or float32"),
    (numpy.zeros(8, numpy.float32), ValueError, "1 dimensions"),
    (numpy.zeros((4, 4, 4, 1), numpy.float32), ValueError, "4 dimensions"),
    (numpy.zeros((8, 8, 5), numpy.float32), ValueError, "5 channels"),
    (numpy.zeros((0, 8), numpy.float32), ValueError, "empty"),
    (numpy.zeros((8, 8), numpy.float32), ValueError, "constant"),
    (numpy.full((1, 8), 0.5, numpy.float32), ValueError, "1"),
    # A broadcast view claims 10^12 pixels without their memory: refused before any copy.
    (numpy.broadcast_to(numpy.float32(0.5), (10**6, 10**6)), ValueError, "more than the 67108864"),
])
def test_bad_arrays_are_clear_errors(array, error, words):
    with pytest.raises(error, match=words):
        stochtex.analyze(array, "texton")


def test_nan_exemplar_is_refused(exemplar):
    bad = exemplar.copy()
    bad[3, 4, 1] = numpy.nan
    with pytest.raises(ValueError, match="NaN"):
        stochtex.analyze(bad, "texton")


def test_parameters_are_keywords(exemplar):
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        stochtex.analyze(exemplar, "nope")
    with pytest.raises(ValueError, match="unknown parameter 'brightness'"):
        stochtex.analyze(exemplar, "texton", brightness=1)
    with pytest.raises(ValueError, match="iterations"):
        stochtex.analyze(exemplar, "texton", iterations=-4)
    with pytest.raises(TypeError, match="number or a choice"):
        stochtex.analyze(exemplar, "texton", iterations=[1])
    # A choice by its name or by its number.
    by_name = stochtex.analyze(exemplar, "tiling", blend="variance")
    by_number = stochtex.analyze(exemplar, "tiling", blend=1)
    assert pickle.dumps(by_name) == pickle.dumps(by_number)
    assert by_name.info["params"]["blend"] == 1.0


def test_render_is_deterministic_whatever_the_threads(texton_model):
    one = texton_model.render(64, 48, origin=(3.5, -2), scale=0.75, seed=9, threads=1)
    two = texton_model.render(64, 48, origin=(3.5, -2), scale=0.75, seed=9, threads=2)
    assert one.dtype == numpy.float32 and one.shape == (48, 64, 3)
    assert numpy.array_equal(one, two)
    assert not numpy.array_equal(one, texton_model.render(64, 48, origin=(3.5, -2), scale=0.75,
                                                           seed=10))


def test_every_cpu_target_renders_the_same_bytes(exemplar):
    model = stochtex.analyze(exemplar, "lrp", cosines=12)
    targets = stochtex.cpu_targets()
    assert targets[0] == "reference" and stochtex.cpu_target() == targets[-1]
    try:
        renders = []
        for target in targets:
            stochtex.set_cpu_target(target)
            assert stochtex.cpu_target() == target
            renders.append(model.render(37, 29, origin=(-5, 8), scale=3, seed=2, threads=1))
        assert all(numpy.array_equal(renders[0], r) for r in renders[1:])
        with pytest.raises(ValueError, match="cannot run 'neon'"):
            stochtex.set_cpu_target("neon")
    finally:
        stochtex.set_cpu_target(targets[-1])


def test_offset_chunks_equal_the_whole_render(texton_model):
    whole = texton_model.render(70, 50, origin=(1, 2), scale=1.5, seed=4)
    chunk = texton_model.render(30, 20, origin=(1, 2), scale=1.5, seed=4, offset=(33, 17))
    assert numpy.array_equal(chunk, whole[17:37, 33:63])


def test_evaluate_matches_render(texton_model):
    image = texton_model.render(16, 8, origin=(5, 6), scale=1.0, seed=2)
    y, x = numpy.mgrid[0:8, 0:16]
    points = numpy.stack([5 + x + 0.5, 6 + y + 0.5], axis=-1).reshape(-1, 2)
    footprints = numpy.tile(numpy.array([[1.0, 0.0], [0.0, 1.0]]), (len(points), 1, 1))
    values = texton_model.evaluate(points, footprints, seed=2)
    assert values.shape == (128, 3) and values.dtype == numpy.float32
    assert numpy.array_equal(values, image.reshape(-1, 3))
    with pytest.raises(ValueError, match="Nx2"):
        texton_model.evaluate(numpy.zeros((4, 3)))
    with pytest.raises(ValueError, match="Nx2x2"):
        texton_model.evaluate(points, numpy.zeros((3, 2, 2)))
    with pytest.raises(ValueError, match="finite"):
        texton_model.evaluate(numpy.array([[numpy.nan, 0.0]]))


def test_render_arguments_are_checked(texton_model):
    with pytest.raises(ValueError, match="width and height"):
        texton_model.render(0, 4)
    with pytest.raises(ValueError):
        texton_model.render(4, 4, scale=float("nan"))
    with pytest.raises(ValueError, match="threads"):
        texton_model.render(4, 4, threads=-1)
    # More pixels than `stochtex render` holds in memory: rendered in pieces instead.
    with pytest.raises(ValueError, match="stochtex.dask.render"):
        texton_model.render(40000, 40000)


# Scales that `stochtex render --scale` refuses (0, -1 and 1e-300 were rendered in Python) and
# takes; a side beyond what it holds in memory.
BAD_SCALES = [0, -1, 1e-300, 9e-7, 1.1e6, float("nan"), float("inf")]
GOOD_SCALES = [1e-6, 1e6]


def test_render_refuses_what_stochtex_render_refuses(texton_model):
    for scale in BAD_SCALES:
        for render in (texton_model.render, texton_model.render_maps):
            with pytest.raises(ValueError, match="scale"):
                render(2, 2, scale=scale)
    for scale in GOOD_SCALES:
        assert texton_model.render(2, 2, scale=scale).shape == (2, 2, 3)
    with pytest.raises(ValueError, match="32768"):
        texton_model.render(32769, 1)
    # The Gaussian version takes the sizes of `stochtex gaussian`: the same rule.
    exemplar = smooth_noise(8, 8, 1, 3)
    assert stochtex.gaussian(exemplar, 20000, 1).shape == (1, 20000, 1)
    with pytest.raises(ValueError, match="32768"):
        stochtex.gaussian(exemplar, 32769, 1)


def test_stochtex_render_refuses_the_same(texton_model, cli, tmp_path):
    texton_model.save(tmp_path / "model.stx")

    def cli_render(size, scale):
        return subprocess.run([cli, "render", str(tmp_path / "model.stx"), "-o",
                               str(tmp_path / "render.pfm"), "--size", size, f"--scale={scale}"],
                              capture_output=True).returncode

    assert [cli_render("2x2", scale) for scale in BAD_SCALES + GOOD_SCALES] == \
        [2] * len(BAD_SCALES) + [0] * len(GOOD_SCALES)
    assert cli_render("32769x1", 1) == 2


def test_requests_beyond_the_memory_budget_are_refused_before_allocating(texton_model, tmp_path):
    # Broadcast views: a few bytes of array that claim gigabytes (evaluate of 10^9 points
    # allocated 16 GB). Each request is refused in another interpreter that may allocate 1 GiB.
    texton_model.save(tmp_path / "model.stx")
    result = run_python(f"""
        import numpy, stochtex
        from conftest import smooth_noise
        model = stochtex.load({str(tmp_path / "model.stx")!r})
        exemplar = smooth_noise(32, 40, 3, 7)
        huge_row = numpy.broadcast_to(numpy.linspace(0, 1, 8192, dtype=numpy.float32),
                                      (8192, 8192))
        huge_rgba = numpy.broadcast_to(smooth_noise(1, 8192, 4, 1), (8192, 8192, 4))
        material = stochtex.analyze_material(
            {{"albedo": exemplar, "paint": exemplar, "roughness": exemplar[:, :, 0]}}, "lrp",
            cosines=4)
        assert material.channels == 7
        requests = {{
            "evaluate": lambda: model.evaluate(numpy.broadcast_to(numpy.zeros(2), (10**9, 2))),
            "evaluate float32": lambda: model.evaluate(
                numpy.broadcast_to(numpy.zeros(2, numpy.float32), (10**9, 2))),
            "evaluate footprints": lambda: model.evaluate(
                numpy.broadcast_to(numpy.zeros(2), (10**8, 2)),
                numpy.broadcast_to(numpy.eye(2), (10**8, 2, 2))),
            "gaussian of a large exemplar": lambda: stochtex.gaussian(huge_row, 64, 64),
            "gaussian": lambda: stochtex.gaussian(exemplar, 8192, 8192),
            "compare": lambda: stochtex.compare(exemplar, [numpy.broadcast_to(
                exemplar[:1, :1], (8192, 8192, 3))] * 2),
            "analyze": lambda: stochtex.analyze(numpy.broadcast_to(
                numpy.float32(0.5), (8192, 8192, 4)), "gabor"),
            "analyze_material": lambda: stochtex.analyze_material(
                {{f"map{{i}}": huge_row for i in range(12)}}, "lrp"),
            "mix": lambda: stochtex.mix(huge_rgba, huge_rgba),
            "split": lambda: material.split(
                numpy.broadcast_to(numpy.float32(0.5), (8192, 8192, 7))),
            "render_maps": lambda: material.render_maps(8192, 8192, threads=1),
            "render of 7 channels": lambda: material.render(8192, 8192, threads=1),
        }}
        failures = []
        for name, request in requests.items():
            try:
                request()
            except ValueError as e:
                if "more than the budget of 2 GiB" not in str(e):
                    failures.append(name + ": " + str(e))
            except Exception as e:
                failures.append(name + ": " + type(e).__name__ + " " + str(e)[:300])
            else:
                failures.append(name + ": accepted")
        assert not failures, "\\n".join(failures)
        """, memory_limit=1 << 30)
    assert result.returncode == 0, result.stderr


def test_save_load_and_pickle(texton_model, tmp_path):
    path = tmp_path / "model.stx"
    texton_model.save(path)
    loaded = stochtex.load(str(path))
    assert loaded.method == "texton" and loaded.channels == 3
    assert numpy.array_equal(loaded.render(20, 20, seed=1), texton_model.render(20, 20, seed=1))
    copy = pickle.loads(pickle.dumps(texton_model))
    assert numpy.array_equal(copy.render(20, 20, seed=1), texton_model.render(20, 20, seed=1))
    with pytest.raises(OSError, match="missing.stx"):
        stochtex.load(tmp_path / "missing.stx")
    (tmp_path / "bad.stx").write_bytes(b"not a model")
    with pytest.raises(ValueError, match="bad.stx"):
        stochtex.load(tmp_path / "bad.stx")


def test_images_are_read_and_written_as_the_cli_does(exemplar, tmp_path):
    # 16-bit PNG and PFM hold these values exactly; 8-bit PNG to the nearest 1/255.
    levels = numpy.round(exemplar * 65535.0).astype(numpy.float32) / 65535.0
    stochtex.write_image(tmp_path / "image.png", levels, bit_depth=16)
    assert numpy.array_equal(stochtex.read_image(tmp_path / "image.png"), levels)
    stochtex.write_image(tmp_path / "image.pfm", exemplar)
    assert numpy.array_equal(stochtex.read_image(tmp_path / "image.pfm"), exemplar)
    stochtex.write_image(tmp_path / "image8.png", exemplar)
    assert numpy.abs(stochtex.read_image(tmp_path / "image8.png") - exemplar).max() <= 0.5 / 255
    with pytest.raises(OSError, match="missing.png"):
        stochtex.read_image(tmp_path / "missing.png")
    with pytest.raises(ValueError, match="extension"):
        stochtex.write_image(tmp_path / "image.bmp", exemplar)


def test_pickle_of_every_protocol_and_copies_are_the_same_model(texton_model, tmp_path):
    # Protocols 0 and 1 and __reduce__() aborted the interpreter: checked in another.
    texton_model.save(tmp_path / "model.stx")
    result = run_python(f"""
        import copy, pickle, numpy, stochtex
        model = stochtex.load({str(tmp_path / "model.stx")!r})
        function, arguments, state = model.__reduce__()
        copies = [function(*arguments)]
        copies[0].__setstate__(state)
        copies += [pickle.loads(pickle.dumps(model, protocol))
                   for protocol in range(pickle.HIGHEST_PROTOCOL + 1)]
        copies += [copy.copy(model), copy.deepcopy(model), copy.copy(copies[0])]
        image = model.render(9, 7, origin=(2, 3), seed=5)
        for twin in copies:
            assert type(twin) is stochtex.Model and twin is not model
            assert twin.__getstate__() == model.__getstate__()
            assert numpy.array_equal(twin.render(9, 7, origin=(2, 3), seed=5), image)
        """)
    assert result.returncode == 0, result.stderr


def test_uninitialised_objects_raise_instead_of_crashing(texton_model, tmp_path):
    # Model.__new__(Model) is a Model without a model (unpickling makes one, then __setstate__
    # fills it): its methods read memory that holds no model. Every public method and property of
    # every class the module exports is called on one, in another interpreter; a new method needs
    # its sample arguments here.
    (tmp_path / "state").write_bytes(texton_model.__getstate__())
    result = run_python(f"""
        import inspect, numpy, stochtex, stochtex._stochtex as module
        arguments = {{"render": (4, 4), "render_maps": (4, 4), "evaluate": (numpy.zeros((1, 2)),),
                     "split": (numpy.zeros((4, 4, 3), numpy.float32),),
                     "save": ({str(tmp_path / "never.stx")!r},), "__getstate__": (),
                     "__reduce__": (), "__reduce_ex__": (2,)}}
        classes = [c for c in vars(module).values() if inspect.isclass(c)]
        assert classes == [stochtex.Model], classes
        class Subclass(stochtex.Model):
            pass
        for cls in classes + [Subclass]:
            empty = cls.__new__(cls)
            assert "not initialised" in repr(empty), repr(empty)
            names = [n for n in dir(cls) if not n.startswith("_")]
            names += ["__getstate__", "__reduce__", "__reduce_ex__"]
            for name in names:
                member = inspect.getattr_static(cls, name)
                try:
                    if isinstance(member, property):
                        getattr(empty, name)
                    else:
                        assert name in arguments, "give " + name + " sample arguments"
                        getattr(empty, name)(*arguments[name])
                except RuntimeError as e:
                    assert "not initialised" in str(e), (name, e)
                else:
                    raise AssertionError(name + " of an empty " + cls.__name__ + " returned")
        try:
            stochtex.Model.render("not a model", 4, 4)
        except TypeError as e:
            assert "stochtex.Model" in str(e), e
        else:
            raise AssertionError("Model.render of a str returned")
        # What unpickling does: __setstate__ makes the empty model whole.
        empty = stochtex.Model.__new__(stochtex.Model)
        with open({str(tmp_path / "state")!r}, "rb") as state:
            empty.__setstate__(state.read())
        assert empty.channels == 3
        """)
    assert result.returncode == 0, result.stderr


def test_info_methods_compare_gaussian(exemplar, texton_model):
    info = texton_model.info
    assert info["method"] == "texton"
    assert repr(texton_model) == "<stochtex.Model texton, 3 channels>"
    methods = {method["name"]: method for method in stochtex.methods()}
    assert {"texton", "tiling", "lrp", "gabor"} <= set(methods)
    blend = next(p for p in methods["tiling"]["params"] if p["name"] == "blend")
    assert [c["name"] for c in blend["choices"]][:2] == ["histogram", "variance"]
    gaussian = stochtex.gaussian(exemplar, 48, 40, seed=1)
    assert gaussian.shape == (40, 48, 3) and gaussian.dtype == numpy.float32
    numbers = stochtex.compare(exemplar, gaussian)
    assert numbers["welch_crop"] == 16
    assert {"spectral_error", "spectral_error_adsn", "histogram_error",
            "histogram_error_floor"} <= set(numbers)
    several = stochtex.compare(exemplar, [gaussian, stochtex.gaussian(exemplar, 48, 40, seed=2)])
    assert several["averaged_spectral_error"] < several["spectral_error"]
    assert "averaged_spectral_error" not in numbers
    with pytest.raises(ValueError, match="first image is 48x40"):
        stochtex.compare(exemplar, [gaussian, gaussian[:32]])
    with pytest.raises(ValueError, match="channels"):
        stochtex.compare(exemplar, gaussian[:, :, :1])
    with pytest.raises(ValueError, match="NaN"):
        stochtex.compare(exemplar, numpy.full((8, 8, 3), numpy.nan, numpy.float32))


def test_mix(exemplar):
    other = smooth_noise(32, 40, 3, 8)
    model = stochtex.mix(exemplar, other, steps=2, iterations=3)
    assert model.method == "texton_mix" and model.channels == 3


def test_python_equals_the_cli(exemplar, texton_model, cli, tmp_path):
    write_pfm(tmp_path / "exemplar.pfm", exemplar)
    # The CLI's default, auto, takes a PFM as linear light; an array's default is data.
    subprocess.run([cli, "analyze", str(tmp_path / "exemplar.pfm"), "-m", "texton", "-p",
                    "iterations=5", "--colour-space", "data", "-o", str(tmp_path / "cli.stx")],
                   check=True)
    assert pickle.dumps(stochtex.load(tmp_path / "cli.stx")) == pickle.dumps(texton_model)
    subprocess.run([cli, "render", str(tmp_path / "cli.stx"), "--size", "40x30", "--seed", "5",
                    "-o", str(tmp_path / "render.pfm")], check=True)
    assert numpy.array_equal(read_pfm(tmp_path / "render.pfm"), texton_model.render(40, 30, seed=5))


def test_progress_is_reported(exemplar, texton_model):
    fractions = []
    texton_model.render(256, 256, threads=2, progress=fractions.append)
    assert len(fractions) > 2 and fractions == sorted(fractions) and fractions[-1] == 1.0
    fractions = []
    stochtex.analyze(exemplar, "texton", progress=fractions.append, iterations=5)
    assert fractions == [1 / 5, 2 / 5, 3 / 5, 4 / 5, 1.0, 1.0]  # each iteration, then the end
    fractions = []
    stochtex.analyze(exemplar, "tiling", progress=fractions.append)
    assert fractions == [1.0]
    fractions = []
    stochtex.analyze(exemplar, "gabor", progress=fractions.append, iterations=50)
    assert len(fractions) > 10 and fractions == sorted(fractions) and fractions[-1] == 1.0


def test_progress_callback_can_stop_analysis(exemplar):
    class Stop(Exception):
        pass

    calls = []

    def stop_early(fraction):
        calls.append(fraction)
        if len(calls) == 3:
            raise Stop()

    with pytest.raises(Stop):
        stochtex.analyze(exemplar, "gabor", progress=stop_early)
    assert len(calls) == 3


def test_ctrl_c_interrupts_a_long_render(exemplar):
    model = stochtex.analyze(exemplar, "gabor", iterations=50)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            model.render(2048, 2048, threads=2)  # about 150 s to the end
    finally:
        timer.cancel()
    assert time.monotonic() - start < 5.0


def test_ctrl_c_interrupts_a_long_analysis():
    exemplar = smooth_noise(256, 256, 3, 5)  # about 6 s of gabor analysis to the end
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            stochtex.analyze(exemplar, "gabor")
    finally:
        timer.cancel()
    assert time.monotonic() - start < 3.0


def test_material_maps_analyse_render_and_split(exemplar):
    roughness = smooth_noise(32, 40, 1, 11)[:, :, 0]
    model = stochtex.analyze_material({"albedo": exemplar, "roughness": roughness}, "tiling")
    # The albedo is srgb by convention (colour="srgb", the default), the other maps data.
    assert model.maps == [
        {"name": "albedo", "kind": "colour", "channels": 3, "colour_space": "srgb"},
        {"name": "roughness", "kind": "scalar", "channels": 1, "colour_space": "data"}]
    as_data = stochtex.analyze_material({"albedo": exemplar, "roughness": roughness}, "tiling",
                                        colour="data")
    assert as_data.maps[0]["colour_space"] == "data"
    with pytest.raises(ValueError, match="colour must be"):
        stochtex.analyze_material({"albedo": exemplar}, "tiling", colour="oklab")
    assert model.channels == 4
    image = model.render(24, 16, seed=3)
    maps = model.split(image)
    assert list(maps) == ["albedo", "roughness"]
    assert numpy.array_equal(maps["albedo"], image[:, :, :3])
    assert numpy.array_equal(maps["roughness"], image[:, :, 3:])
    assert pickle.loads(pickle.dumps(model)).maps == model.maps


def test_material_colour_maps_render_linear_light_or_encoded(exemplar, cli, tmp_path):
    """A CLI material's srgb albedo: render_maps gives linear light, and with
    encoded=True sRGB-encoded values as its PNG holds them; the data maps stay as they are."""
    write_pfm(tmp_path / "albedo.pfm", exemplar)
    write_pfm(tmp_path / "roughness.pfm", smooth_noise(32, 40, 1, 11))
    subprocess.run([cli, "analyze", "--map", f"albedo={tmp_path / 'albedo.pfm'}",
                    "--map", f"roughness={tmp_path / 'roughness.pfm'}", "-m", "tiling",
                    "--colour-space", "srgb", "-o", str(tmp_path / "material.stx")], check=True)
    model = stochtex.load(tmp_path / "material.stx")
    linear = model.render_maps(24, 16, seed=3)
    encoded = model.render_maps(24, 16, seed=3, encoded=True)
    expected = numpy.where(linear["albedo"] <= 0.0031308, linear["albedo"] * 12.92,
                           1.055 * numpy.abs(linear["albedo"]) ** (1 / 2.4) - 0.055)
    assert numpy.abs(encoded["albedo"] - expected).max() < 1e-5
    assert not numpy.allclose(encoded["albedo"], linear["albedo"])
    assert numpy.array_equal(linear["roughness"], encoded["roughness"])


def test_material_normal_maps_come_back_unit_length(exemplar):
    # A normal map of the gradient of a smooth height, encoded 0.5 + 0.5 n.
    height = smooth_noise(32, 40, 1, 5)[:, :, 0] * 8.0
    gy, gx = numpy.gradient(height)
    n = numpy.stack([-gx, gy, numpy.ones_like(gx)], axis=2)
    n /= numpy.linalg.norm(n, axis=2, keepdims=True)
    model = stochtex.analyze_material({"normal": (0.5 + 0.5 * n).astype(numpy.float32)}, "tiling")
    assert model.maps == [{"name": "normal", "kind": "normal", "channels": 2,
                           "colour_space": "data"}]
    normal = model.split(model.render(32, 32))["normal"] * 2.0 - 1.0
    assert numpy.allclose(numpy.linalg.norm(normal, axis=2), 1.0, atol=1e-5)


@pytest.mark.parametrize("maps, kinds, words", [
    ({"albedo": smooth_noise(32, 40, 3, 1), "roughness": smooth_noise(16, 40, 1, 2)}, {},
     "the same size"),
    ({"normal": smooth_noise(32, 40, 3, 1)}, {}, "not a tangent-space normal map"),
    ({"albedo": smooth_noise(32, 40, 3, 1)}, {"albedo": "rgb"}, "colour, normal, height, scalar"),
])
def test_bad_materials_are_clear_errors(maps, kinds, words):
    with pytest.raises(ValueError, match=words):
        stochtex.analyze_material(maps, "tiling", kinds=kinds)


def test_srgb_models_render_linear_light(exemplar, tmp_path):
    """docs/design.md §14: a srgb model renders linear light, encoded=True gives the encoded
    values, pickles keep the colour space, and write_image encodes linear light into a PNG."""
    data = stochtex.analyze(exemplar, "texton", seed=2, support=12, iterations=5)
    srgb = stochtex.analyze(exemplar, "texton", seed=2, support=12, iterations=5, colour="srgb")
    assert (data.colour_space, srgb.colour_space) == ("data", "srgb")
    assert pickle.loads(pickle.dumps(srgb)).colour_space == "srgb"
    linear = srgb.render(32, 24, seed=3)
    encoded = srgb.render(32, 24, seed=3, encoded=True)
    as_data = data.render(32, 24, seed=3)
    # At scale 1 the point samples are decoded exactly: encoded again, the data model's values.
    assert numpy.abs(encoded - as_data).max() < 1e-5
    decoded = numpy.where(as_data <= 0.04045, as_data / 12.92, ((as_data + 0.055) / 1.055) ** 2.4)
    assert numpy.abs(linear - decoded).max() < 1e-5
    # Zoomed out, the linear-light mean: brighter than the encoded values' mean decoded.
    far = srgb.render(16, 16, scale=64, seed=3).mean(axis=(0, 1))
    naive = data.render(16, 16, scale=64, seed=3).mean(axis=(0, 1))
    naive = numpy.where(naive <= 0.04045, naive / 12.92, ((naive + 0.055) / 1.055) ** 2.4)
    assert (far > naive).all()
    with pytest.raises(ValueError, match="colour must be"):
        stochtex.analyze(exemplar, "texton", colour="oklab")
    path = str(tmp_path / "linear.png")
    stochtex.write_image(path, linear, colour="linear")
    clipped = numpy.clip(encoded, 0, 1)  # a PNG holds 0 to 1
    assert numpy.abs(stochtex.read_image(path) - clipped).max() <= 0.5 / 255 + 1e-6
