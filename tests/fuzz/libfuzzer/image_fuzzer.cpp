// Coverage-guided fuzzing (libFuzzer) of the image readers (docs/design.md §9): the input is an
// image file's bytes in any format, decoded from memory by decode_image, which shares read_image's
// decoders and recognises the format by its first bytes (PNG, OpenEXR, PFM, JPEG, TIFF, WebP, TGA;
// the seed corpus in tests/fuzz/corpus/image has each, and PNGs with colour chunks: iCCP, cICP).
// Each input is decoded twice: as stored, then with an ImageColour, which reads the colour chunks
// (the ICC profile through Little CMS) and converts the values. Every input must decode to a
// consistent image or be refused with stochtex::Error; with its colour, a PNG's values must be
// finite and its space sRGB or linear. Anything else (another exception, a crash, a sanitizer
// report, an allocation beyond libFuzzer's -rss_limit_mb) is a finding. Built by
// scripts/sanitize.sh.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "stochtex/io.hpp"

namespace {

void check_shape(const stochtex::ImageF& image) {
  const auto expected = static_cast<std::size_t>(image.width()) *
                        static_cast<std::size_t>(image.height()) *
                        static_cast<std::size_t>(image.channels());
  if (image.width() < 1 || image.height() < 1 || image.channels() < 1 || image.channels() > 4 ||
      image.pixels().size() != expected)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stochtex::ImageReadLimits limits;
  limits.max_pixels = std::int64_t{1} << 20;
  try {
    check_shape(stochtex::decode_image({data, size}, "the input", limits));
  } catch (const stochtex::Error&) {
  }
  try {
    stochtex::ImageColour colour;
    const stochtex::ImageF image =
        stochtex::decode_image({data, size}, "the input", limits, &colour);
    check_shape(image);
    if (colour.space == stochtex::ColourSpace::data || colour.origin.empty()) std::abort();
    const bool png = size >= 4 && std::memcmp(data, "\x89PNG", 4) == 0;
    if (png)
      for (const float value : image.pixels())
        if (!std::isfinite(value)) std::abort();
  } catch (const stochtex::Error&) {
  }
  return 0;
}
