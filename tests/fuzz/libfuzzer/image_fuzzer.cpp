// Coverage-guided fuzzing (libFuzzer) of the image readers (docs/design.md §9): the input is an
// image file's bytes in any format, decoded from memory by decode_image, which shares read_image's
// decoders and recognises the format by its first bytes (PNG, OpenEXR, PFM; the seed corpus in
// tests/fuzz/corpus/image has each). Every input must decode to a consistent image or be refused
// with stochtex::Error; anything else (another exception, a crash, a sanitizer report, an
// allocation beyond libFuzzer's -rss_limit_mb) is a finding. Built by scripts/sanitize.sh.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "stochtex/error.hpp"
#include "stochtex/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    stochtex::ImageReadLimits limits;
    limits.max_pixels = std::int64_t{1} << 20;
    const stochtex::ImageF image = stochtex::decode_image({data, size}, "the input", limits);
    const auto expected = static_cast<std::size_t>(image.width()) *
                          static_cast<std::size_t>(image.height()) *
                          static_cast<std::size_t>(image.channels());
    if (image.width() < 1 || image.height() < 1 || image.channels() < 1 || image.channels() > 4 ||
        image.pixels().size() != expected)
      std::abort();
  } catch (const stochtex::Error&) {
  }
  return 0;
}
