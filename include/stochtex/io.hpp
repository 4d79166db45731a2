#pragma once
// Image files (library stochtex::io; stochtex::runtime needs none of it), on disk or in memory.
// Reading: PNG (8/16-bit; grey, grey+alpha, RGB, RGBA; palette expanded), OpenEXR (half/float),
// PFM, recognised by their first bytes whatever the extension. Values become float32: PNG integers
// are divided by 255 or 65535, float formats are kept.
// Writing: by extension — .png (8-bit, or 16-bit with bit_depth 16; values clamped to [0,1] and
// rounded), .exr (float32), .pfm (1 or 3 channels). Files are written to a temporary of a unique
// name in the same folder, synced, then renamed, so a failure or a concurrent writer never leaves
// a partial output; only a missing path or a regular file is replaced. 1, 2, 3 or 4 channels.
// A file and a buffer go through the same decoder and encoder: decode_image of a file's bytes
// gives read_image's image or error, and encode_image gives the bytes write_image writes.
// Every failure throws stochtex::Error with one sentence naming the file (or the buffer, by the
// name the caller gives it) and the problem; a bad argument to write_image or encode_image
// (unknown extension, bit depth other than 8 or 16, empty image) throws std::invalid_argument.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "stochtex/error.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

struct ImageReadLimits {
  std::int64_t max_pixels = std::int64_t{1} << 26;  // 64 Mpixel: refuse before allocating
  // Called with the size and channels the file declares, before its pixels are decoded: a caller
  // refuses there (throws) what its own memory budget cannot hold.
  std::function<void(int width, int height, int channels)> check_declared;
};

// The formats write_image and encode_image write.
enum class ImageFormat { png, exr, pfm };

ImageF read_image(const std::filesystem::path& path, const ImageReadLimits& limits = {});
void write_image(const std::filesystem::path& path, ImageView<const float> image,
                 int png_bit_depth = 8);

// read_image of an image file's bytes held in memory. The messages call them `name`, written as
// given (read_image's are the path in quotes): "the uploaded image is truncated...".
ImageF decode_image(std::span<const std::uint8_t> bytes, const std::string& name,
                    const ImageReadLimits& limits = {});
// The bytes write_image would write for a file of `format`.
std::vector<std::uint8_t> encode_image(ImageView<const float> image, ImageFormat format,
                                       int png_bit_depth = 8);

}  // namespace stochtex
