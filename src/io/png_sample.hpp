#pragma once
// How a float value becomes a PNG sample: write_image's rule (image_io.cpp), shared with the GL
// exporter, which quantises its PNG data images the same way so the renderer binds what the files
// hold (gl/twin.hpp quantized).

#include <array>
#include <bit>
#include <cstdint>

namespace stochtex {

// NaN and values below 0 become 0, values above 1 become `maximum` (255 or 65535); the others
// value * maximum rounded to the nearest, halves up: std::lround's result without its call.
inline unsigned png_sample(float value, unsigned maximum) {
  if (!(value > 0.0f)) return 0;
  if (value >= 1.0f) return maximum;
  const float scaled = value * static_cast<float>(maximum);
  const auto whole = static_cast<unsigned>(scaled);
  // Exact: `whole` is 0 or within a factor 2 of `scaled`.
  return whole + (scaled - static_cast<float>(whole) >= 0.5f ? 1u : 0u);
}

// The 8-bit sample of a linear value sRGB-encoded, png_sample(srgb_encode(linear), 255), for
// every float, from a table instead of a power per value (a 2048x2048 colour render has 12.6
// million). The floats from 2^-14 to 1 are cut into buckets of 2^15 consecutive bit patterns, over
// which the sample rises by at most 1: each bucket holds the sample of its first float and the
// first float of the next sample. Below 2^-14 the sample is 0, from 1 on 255. Built once (about
// 11,000 powers); tests/unit/image_io_test.cpp compares it with the formula on every float of
// the table's range.
class SrgbSamples8 {
 public:
  static const SrgbSamples8& get();

  unsigned operator()(float linear) const {
    if (!(linear >= kLow)) return 0;  // NaN too
    if (linear >= 1.0f) return 255;
    const std::uint32_t bucket = (std::bit_cast<std::uint32_t>(linear) - kLowBits) >> kShift;
    return samples_[bucket] + (linear >= next_[bucket] ? 1u : 0u);
  }

  static constexpr float kLow = 0x1p-14f;

 private:
  static constexpr int kShift = 15;
  static constexpr std::uint32_t kLowBits = std::bit_cast<std::uint32_t>(kLow);
  static constexpr std::size_t kBuckets = (std::bit_cast<std::uint32_t>(1.0f) - kLowBits) >> kShift;

  SrgbSamples8();

  std::array<float, kBuckets> next_;
  std::array<std::uint8_t, kBuckets> samples_;
};

}  // namespace stochtex
