#pragma once

#include <cstdint>
#include <type_traits>

#include "methods/texton/model.hpp"
#include "methods/texton/params.hpp"
#include "stochtex/image.hpp"

namespace stochtex::texton {

// Algorithm 1 of the paper with the colour projection and colour covariance correction of
// section 4.3.
TextonModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed);

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<TextonModel>) {
  return {
      "texton noise (Galerne, Leclaire, Moisan 2017): a small texton summarising the "
      "spectrum, ~30 fetches per sample",
      kFields,
      {.per_pixel = 28, .per_channel = 20}};
}

}  // namespace stochtex::texton
