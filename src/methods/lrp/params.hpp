#pragma once
// Local random-phase noise parameters (Gilet, Sauvage, Vanhoey, Dischler, Ghazanfarpour, "Local
// Random-Phase Noise for Procedural Texturing", ACM TOG 2014), described once
// (methods/param_record.hpp). The record feeds the CLI (`-p name=value`), the model file and
// docs/methods/lrp.md.

#include <array>

#include "methods/param_record.hpp"

namespace stochtex::lrp {

struct Params {
  int cosines = 50;
  int strata = 8;
  bool envelope = true;
  bool amplitudes = true;
  bool deblur = true;
  double widen = 1;
  double spacing = 24;
  double ratio = 0;
  double turbulence = 0;
  bool placement = true;

  bool operator==(const Params&) const = default;
};

inline constexpr std::array<ParamField<Params>, 10> kFields = {{
    number_field<&Params::cosines>(
        "cosines", 1, 2000,
        "cosine budget J per channel (sections 4.1, 6.3): each stratum gets J_S = J / L cosines "
        "(at least one); a sample costs 9 (J + L) cosines and windows per channel"),
    number_field<&Params::strata>(
        "strata", 1, 16,
        "number L of equal-energy strata of the power spectrum (section 4.2; the paper uses 4, "
        "tuned on 128-256 pixel exemplars; 8 keeps the strong low-frequency strata narrow, docs)"),
    choice_field<&Params::envelope>(
        "envelope", kSwitch,
        "on: divide each stratum's noise by the root of the local sum of squared windows so that "
        "the variance is the same everywhere (our addition, docs/methods/lrp.md); off: equation "
        "(1) as published, whose variance varies over a lattice cell"),
    choice_field<&Params::amplitudes>(
        "amplitudes", kSwitch,
        "on: each frequency's amplitude follows the target's power inside its sub-stratum, so the "
        "expected spectrum follows the target within a stratum (our addition, "
        "docs/methods/lrp.md); off: one amplitude A_S per stratum (equation 3 as published)"),
    choice_field<&Params::deblur>(
        "deblur", kSwitch,
        "on: undo most of the Hann window's blur of Welch's estimate (section 4.4), which a render "
        "measured again would otherwise show twice (our addition, docs/methods/lrp.md); off: the "
        "estimate as published"),
    number_field<&Params::widen>(
        "widen", 1, 16,
        "factor on section 4.3's lattice spacing Delta_S, before the floor `spacing` (our "
        "addition, docs/methods/lrp.md): the paper's J_S footprints of radius 1 / Delta_S cover "
        "2 pi times their stratum and blur narrow spectra (2 suits a brushed metal's lines); a "
        "wider spacing narrows them at no cost per sample but leaves fewer nodes, so one render's "
        "statistics vary more; 1: Delta_S as published"),
    number_field<&Params::spacing>(
        "spacing", 0, 1024,
        "smallest lattice spacing Delta_S in pixels (our floor on section 4.3's Delta_S, "
        "docs/methods/lrp.md): a wider spacing narrows each cosine's spectral footprint at no "
        "cost per sample; 0: Delta_S as published"),
    number_field<&Params::ratio>(
        "ratio", 0, 1,
        "energy ratio r of the fixed-phase region R (section 5.1): the highest-power frequencies "
        "holding this fraction of the energy keep the exemplar's phases, with J_R = rJ cosines "
        "per block (section 5.3); 0: pure noise, 1: the exemplar's structure alone"),
    number_field<&Params::turbulence>(
        "turbulence", 0, 256,
        "turbulence sigma (section 5.2): the structure is read at x + sigma n_T(x), n_T = sum_S "
        "|n_S| a unit-variance noise of the exemplar's spectrum per axis; in exemplar pixels, "
        "about the size of the texture's features"),
    choice_field<&Params::placement>(
        "placement", kSwitch,
        "on: random placement (section 5.2), blocks of half the structure period shifted by "
        "hashed offsets and blended at their borders; off: the structure repeats with period T"),
}};

inline constexpr auto kParams = param_infos(kFields);

}  // namespace stochtex::lrp
