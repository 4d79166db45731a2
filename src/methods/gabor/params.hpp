#pragma once
// Gabor noise by example parameters (Galerne, Lagae, Lefebvre, Drettakis, "Gabor Noise by
// Example", ACM TOG 2012), described once (methods/param_record.hpp). The record feeds the CLI
// (`-p name=value`), the model file and docs/methods/gabor.md.

#include <array>

#include "methods/param_record.hpp"

namespace stochtex::gabor {

// Colour spaces of section 7, in which each channel is synthesised independently.
enum class ColourSpace { independent = 0, pca = 1, rgb = 2 };

struct Params {
  double kappa = 1.0 / 1024.0;
  int impulses = 1024;
  ColourSpace colour_space = ColourSpace::pca;
  int iterations = 300;
  double weighting = 0.25;
  int narrowest = 0;
  bool renormalise = true;

  bool operator==(const Params&) const = default;
};

inline constexpr std::array<ParamChoice, 3> kColourSpaces = {
    {{"independent", 0}, {"pca", 1}, {"rgb", 2}}};

inline constexpr std::array<ParamField<Params>, 7> kFields = {{
    number_field<&Params::kappa>(
        "kappa", 1.0 / 65536.0, 1.0,
        "relative regularisation: nu = kappa nu_max in the basis pursuit denoising of eq. (8); "
        "smaller keeps more Gaussians and fits the spectrum closer (section 5.2)"),
    number_field<&Params::impulses>(
        "impulses", 1, 65536,
        "impulse budget N: the expected number of Gabor kernels overlapping a point, split over "
        "the Gaussians by variance (section 6.2); the evaluation cost per sample grows linearly "
        "with it"),
    choice_field<&Params::colour_space>(
        "colour_space", kColourSpaces,
        "colour space of the independent channel synthesis (section 7): pca, PCA (orthogonal: the "
        "channels' power spectra sum to the exemplar's, docs); independent, maximally independent "
        "(approximate joint diagonalisation, the paper's); rgb, RGB"),
    number_field<&Params::iterations>(
        "iterations", 1, 100000,
        "most FISTA iterations per step of the kappa homotopy (section 5.3); the last step stops "
        "earlier when the duality gap certifies the objective within 1% of its optimum"),
    number_field<&Params::weighting>(
        "weighting", 0.0, 1.0,
        "exponent gamma of the data weights of the fit, (smoothed periodogram)^-gamma: 0 is the "
        "paper's unweighted eq. (8), which drops the weak, diffuse part of a spectrum; 1/2 makes "
        "the l1 shrinkage proportional to the local spectrum level (docs)"),
    chosen_number_field<&Params::narrowest>(
        "narrowest", 1, 64,
        "FWHM of the dictionary's narrowest band, in frequency bins of the exemplar (section 4.3): "
        "1 is the paper's (down to one bin); 0 chooses per channel: 4 bins, or 1 when the 4-bin "
        "fit stays above the periodogram's noise level (a spectrum with sharp features). One-bin "
        "Gaussians fitted to a diffuse spectrum's periodogram noise become kernels hundreds of "
        "pixels wide, too few per render for the impulse budget (docs)"),
    choice_field<&Params::renormalise>(
        "renormalise", kSwitch,
        "on: each synthesis channel's Gaussians are scaled together so that its noise has the "
        "variance of its periodogram, as ADSN's (our addition: the l1 shrinkage lowers it, a fit "
        "coarser than the spectrum's features raises it; docs); off: as fitted (the paper)"),
}};

inline constexpr auto kParams = param_infos(kFields);

}  // namespace stochtex::gabor
