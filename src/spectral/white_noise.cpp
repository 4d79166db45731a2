#include "spectral/white_noise.hpp"

#include <cmath>
#include <numbers>

#include "core/hash.hpp"

namespace stochtex {

std::vector<float> gaussian_white_noise(std::size_t count, std::uint32_t key) {
  CounterRng rng(key);
  std::vector<float> noise(count);
  for (std::size_t i = 0; i < count; i += 2) {
    // One draw per statement: the order of the two draws is then fixed (docs/design.md §5).
    const float u = rng.uniform();
    const float v = rng.uniform();
    // 1 - u is in (0, 1], so the logarithm is finite.
    const double radius = std::sqrt(-2.0 * std::log(1.0 - static_cast<double>(u)));
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(v);
    noise[i] = static_cast<float>(radius * std::cos(angle));
    if (i + 1 < count) noise[i + 1] = static_cast<float>(radius * std::sin(angle));
  }
  return noise;
}

}  // namespace stochtex
