#pragma once
// Gabor noise by example parameters (Galerne, Lagae, Lefebvre, Drettakis, "Gabor Noise by
// Example", ACM TOG 2012), described once. The record feeds the CLI (`-p name=value`), the model
// file and docs/methods/gabor.md.

#include <array>

#include "stochtex/model.hpp"

namespace stochtex::gabor {

// Colour spaces of section 7, in which each channel is synthesised independently.
enum class ColourSpace { independent = 0, pca = 1, rgb = 2 };
inline constexpr std::array<double, 3> kAllowedColourSpaces = {0, 1, 2};

inline constexpr std::array<ParamInfo, 4> kParams = {{
    {"kappa", 1.0 / 256.0, 1.0 / 65536.0, 1.0, false,
     "relative regularisation: nu = kappa nu_max in the basis pursuit denoising of eq. (8); "
     "smaller keeps more Gaussians and fits the spectrum closer (section 5.2)"},
    {"impulses", 1024, 1, 65536, true,
     "impulse budget N: the expected number of Gabor kernels overlapping a point, split over the "
     "Gaussians by variance (section 6.2); the evaluation cost per sample grows linearly with it"},
    {"colour_space", 0, 0, 2, true,
     "colour space of the independent channel synthesis (section 7): 0 maximally independent "
     "(approximate joint diagonalisation), 1 PCA, 2 RGB",
     kAllowedColourSpaces},
    {"iterations", 300, 1, 100000, true,
     "most FISTA iterations per step of the kappa homotopy (section 5.3); the last step stops "
     "earlier when the duality gap certifies the objective within 1% of its optimum"},
}};

}  // namespace stochtex::gabor
