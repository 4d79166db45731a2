"""Shared fixtures of the Python module's tests: small synthetic exemplars (so no image library
is needed) and the CLI, when CTest names it (STOCHTEX_CLI)."""

import os
import subprocess
import sys
import textwrap

import numpy
import pytest


def smooth_noise(height, width, channels, seed):
    """A deterministic stochastic texture: white noise low-pass filtered, values in [0, 1]."""
    rng = numpy.random.default_rng(seed)
    noise = rng.standard_normal((height, width, channels))
    fy = numpy.fft.fftfreq(height)[:, None]
    fx = numpy.fft.fftfreq(width)[None, :]
    gain = numpy.exp(-(fx * fx + fy * fy) / (2 * 0.08 ** 2))[:, :, None]
    image = numpy.real(numpy.fft.ifft2(numpy.fft.fft2(noise, axes=(0, 1)) * gain, axes=(0, 1)))
    image = (image - image.min()) / (image.max() - image.min())
    return image.astype(numpy.float32)


@pytest.fixture(scope="session")
def exemplar():
    return smooth_noise(32, 40, 3, 7)


@pytest.fixture(scope="session")
def texton_model(exemplar):
    import stochtex
    return stochtex.analyze(exemplar, "texton", iterations=5)


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("STOCHTEX_CLI")
    if not path:
        pytest.skip("STOCHTEX_CLI (the stochtex executable) is not set")
    return path


def run_python(code, memory_limit=None):
    """`code` run by a fresh interpreter with this one's environment and the helpers here, its
    stdout and stderr captured: a crash there fails a test here (with the Python stack of the
    crash, faulthandler's) instead of killing pytest. memory_limit caps its address space, in
    bytes, so that what allocates beyond it fails there (MemoryError) rather than swap here."""
    code = textwrap.dedent(code)
    if memory_limit:
        code = ("import resource\n"
                f"resource.setrlimit(resource.RLIMIT_AS, ({memory_limit}, {memory_limit}))\n"
                + code)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [os.path.dirname(__file__)] + os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    return subprocess.run([sys.executable, "-X", "faulthandler", "-c", code], capture_output=True,
                          text=True, env=env, timeout=120)


def write_pfm(path, image):
    """A float32 HxWxC (C = 1 or 3) array as PFM: bottom row first, little-endian."""
    height, width, channels = image.shape
    header = f"{'PF' if channels == 3 else 'Pf'}\n{width} {height}\n-1.0\n".encode()
    with open(path, "wb") as f:
        f.write(header + numpy.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields = data[:64].split()
    channels = 3 if fields[0] == b"PF" else 1
    width, height, scale = int(fields[1]), int(fields[2]), float(fields[3])
    pixels = numpy.frombuffer(data[-width * height * channels * 4:],
                              dtype="<f4" if scale < 0 else ">f4")
    return pixels.reshape(height, width, channels)[::-1].astype(numpy.float32)
