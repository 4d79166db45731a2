#pragma once

#include <cstdint>
#include <span>
#include <type_traits>

#include "methods/texton_mix/model.hpp"
#include "methods/texton_mix/params.hpp"
#include "stochtex/image.hpp"

namespace stochtex::texton_mix {

// Section 7 of the texton paper: the kernels tau_rho = (1 - rho) tau_0 + rho t_B of the
// optimal-transport barycentres between the Gaussian models of A and B (tau_0 is t_A with the
// phase of its projection on t_B), for rho = k / (steps - 1), each turned into a texton by
// Algorithm 1 from the same white-noise initialisation. A and B have the same channel count; the
// larger is centre-cropped to the smaller's width and height (the barycentre is taken frequency by
// frequency on one DFT grid). `field` is the mixing field the model keeps.
TextonMixModel analyze(ImageView<const float> a, ImageView<const float> b, const Params& params,
                       MixField field, std::uint32_t seed);

// This method's parameter record for the registry (src/registry.cpp). It has no registry row: it
// is made from two exemplars by `stochtex mix` (stochtex::mix), not by `stochtex analyze`.
constexpr std::span<const ParamInfo> params_of(std::type_identity<TextonMixModel>) {
  return kParams;
}

}  // namespace stochtex::texton_mix
