#pragma once
// Image files (library stochtex::io; stochtex::runtime needs none of it), on disk or in memory.
// Reading: PNG (8/16-bit; grey, grey+alpha, RGB, RGBA; palette expanded), OpenEXR (half/float),
// PFM, recognised by their first bytes whatever the extension. Values become float32: PNG integers
// are divided by 255 or 65535, float formats are kept.
// Colour on input (docs/design.md §14): without an ImageColour, read_image and decode_image give
// those stored values and look at no colour chunk. With one, they honour what the file says its
// values are and fill it; the values returned are then sRGB-encoded or linear light (never data:
// a user says data, and the caller keeps the values as they are). A PNG's colour is its first
// chunk in the PNG specification's (3rd edition) order of precedence, among those before its
// pixels:
//   cICP  BT.709 primaries, RGB, full range, with the sRGB transfer (13): srgb; linear transfer
//         (8): linear; values unchanged. Any other cICP (HDR PQ or HLG, other primaries, video
//         range) is refused.
//   iCCP  an ICC profile (Little CMS): one that maps test colours onto sRGB within 1/4096 of
//         linear light leaves the values, srgb; any other is converted to sRGB (relative
//         colorimetric, on floats; grey images to grey with the sRGB tone curve), srgb. A
//         profile that cannot be read or used, or whose colour space is not the image's (an RGB
//         profile on grey, CMYK), is refused.
//   sRGB  srgb, values unchanged.
//   gAMA  file gamma g: 1.0 is linear, values unchanged; any other converts each value v to
//         srgb_encode(v^(1/g)), srgb. cHRM is ignored.
//   none  srgb ("no colour chunk: sRGB by default").
// The colour chunk that decides, if it cannot be read (a bad checksum, a wrong length), refuses
// the file. OpenEXR and PFM are linear, values unchanged. Conversions affect the colour channels
// only (is_colour_channel: an alpha channel is data), clamp nothing and keep every value finite:
// a wider profile's colours outside sRGB's gamut leave [0, 1], below 0 through the sRGB curve
// extended to negative light (Adobe RGB's pure green has a red of -5.1).
// Writing: by extension — .png (8-bit, or 16-bit with bit_depth 16; values clamped to [0,1] and
// rounded), .exr (float32), .pfm (1 or 3 channels). Files are written to a temporary of a unique
// name in the same folder, synced, then renamed, so a failure or a concurrent writer never leaves
// a partial output; only a missing path or a regular file is replaced. 1, 2, 3 or 4 channels.
// Colour on output (docs/design.md §14): `space` says what the image's values are. data (the
// default) is written as it is, with no colour chunk. linear: a PNG's colour channels are encoded
// with the sRGB transfer function before they are clamped and rounded, and the PNG gets an sRGB
// chunk (with the gAMA and cHRM chunks the PNG specification recommends beside it for decoders
// that do not know sRGB); OpenEXR and PFM get the values as they are. srgb: a PNG gets the values
// as they are and the sRGB chunk; OpenEXR and PFM get the colour channels decoded to linear light.
// Alpha is written as it is.
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

#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

struct ImageReadLimits {
  std::int64_t max_pixels = std::int64_t{1} << 26;  // 64 Mpixel: refuse before allocating
  // Called with the size and channels the file declares, before its pixels are decoded: a caller
  // refuses there (throws) what its own memory budget cannot hold.
  std::function<void(int width, int height, int channels)> check_declared;
};

// What an image file says its values are, as read_image found it.
struct ImageColour {
  ColourSpace space = ColourSpace::srgb;  // srgb or linear, never data
  // One short phrase for `stochtex info` and messages: "sRGB chunk", "no colour chunk: sRGB by
  // default", "gAMA 0.45455, converted to sRGB", "ICC profile 'Adobe RGB (1998)', converted to
  // sRGB", "cICP: linear", "OpenEXR: linear".
  std::string origin;
};

// The formats write_image and encode_image write.
enum class ImageFormat { png, exr, pfm };

// `colour`: none gives the stored values; one gives them in colour->space and fills it (above).
ImageF read_image(const std::filesystem::path& path, const ImageReadLimits& limits = {},
                  ImageColour* colour = nullptr);
// `space`: what the values of `image` are (above); data writes them as they are.
void write_image(const std::filesystem::path& path, ImageView<const float> image,
                 int png_bit_depth = 8, ColourSpace space = ColourSpace::data);

// read_image of an image file's bytes held in memory. The messages call them `name`, written as
// given (read_image's are the path in quotes): "the uploaded image is truncated...".
ImageF decode_image(std::span<const std::uint8_t> bytes, const std::string& name,
                    const ImageReadLimits& limits = {}, ImageColour* colour = nullptr);
// The bytes write_image would write for a file of `format`.
std::vector<std::uint8_t> encode_image(ImageView<const float> image, ImageFormat format,
                                       int png_bit_depth = 8,
                                       ColourSpace space = ColourSpace::data);

}  // namespace stochtex
