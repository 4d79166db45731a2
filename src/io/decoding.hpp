#pragma once
// What every image decoder of read_image shares (image_io.cpp's codec table): the input being
// decoded, the checks of a declared size before anything proportional to it is allocated
// (docs/design.md §9) and the colour of an embedded ICC profile (docs/design.md §14). One file per
// format holds its decoder: PNG, OpenEXR and PFM in image_io.cpp (they are also written), JPEG,
// TIFF, WebP and TGA in their own files.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/io.hpp"

namespace stochtex {

// An image file's bytes being decoded: a stdio stream at its start (the file, or a buffer opened
// with fmemopen), their count, and what the messages call them.
struct Input {
  std::FILE* file = nullptr;
  std::uintmax_t bytes = 0;
  std::string name;         // in stochtex's messages: the path in quotes, or the caller's name
  std::string stream_name;  // in OpenEXR's messages: the path as it is, or the caller's name
};

// The whole input, for the decoders that take a buffer (WebP, TGA): Error(format) before reading,
// when it is larger than `max_bytes`, the most a valid file of its format can hold; Error(io)
// when it cannot be read.
std::vector<unsigned char> read_all(const Input& input, double max_bytes);

// Refuses a declared size before anything proportional to it is allocated (docs/design.md §9):
// Error(format) for a size below one pixel, Error(invalid_input) beyond limits.max_pixels.
void check_size(const std::string& name, std::int64_t width, std::int64_t height,
                const ImageReadLimits& limits);

// The caller's refusal of a size its memory budget cannot hold, once the size and channels are
// known (check_size passed) and before the pixels are allocated.
void check_declared(std::int64_t width, std::int64_t height, int channels,
                    const ImageReadLimits& limits);

// Deflate codes a 258-byte match in 2 bits at best, so zlib data never expands more than 1032
// times: the bound behind every minimum compressed size of a deflated format.
constexpr double kMaxDeflateRatio = 1032.0;

// A tiny file declaring a huge image must not cost the image's memory: what the declared pixels
// need at least, compressed as well as the format possibly can, is compared with the file's size
// before anything proportional to the pixels is allocated. Error(format) when they do not fit.
void check_fits_file(const std::string& name, std::int64_t width, std::int64_t height,
                     double minimum_bytes, std::uintmax_t file_bytes);

// Text from a file (a profile's description, a library's warning quoting a name), for a message:
// printable ASCII, other bytes as '?', at most `limit` characters.
std::string printable(std::string_view text, std::size_t limit);

// `image` as displayed, where a file's orientation tag (EXIF or TIFF: 1 to 8, TIFF 6.0
// "Orientation") says where its stored rows and columns go; 1 and unknown values leave it as it is.
ImageF oriented(ImageF image, int orientation);

// ImageColour::origin of an image of `channels` whose ICC profile is RGB on grey or grey on RGB:
// the profile is ignored and the values are sRGB, as browsers read them.
std::string mismatched_profile_origin(int channels);

// What an image's embedded ICC profile makes of its values: Little CMS opens the profile and
// decides by what it does whether it is sRGB; if not, convert() turns the colour channels into
// sRGB-encoded ones, relative colorimetric (the alpha channel stays as it is).
class IccConversion;
class IccColour {
 public:
  // Refuses (Error(format), one sentence naming `name`) a profile Little CMS cannot open or turn
  // into a transform, or whose colour space is neither grey nor RGB. A grey profile on an RGB
  // image, or an RGB one on grey, is ignored (mismatched_profile_origin).
  IccColour(std::span<const unsigned char> profile, int channels, const std::string& name);
  ~IccColour();
  IccColour(const IccColour&) = delete;
  IccColour& operator=(const IccColour&) = delete;

  // For ImageColour::origin: "ICC profile 'Display P3': sRGB" or "ICC profile 'Adobe RGB (1998)',
  // converted to sRGB" (a profile without a description: "ICC profile without a description").
  const std::string& origin() const { return origin_; }
  // Converts the colour channels of `image` (of the constructor's channels) to sRGB, in place;
  // nothing when the profile is sRGB. Values the profile makes infinite or NaN become 0.
  void convert(ImageF& image) const;

 private:
  std::unique_ptr<IccConversion> conversion_;  // null when the profile is sRGB
  std::string origin_;
};

// The image of 8-bit `samples` (width x height x channels, row after row: each value / 255) and,
// with `colour`, its colour: converted by `icc` where there is one, else sRGB, which `format`
// ("JPEG") says by default.
ImageF image_of_bytes(std::span<const unsigned char> samples, int width, int height, int channels,
                      const IccColour* icc, const char* format, ImageColour* colour);

// The decoders of the formats stochtex reads but does not write: whether the first bytes of a
// file (at least 8 where the file has them) are the format's, and the image they hold, like
// read_image (`colour`: null gives the stored values; otherwise they are read in colour->space,
// filled in). Each refuses a bad file with Error(format), one sentence naming input.name.
bool is_jpeg(std::span<const unsigned char> first_bytes);
ImageF read_jpeg(const Input& input, const ImageReadLimits& limits, ImageColour* colour);
bool is_tiff(std::span<const unsigned char> first_bytes);
ImageF read_tiff(const Input& input, const ImageReadLimits& limits, ImageColour* colour);
bool is_webp(std::span<const unsigned char> first_bytes);
ImageF read_webp(const Input& input, const ImageReadLimits& limits, ImageColour* colour);
// TGA has no signature: a header whose fields hold values only a TGA has.
bool is_tga(std::span<const unsigned char> first_bytes);
ImageF read_tga(const Input& input, const ImageReadLimits& limits, ImageColour* colour);

}  // namespace stochtex
