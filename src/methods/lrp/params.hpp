#pragma once
// Local random-phase noise parameters (Gilet, Sauvage, Vanhoey, Dischler, Ghazanfarpour, "Local
// Random-Phase Noise for Procedural Texturing", ACM TOG 2014), described once. The record feeds
// the CLI (`-p name=value`), the model file and docs/methods/lrp.md.

#include <array>

#include "stochtex/model.hpp"

namespace stochtex::lrp {

inline constexpr std::array<double, 2> kAllowedSwitch = {0, 1};

inline constexpr std::array<ParamInfo, 7> kParams = {{
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
    {"ratio", 0, 0, 1, false,
     "energy ratio r of the fixed-phase region R (section 5.1): the highest-power frequencies "
     "holding this fraction of the energy keep the exemplar's phases, with J_R = rJ cosines per "
     "block (section 5.3); 0: pure noise, 1: the exemplar's structure alone"},
    {"turbulence", 0, 0, 256, false,
     "turbulence sigma (section 5.2): the structure is read at x + sigma n_T(x), n_T = sum_S "
     "|n_S| a unit-variance noise of the exemplar's spectrum per axis; in exemplar pixels, about "
     "the size of the texture's features"},
    {"placement", 1, 0, 1, true,
     "1: random placement (section 5.2), blocks of half the structure period shifted by hashed "
     "offsets and blended at their borders; 0: the structure repeats with period T",
     kAllowedSwitch},
}};

}  // namespace stochtex::lrp
