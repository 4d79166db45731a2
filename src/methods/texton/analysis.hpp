#pragma once

#include <cstdint>

#include "methods/texton/model.hpp"
#include "methods/texton/params.hpp"
#include "stochtex/image.hpp"

namespace stochtex::texton {

// Algorithm 1 of the paper with the colour projection and colour covariance correction of
// section 4.3.
TextonModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed);

}  // namespace stochtex::texton
