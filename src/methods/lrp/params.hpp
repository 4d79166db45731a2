#pragma once
// Local random-phase noise parameters (Gilet, Sauvage, Vanhoey, Dischler, Ghazanfarpour, "Local
// Random-Phase Noise for Procedural Texturing", ACM TOG 2014), described once. The record feeds
// the CLI (`-p name=value`), the model file and docs/methods/lrp.md.

#include <array>

#include "stochtex/model.hpp"

namespace stochtex::lrp {

inline constexpr std::array<double, 2> kAllowedSwitch = {0, 1};

inline constexpr std::array<ParamInfo, 4> kParams = {{
    {"cosines", 50, 1, 2000, true,
     "cosine budget J per channel (sections 4.1, 6.3): each stratum gets J_S = J / L cosines (at "
     "least one); a sample costs 9 (J + L) cosines and windows per channel"},
    {"strata", 4, 1, 16, true,
     "number L of equal-energy strata of the power spectrum (section 4.2; the paper uses 4)"},
    {"envelope", 1, 0, 1, true,
     "1: divide each stratum's noise by the root of the local sum of squared windows so that the "
     "variance is the same everywhere (our addition, docs/methods/lrp.md); 0: equation (1) as "
     "published, whose variance varies over a lattice cell",
     kAllowedSwitch},
    {"amplitudes", 1, 0, 1, true,
     "1: each frequency's amplitude follows the target's power inside its sub-stratum, so the "
     "expected spectrum follows the target within a stratum (our addition, docs/methods/lrp.md); "
     "0: one amplitude A_S per stratum (equation 3 as published)",
     kAllowedSwitch},
}};

}  // namespace stochtex::lrp
