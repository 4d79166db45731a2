// Coverage-guided fuzzing (libFuzzer) of the image readers (docs/design.md §9): the input is a file
// of any format, recognised by its first bytes as read_image does (PNG, OpenEXR, PFM; the seed
// corpus in tests/fuzz/corpus/image has each). Every input must read as a consistent image or be
// refused with stochtex::Error; anything else (another exception, a crash, a sanitizer report, an
// allocation beyond libFuzzer's -rss_limit_mb) is a finding. Built by scripts/sanitize.sh.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "stochtex/error.hpp"
#include "stochtex/io.hpp"

namespace {

// read_image takes a path: each input goes to one file of this process.
const std::string& input_path() {
  static const std::string path = "/tmp/stochtex-image-fuzzer-" + std::to_string(getpid());
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::FILE* file = std::fopen(input_path().c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  try {
    stochtex::ImageReadLimits limits;
    limits.max_pixels = std::int64_t{1} << 20;
    const stochtex::ImageF image = stochtex::read_image(input_path(), limits);
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
