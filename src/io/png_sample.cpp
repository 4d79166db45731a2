#include "io/png_sample.hpp"

#include <limits>
#include <stdexcept>

#include "core/srgb.hpp"

namespace stochtex {
namespace {

unsigned formula(std::uint32_t bits) {
  return png_sample(srgb_encode(std::bit_cast<float>(bits)), 255);
}

}  // namespace

const SrgbSamples8& SrgbSamples8::get() {
  static const SrgbSamples8 table;
  return table;
}

SrgbSamples8::SrgbSamples8() {
  for (std::size_t bucket = 0; bucket < kBuckets; ++bucket) {
    const std::uint32_t first = kLowBits + (static_cast<std::uint32_t>(bucket) << kShift);
    const std::uint32_t last = first + (std::uint32_t{1} << kShift) - 1;
    const unsigned sample = formula(first);
    samples_[bucket] = static_cast<std::uint8_t>(sample);
    next_[bucket] = std::numeric_limits<float>::infinity();
    if (formula(last) == sample) continue;
    // A bucket spans 2^-8 of its float's binade: the sample rises by at most 0.44 over one, near 1.
    if (formula(last) != sample + 1)
      throw std::logic_error("SrgbSamples8: a bucket spans more than two samples");
    std::uint32_t low = first;  // formula(low) == sample
    std::uint32_t high = last;  // formula(high) == sample + 1
    while (high - low > 1) {
      const std::uint32_t middle = low + (high - low) / 2;
      (formula(middle) == sample ? low : high) = middle;
    }
    next_[bucket] = std::bit_cast<float>(high);
  }
}

}  // namespace stochtex
