"""Writes docs/comparison.md from the JSON summary of `stochtex report` (see scripts/report.sh).

usage: comparison_markdown.py SUMMARY.json ATTRIBUTION.md THUMBNAILS_DIR IMAGES_DIR IMAGES_LINK
Prints the Markdown on stdout and copies the thumbnails into IMAGES_DIR (linked as
IMAGES_LINK/NAME_KIND.png). ATTRIBUTION.md (data/exemplars) gives each exemplar's category.
"""

import json
import re
import shutil
import statistics
import sys
from pathlib import Path

MEASURES = [  # key, column title, format
    ("spectral_error", "spectral", "{:.3f}"),
    ("averaged_spectral_error", "averaged", "{:.3f}"),
    ("histogram_error", "colour SW2", "{:.4f}"),
    ("covariance_error", "covariance", "{:.3f}"),
    ("structure_error", "structure", "{:.3f}"),
    ("nonstationarity", "non-stat.", "{:.3f}"),
    ("analysis_seconds", "analysis s", "{:.2f}"),
    ("ns_per_sample", "ns/sample", "{:,.0f}"),
]
CATEGORIES = ["gaussian", "stochastic", "structured"]


def corpus_table(attribution):
    """file stem -> (category, content) from the table of data/exemplars/ATTRIBUTION.md."""
    rows = {}
    for line in Path(attribution).read_text().splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        match = re.fullmatch(r"`(.+)\.png`", cells[0]) if cells else None
        if match and len(cells) >= 8:
            rows[match.group(1)] = (cells[2], cells[3])
    return rows


def label(name):
    return "Gaussian (ADSN)" if name == "gaussian" else name


def value(synthesis, key, form):
    if "error" in synthesis:
        return "failed"
    if key not in synthesis:
        return "—"
    return form.format(synthesis[key])


def which_method(summary, corpus):
    """The section on --method auto: its measures of every exemplar and its choice."""
    out = ["## Which method?\n"]
    out.append(
        "`stochtex analyze -m auto` (and `synth`, the studio, and every page of the report) "
        "measures the exemplar and chooses (`choose_method`, src/method_choice.cpp): **tiling** "
        "where it is far from Gaussian, its band-pass kurtosis above 4, or periodic, more than 10% "
        "of its power in spectral peaks: there the Gaussian methods turn its edges, shapes or "
        "pattern into coloured blur, and only tiling keeps them and its colour histogram; else "
        "**texton**, which reproduces a Gaussian texture as well as lrp and gabor (the spectral "
        "errors above) and renders 15 to 60 times as fast. The measures (src/metrics/structure.hpp, "
        "docs/design.md §8), on the mean of the channels as stored:\n")
    out.append(
        "- *band-pass kurtosis*: the largest, over octave bands (differences of Gaussians of "
        "1, 2, 4, ... pixels up to a 64th of the smaller side, on the periodic component), of the "
        "kurtosis of the band's responses. Any linear filter of a Gaussian texture is Gaussian, "
        "kurtosis 3: the ADSN versions of these exemplars measure at most 3.3 (8 seeds each); "
        "edges, blobs and lines concentrate the band's energy and raise it. The line, 4, sits in "
        "the gap between the Gaussian-looking exemplars (at most 3.3) and the others (4.4 and "
        "up).")
    out.append(
        "- *spectral peaks*: the share of the power (Hann-windowed periodogram, bins 4 or more "
        "from DC) in bins above 16 times the median of their 9×9 neighbourhood: near 0 for a "
        "smooth spectrum (at most 4% here, brushed aluminium's ridge), high for a repeated "
        "pattern. The line, 10%, sits between 4% and the periodic exemplars (12% and up).")
    out.append(
        "- *wrap step* (docs/inputs.md): does not change the choice: tiling makes a non-tileable "
        "exemplar tileable before analysing it (`make_tileable`, but for a strongly repeated "
        "pattern), and the Gaussian methods lose the structure of every non-tileable exemplar "
        "here but the brushed aluminium, which is Gaussian anyway. `analyze` says it in a note "
        "of its own.\n")
    out.append("| exemplar | category | band-pass kurtosis (at px) | spectral peaks | wrap step | "
               "auto |")
    out.append("|---|---|---|---|---|---|")
    for exemplar in summary["exemplars"]:
        choice = exemplar["auto"]
        out.append("| {} | {} | {:.2f} ({}) | {:.1%} | {:.2f} | {} |".format(
            exemplar["name"], corpus.get(exemplar["name"], ("?",))[0], choice["band_kurtosis"],
            choice["band_scale"], choice["peak_fraction"], choice["wrap_step"], choice["method"]))
    out.append("")
    out.append(
        "Looking at the pictures below: tiling is the one that keeps bricks, cobblestones, "
        "paving, nuts, caustics, plaid and knit; on moss, sandstone, rock roughness and concrete "
        "(chosen tiling by their kurtosis) the Gaussian methods look about as good, and on wood, "
        "which does not tile, tiling's seams show where texton's blur does not (tiling's shortfall "
        "in docs/fidelity.md): there auto's choice is defensible, not clearly right. What auto "
        "does not measure: a skewed channel that a Gaussian clips (water's red, docs/inputs.md), "
        "non-stationary lighting (wood's vignette), and how large the exemplar's features are "
        "against its size.\n")
    return out


def main():
    summary_path, attribution, thumbnails, images, link = sys.argv[1:6]
    summary = json.loads(Path(summary_path).read_text())
    corpus = corpus_table(attribution)
    settings = summary["settings"]
    methods = settings["methods"]
    kinds = ["exemplar", "gaussian"] + methods
    Path(images).mkdir(parents=True, exist_ok=True)

    out = []
    out.append("# The methods compared\n")
    out.append(
        "Every method with its default parameters on every shipped exemplar "
        "(`data/exemplars`, {} images), rendered at {}×{} with seed {} beside the exemplar's "
        "Gaussian version (ADSN), measured by `stochtex report` in one run on one machine. "
        "Regenerate with `bash scripts/report.sh`; the full HTML report (every render at full "
        "size, log power spectra, colour histograms) is written to `build/report/index.html`."
        "\n".format(len(summary["exemplars"]), settings["width"], settings["height"],
                     settings["seed"]))
    threads = settings["threads"]
    share = summary["cpu_seconds"] / (summary["wall_seconds"] * threads)
    machine = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                    if line.startswith("model name")), "unknown CPU")
    out.append("This run: {}, {} threads, **{:.0f} s wall, {:.0f} s CPU** for the whole corpus."
               .format(machine, threads, summary["wall_seconds"], summary["cpu_seconds"]))
    if share < 0.8:
        out.append(
            "Other work shared the cores during the run, which got {:.0f}% of its {} threads' "
            "time: on idle cores the same work needs about {:.0f} s (CPU time / threads, if the "
            "pairs balance).".format(100 * share, threads, summary["cpu_seconds"] / threads))
    out.append("")
    out.append("""## The measures

All errors compare the synthesis with the exemplar (docs/design.md §8); lower is better.

| column | measure |
|---|---|
| spectral | relative L1 distance of Welch power spectra (Hann-windowed crops). The Gaussian version's value is what an ideal Gaussian texture scores: texton, lrp and gabor aim at that level, not at 0 |
| averaged | the same distance for the Welch spectrum averaged over the renders of {seeds} seeds: what is left is the synthesis's bias (its expected spectrum differs from the exemplar's), and the difference to "spectral" is one render's shot noise. The Gaussian version's value is the exemplar's own estimator noise |
| colour SW2 | sliced Wasserstein-2 distance of the pixel colours (64 fixed directions). "floor" is the exemplar's top half against its bottom half |
| covariance | relative Frobenius distance of the colour covariance matrices |
| non-stat. | non-stationarity: coefficient of variation, over 4×4-sample blocks, of the per-sample variance across 8 seeds on a 64×64 grid of point samples 2 exemplar pixels apart. The Gaussian version is exactly stationary, so its value is the estimator's own noise; a method well above it shows its lattice |
| analysis s | CPU seconds of one thread running the analysis with the default parameters |
| ns/sample | CPU nanoseconds per sample of one thread rendering the {w}×{h} image |

Reading it: a spectral error at the Gaussian version's level means the method reproduces the
spectrum as well as a Gaussian texture can; tiling, which blends patches of the exemplar itself,
can go below it. A colour error near the floor means the colour histogram is kept: tiling is the
only method built to keep it, so on non-Gaussian exemplars it should beat the Gaussian version,
while texton, lrp and gabor produce Gaussian-like histograms. A non-stationarity near the Gaussian
version's value means no lattice shows at this measure's resolution.

Times are thread CPU times, which other work sharing the cores changes little (the run used all
cores for independent (exemplar, method) pairs). How the per-sample costs compare with the papers'
GPU claims, and why, is in [docs/performance.md](performance.md#cpu-the-four-methods-side-by-side).
""".format(w=settings["width"], h=settings["height"], seeds=settings["averaged_seeds"]))

    # Summary per category: mean of each measure over the category's exemplars.
    out.append("## Summary per category\n")
    out.append(
        "Means over the exemplars of each category of `data/exemplars/ATTRIBUTION.md` "
        "(gaussian: micro-textures a Gaussian field models well; stochastic: random but "
        "non-Gaussian; structured: macro-structure, the failure cases of Gaussian models). "
        "No column ranks the methods: on bricks the lowest spectral error is texton's, whose "
        "picture has lost the bricks; \"auto\" counts the exemplars for which `--method auto` "
        "chooses the method (below).\n")
    for category in CATEGORIES:
        members = [e for e in summary["exemplars"] if corpus.get(e["name"], ("?",))[0] == category]
        if not members:
            continue
        out.append("### {} ({} exemplars)\n".format(category, len(members)))
        out.append("| | " + " | ".join(title for _, title, _ in MEASURES) + " | auto |")
        out.append("|---" * (len(MEASURES) + 2) + "|")
        for name in ["gaussian"] + methods:
            cells = []
            for key, _, form in MEASURES:
                values = [s[key] for e in members for s in e["syntheses"]
                          if s["name"] == name and key in s]
                cells.append(form.format(statistics.mean(values)) if values else "—")
            chosen = "" if name == "gaussian" else str(
                sum(e["auto"]["method"] == name for e in members))
            out.append("| {} | {} | {} |".format(label(name), " | ".join(cells), chosen))
        out.append("")

    out.extend(which_method(summary, corpus))

    out.append("## Per exemplar\n")
    out.append(
        "Thumbnails are {}-pixel reductions of the {}×{} renders. Below them, the log power "
        "spectra (DC at the centre, one scale per exemplar): the exemplar's, then each "
        "synthesis's averaged over {} seeds, where what still differs from the exemplar's is "
        "bias, not shot noise.\n".format(96, settings["width"], settings["height"],
                                          settings["averaged_seeds"]))
    for exemplar in summary["exemplars"]:
        name = exemplar["name"]
        category, content = corpus.get(name, ("?", ""))
        out.append("### {}\n".format(name))
        out.append("{}×{}, {} channel(s), {}: {}.\n".format(
            exemplar["width"], exemplar["height"], exemplar["channels"], category, content))
        cells = []
        spectra = []
        for kind in kinds:
            source = Path(thumbnails) / "{}_{}.png".format(name, kind)
            shutil.copyfile(source, Path(images) / source.name)
            cells.append("![{}]({}/{})".format(kind, link, source.name))
            # The report's pictures of the spectrum averaged over its seeds (the exemplar's own
            # spectrum for the exemplar), beside the same exemplar's, on one log scale.
            spectrum = Path(thumbnails).parent / name / "{}_spectrum_averaged.png".format(kind)
            copy = "{}_{}_spectrum.png".format(name, kind)
            shutil.copyfile(spectrum, Path(images) / copy)
            spectra.append("![{} averaged spectrum]({}/{})".format(kind, link, copy))
        out.append("| exemplar | " + " | ".join(label(k) for k in kinds[1:]) + " |")
        out.append("|---" * len(kinds) + "|")
        out.append("| " + " | ".join(cells) + " |")
        out.append("| " + " | ".join(spectra) + " |\n")
        out.append("| | " + " | ".join(title for _, title, _ in MEASURES) + " |")
        out.append("|---" * (len(MEASURES) + 1) + "|")
        for synthesis in exemplar["syntheses"]:
            out.append("| {} | {} |".format(label(synthesis["name"]), " | ".join(
                value(synthesis, key, form) for key, _, form in MEASURES)))
        out.append("| floor | | | {:.4f} |{}\n".format(exemplar["histogram_error_floor"],
                                                     " |" * (len(MEASURES) - 3)))
        out.append("`--method auto` chose {}\n".format(exemplar["auto"]["reason"]))
    print("\n".join(out))


if __name__ == "__main__":
    main()
