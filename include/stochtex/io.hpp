#pragma once
// Image files (library stochtex::io; stochtex::runtime needs none of it).
// Reading: PNG (8/16-bit; grey, grey+alpha, RGB, RGBA; palette expanded), OpenEXR (half/float),
// PFM, recognised by their first bytes whatever the extension. Values become float32: PNG integers
// are divided by 255 or 65535, float formats are kept.
// Writing: by extension — .png (8-bit, or 16-bit with bit_depth 16; values clamped to [0,1] and
// rounded), .exr (float32), .pfm (1 or 3 channels). Files are written to a temporary of a unique
// name in the same folder, synced, then renamed, so a failure or a concurrent writer never leaves
// a partial output; only a missing path or a regular file is replaced. 1, 2, 3 or 4 channels.
// Every failure throws stochtex::Error with one sentence naming the file and the problem; a bad
// argument to write_image (unknown extension, bit depth other than 8 or 16, empty image) throws
// std::invalid_argument.

#include <cstdint>
#include <filesystem>

#include "stochtex/error.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

struct ImageReadLimits {
  std::int64_t max_pixels = std::int64_t{1} << 26;  // 64 Mpixel: refuse before allocating
};

ImageF read_image(const std::filesystem::path& path, const ImageReadLimits& limits = {});
void write_image(const std::filesystem::path& path, ImageView<const float> image,
                 int png_bit_depth = 8);

}  // namespace stochtex
