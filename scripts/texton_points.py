#!/usr/bin/env python3
"""Texton noise's point processes against ADSN, per render (docs/methods/texton.md, "Balanced
points"): texton noise at its default parameters with `points=poisson` and `points=balanced`, and
the exemplar's ADSN, rendered at 1024², on each `gaussian` and `stochastic` exemplar of
data/exemplars (or those named). Two measures, a markdown table each:

- `compare`: the spectral error / ADSN's (`stochtex compare`) and the colour covariance error,
  mean ± standard deviation over seeds 1 to --seeds (ADSN: seeds 101 on, since compare's own ADSN
  sample is drawn with seed 1). About 3.5 minutes per exemplar at 6 seeds on 2 cores.
- `spread`: the relative standard deviation, over seeds 1 to --spread-seeds, of one render's total
  variance (the trace of its colour covariance): how much a render's variance moves with its
  seed, what the covariance error of one render mostly measures. About 3 minutes per exemplar at
  48 seeds.

Usage: python3 scripts/texton_points.py [--build DIR] [--measure compare|spread|both]
                                         [--seeds N] [--spread-seeds N] [exemplar.png ...]
"""
import argparse
import array
import json
import operator
import pathlib
import re
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXEMPLARS = ROOT / "data" / "exemplars"
SIDE = "1024x1024"


def shipped_exemplars():
    row = re.compile(r"^\| `([^`]+\.png)` \| [^|]+ \| (gaussian|stochastic) \|")
    text = (EXEMPLARS / "ATTRIBUTION.md").read_text()
    return [m.group(1) for m in map(row.match, text.splitlines()) if m]


def run(*args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def total_variance(path):
    """The trace of a PFM image's colour covariance."""
    with open(path, "rb") as pfm:
        channels = 3 if pfm.readline().strip() == b"PF" else 1
        width, height = map(int, pfm.readline().split())
        big_endian = float(pfm.readline()) > 0
        values = array.array("f")
        values.frombytes(pfm.read())
    if big_endian:
        values.byteswap()
    pixels = width * height
    total = 0.0
    for c in range(channels):
        plane = values[c::channels]
        mean = sum(plane) / pixels
        total += sum(map(operator.mul, plane, plane)) / pixels - mean * mean
    return total


class Sources:
    """The three columns: a render of each texton model, and ADSN."""

    def __init__(self, tool, exemplar, work):
        self.tool, self.exemplar, self.work = tool, exemplar, work
        self.models = {}
        for points in ("poisson", "balanced"):
            model = work / (points + ".stx")
            run(tool, "analyze", "--method", "texton", str(exemplar), "-o", str(model), "-p",
                "points=" + points)
            self.models[points] = model

    def image(self, column, seed):
        image = self.work / (column + ".pfm")
        if column == "ADSN":
            run(self.tool, "gaussian", str(self.exemplar), "--size", SIDE, "--seed",
                str(100 + seed), "-o", str(image))
        else:
            run(self.tool, "render", str(self.models[column]), "--size", SIDE, "--seed",
                str(seed), "-o", str(image))
        return image


COLUMNS = ("poisson", "balanced", "ADSN")


def compare_cell(tool, sources, column, seeds):
    ratios, covariances = [], []
    for seed in range(1, seeds + 1):
        numbers = json.loads(run(tool, "compare", "--json", str(sources.exemplar),
                                 str(sources.image(column, seed))))
        ratios.append(numbers["spectral_error"] / numbers["spectral_error_adsn"])
        covariances.append(numbers["covariance_error"])
    return "{:.2f} ± {:.2f}, {:.3f} ± {:.3f}".format(
        statistics.mean(ratios), statistics.stdev(ratios), statistics.mean(covariances),
        statistics.stdev(covariances))


def spread_cell(sources, column, seeds):
    variances = [total_variance(sources.image(column, seed)) for seed in range(1, seeds + 1)]
    return "{:.2f}%".format(100.0 * statistics.stdev(variances) / statistics.mean(variances))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", help="the build directory (default: build)")
    parser.add_argument("--measure", choices=("compare", "spread", "both"), default="both")
    parser.add_argument("--seeds", type=int, default=6, help="renders per cell of `compare`")
    parser.add_argument("--spread-seeds", type=int, default=48, help="renders per cell of `spread`")
    parser.add_argument("exemplars", nargs="*", help="file names in data/exemplars")
    args = parser.parse_args()
    tool = str((pathlib.Path(args.build) / "stochtex").resolve())
    measures = ("compare", "spread") if args.measure == "both" else (args.measure,)
    lines = {m: ["| exemplar | " + " | ".join(COLUMNS) + " |", "|---" * 4 + "|"] for m in measures}
    with tempfile.TemporaryDirectory() as work:
        for name in args.exemplars or shipped_exemplars():
            sources = Sources(tool, EXEMPLARS / name, pathlib.Path(work))
            for measure in measures:
                cells = [compare_cell(tool, sources, c, args.seeds) if measure == "compare" else
                         spread_cell(sources, c, args.spread_seeds) for c in COLUMNS]
                lines[measure].append("| {} | {} |".format(name.removesuffix(".png"),
                                                           " | ".join(cells)))
                print("{}: {}".format(measure, lines[measure][-1]), flush=True)
    for measure in measures:
        print("\n" + measure + "\n\n" + "\n".join(lines[measure]))


if __name__ == "__main__":
    main()
