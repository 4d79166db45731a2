#pragma once
// Standard Gaussian white noise for the analyses (ADSN, the texton initialisation of Algorithm 1),
// drawn from the counter-based generator of docs/design.md §5 so that it is a pure function of
// the key and identical on every platform.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace stochtex {

// `count` independent N(0, 1) values (Box-Muller on pairs of 24-bit uniforms).
std::vector<float> gaussian_white_noise(std::size_t count, std::uint32_t key);

}  // namespace stochtex
