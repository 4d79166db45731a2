"""PFM reading for the docs scripts (PYTHONPATH=scripts): stochtex writes renders as PFM when
exact float values are measured."""
import numpy


def read_pfm(path):
    """The image at `path` as a height x width x channels float32 array, first row at the top
    (a PFM stores its rows bottom up; a negative scale means little-endian values)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = numpy.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3 if kind == b"PF" else 1)[::-1]
