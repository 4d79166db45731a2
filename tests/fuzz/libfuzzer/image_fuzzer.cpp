// Coverage-guided fuzzing (libFuzzer) of the image readers (docs/design.md §9): the input is a file
// of any format, recognised by its first bytes as read_image does (PNG, OpenEXR, PFM; the seed
// corpus in tests/fuzz/corpus/image has each). Every input must read as a consistent image or be
// refused with stochtex::Error; anything else (another exception, a crash, a sanitizer report, an
// allocation beyond libFuzzer's -rss_limit_mb) is a finding. Built by scripts/sanitize.sh.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "input_file.hpp"
#include "stochtex/error.hpp"
#include "stochtex/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& input_path = write_input_file("image", "", data, size);
  try {
    stochtex::ImageReadLimits limits;
    limits.max_pixels = std::int64_t{1} << 20;
    const stochtex::ImageF image = stochtex::read_image(input_path, limits);
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
