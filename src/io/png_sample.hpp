#pragma once
// How a float value becomes a PNG sample: write_image's rule (image_io.cpp), shared with the GL
// exporter, which quantises its PNG data images the same way so the renderer binds what the files
// hold (gl/twin.hpp quantized).

#include <cmath>

namespace stochtex {

// NaN and values below 0 become 0, values above 1 become `maximum` (255 or 65535).
inline unsigned png_sample(float value, unsigned maximum) {
  if (!(value > 0.0f)) return 0;
  if (value >= 1.0f) return maximum;
  return static_cast<unsigned>(std::lround(value * static_cast<float>(maximum)));
}

}  // namespace stochtex
