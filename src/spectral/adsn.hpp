#pragma once
// ADSN, the Gaussian version of an exemplar (Galerne, Gousseau, Morel 2011; texton paper 3.1):
// the normalised kernel t = (p - mean(p)) / sqrt(|Omega|) of the periodic component p, convolved
// with one standard Gaussian white noise shared by all channels (so colour correlations are kept),
// plus mean(u). Any output size: the noise lives on a domain large enough that the convolution
// does not wrap (the result is an exact, non-periodic ADSN sample).

#include <cstdint>

#include "stochtex/image.hpp"

namespace stochtex {

ImageF adsn(ImageView<const float> exemplar, int width, int height, std::uint32_t seed);

}  // namespace stochtex
