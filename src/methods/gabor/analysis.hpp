#pragma once
// Gabor noise by example, analysis (sections 3.2, 5 and 7): the periodogram of the periodic
// component, its sparse non-negative decomposition into bandwidth-quantised Gaussians, and the
// colour space of the independent channel synthesis. The pieces are public for tests: the
// dictionary (dictionary.hpp), the spectrum fit (fit.hpp) and the colour space (colour_space.hpp).

#include <cstdint>
#include <functional>
#include <type_traits>

#include "methods/gabor/edit_analysis.hpp"
#include "methods/gabor/model.hpp"
#include "methods/gabor/params.hpp"
#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::gabor {

// The method's analysis. `progress` (may be empty) is called from the calling thread with the
// fraction done, at each iteration of the fit that thread runs; an exception it throws stops every
// channel's fit at its next iteration and is rethrown.
GaborModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                   const std::function<void(double)>& progress = {});

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<GaborModel>) {
  return {.summary =
              "Gabor noise by example (Galerne, Lagae, Lefebvre, Drettakis 2012): a sparse "
              "sum of bandwidth-quantised Gaussians fitted to the spectrum, ~2N kernels per "
              "sample",
          .fields = kFields,
          .analysis_memory = {.per_pixel = 200, .per_channel = 260},
          .max_channels = kMaxChannels,
          // The sparse fit takes about 100 times the other methods' analyses per pixel.
          .analysis_cost = 100.0,
          // 1024x768 took 4 minutes (a phone photo downscaled): 512 keeps it near one.
          .analysis_side = 512,
          .edit = &kEdit};
}

}  // namespace stochtex::gabor
