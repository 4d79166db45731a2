// TIFF through libtiff: grey, grey and alpha, RGB and RGBA of 8 or 16 bits or 32-bit floats read
// as they are (strips or tiles, interleaved samples); every other layout libtiff knows (palettes,
// 1 to 4 bits, YCbCr, CMYK, separate planes) through its RGBA interface, at 8 bits.

#include <tiffio.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/file_message.hpp"
#include "io/decoding.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

// No single allocation of libtiff (a strip, a tile, a tag's values) may exceed 256 MiB: a declared
// strip size is refused rather than allocated (docs/design.md §9).
constexpr tmsize_t kMaxTiffAllocation = tmsize_t{256} << 20;

struct TiffInput {
  const Input* input;
  char error[256] = {};
};

int on_tiff_error(TIFF*, void* user_data, const char*, const char* format, va_list arguments) {
  auto* state = static_cast<TiffInput*>(user_data);
  if (!state->error[0]) std::vsnprintf(state->error, sizeof state->error, format, arguments);
  return 1;
}

int on_tiff_warning(TIFF*, void*, const char*, const char*, va_list) {
  return 1;  // unknown tags and the like do not affect the pixels
}

tmsize_t read_tiff_bytes(thandle_t handle, void* buffer, tmsize_t bytes) {
  std::FILE* file = static_cast<TiffInput*>(handle)->input->file;
  return static_cast<tmsize_t>(std::fread(buffer, 1, static_cast<std::size_t>(bytes), file));
}

tmsize_t write_tiff_bytes(thandle_t, void*, tmsize_t) {
  return 0;
}

// Within the input only: a file's stream can seek past its end and an fmemopen buffer cannot, and
// a reader never needs to, so both refuse it alike.
toff_t seek_tiff(thandle_t handle, toff_t offset, int whence) {
  const Input& input = *static_cast<TiffInput*>(handle)->input;
  const auto relative = static_cast<std::int64_t>(offset);
  const std::int64_t base = whence == SEEK_SET   ? 0
                            : whence == SEEK_CUR ? static_cast<std::int64_t>(ftello(input.file))
                                                 : static_cast<std::int64_t>(input.bytes);
  const std::int64_t target = base + relative;
  if (base < 0 || (relative > 0 && target < base) || target < 0 ||
      static_cast<std::uintmax_t>(target) > input.bytes ||
      fseeko(input.file, static_cast<off_t>(target), SEEK_SET) != 0)
    return static_cast<toff_t>(-1);
  return static_cast<toff_t>(target);
}

int close_tiff(thandle_t) {
  return 0;  // the caller owns the file
}

toff_t tiff_size(thandle_t handle) {
  return static_cast<toff_t>(static_cast<TiffInput*>(handle)->input->bytes);
}

struct TiffCloser {
  void operator()(TIFF* tiff) const { TIFFClose(tiff); }
};

struct TiffLayout {
  std::uint32_t width = 0, height = 0;
  std::uint16_t samples = 1, bits = 1, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_RGB;
  std::uint16_t planar = PLANARCONFIG_CONTIG, compression = COMPRESSION_NONE;
  std::uint16_t orientation = ORIENTATION_TOPLEFT, extra_samples = 0;

  // Grey or RGB with or without alpha, interleaved, of 8 or 16 bits or 32-bit floats: read as
  // stored. Anything else goes through libtiff's RGBA interface.
  bool direct() const {
    const int colour = photometric == PHOTOMETRIC_MINISBLACK ? 1
                       : photometric == PHOTOMETRIC_RGB      ? 3
                                                             : 0;
    const bool sample_format = (format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16)) ||
                               (format == SAMPLEFORMAT_IEEEFP && bits == 32);
    return colour > 0 && sample_format && planar == PLANARCONFIG_CONTIG && samples >= colour &&
           samples <= colour + 1;
  }
};

// The fewest bytes the pixels can be stored in, where the compression bounds how far it expands:
// none, PackBits (a 2-byte run of 128 samples), LZW (a 12-bit code stands for at most 4096 bytes)
// and deflate; 0 for the others.
double minimum_tiff_bytes(const TiffLayout& layout) {
  const double raw = double(layout.width) * layout.height * layout.samples * layout.bits / 8.0;
  switch (layout.compression) {
    case COMPRESSION_NONE:
      return raw;
    case COMPRESSION_PACKBITS:
      return raw / 64.0;
    case COMPRESSION_LZW:
      return raw / (4096.0 * 8.0 / 12.0);
    case COMPRESSION_ADOBE_DEFLATE:
    case COMPRESSION_DEFLATE:
      return raw / kMaxDeflateRatio;
    default:
      return 0.0;
  }
}

// Copies decoded interleaved samples (8 or 16 bits or floats) into floats, 8 and 16 bits scaled
// to [0, 1]; a float that is not finite becomes 0.
void to_floats(const TiffLayout& layout, const unsigned char* from, float* to, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    if (layout.bits == 8) {
      to[i] = static_cast<float>(from[i]) / 255.0f;
    } else if (layout.bits == 16) {
      std::uint16_t value;
      std::memcpy(&value, from + 2 * i, 2);
      to[i] = static_cast<float>(value) / 65535.0f;
    } else {
      float value;
      std::memcpy(&value, from + 4 * i, 4);
      to[i] = std::isfinite(value) ? value : 0.0f;
    }
  }
}

// Reads the samples as stored, tile by tile or strip by strip (libtiff gives them in the host's
// byte order).
bool read_direct(TIFF* tiff, const TiffLayout& layout, ImageF& image) {
  const std::size_t sample_bytes = layout.bits / 8;
  const std::size_t pixel_bytes = sample_bytes * layout.samples;
  if (TIFFIsTiled(tiff)) {
    std::uint32_t tile_width = 0, tile_height = 0;
    TIFFGetField(tiff, TIFFTAG_TILEWIDTH, &tile_width);
    TIFFGetField(tiff, TIFFTAG_TILELENGTH, &tile_height);
    const tmsize_t tile_bytes = TIFFTileSize(tiff);
    if (tile_width == 0 || tile_height == 0 || tile_bytes <= 0 ||
        static_cast<std::size_t>(tile_bytes) < std::size_t{tile_width} * tile_height * pixel_bytes)
      return false;
    std::vector<unsigned char> tile(static_cast<std::size_t>(tile_bytes));
    for (std::uint32_t y0 = 0; y0 < layout.height; y0 += tile_height)
      for (std::uint32_t x0 = 0; x0 < layout.width; x0 += tile_width) {
        if (TIFFReadTile(tiff, tile.data(), x0, y0, 0, 0) < 0) return false;
        const std::uint32_t columns = std::min(tile_width, layout.width - x0);
        for (std::uint32_t y = y0; y < std::min(y0 + tile_height, layout.height); ++y)
          to_floats(layout, tile.data() + (y - y0) * tile_width * pixel_bytes,
                    &image.at(static_cast<int>(x0), static_cast<int>(y), 0),
                    std::size_t{columns} * layout.samples);
      }
    return true;
  }
  const tmsize_t line_bytes = TIFFScanlineSize(tiff);
  if (line_bytes <= 0 || static_cast<std::size_t>(line_bytes) < layout.width * pixel_bytes)
    return false;
  std::vector<unsigned char> line(static_cast<std::size_t>(line_bytes));
  for (std::uint32_t y = 0; y < layout.height; ++y) {
    if (TIFFReadScanline(tiff, line.data(), y, 0) < 0) return false;
    to_floats(layout, line.data(), &image.at(0, static_cast<int>(y), 0),
              std::size_t{layout.width} * layout.samples);
  }
  return true;
}

// Reads any other layout libtiff knows as 8-bit RGBA, top row first; alpha is kept where the file
// has an extra sample.
bool read_rgba(TIFF* tiff, const TiffLayout& layout, ImageF& image) {
  std::vector<std::uint32_t> raster(std::size_t{layout.width} * layout.height);
  if (!TIFFReadRGBAImageOriented(tiff, layout.width, layout.height, raster.data(),
                                 ORIENTATION_TOPLEFT, 0))
    return false;
  const int channels = image.channels();
  // Grey and alpha take red and alpha.
  const std::array<int, 4> sources =
      channels == 2 ? std::array{0, 3, 0, 0} : std::array{0, 1, 2, 3};
  std::span<float> pixels = image.pixels();
  for (std::size_t i = 0; i < raster.size(); ++i) {
    const std::uint32_t pixel = raster[i];
    const unsigned char rgba[4] = {
        static_cast<unsigned char>(TIFFGetR(pixel)), static_cast<unsigned char>(TIFFGetG(pixel)),
        static_cast<unsigned char>(TIFFGetB(pixel)), static_cast<unsigned char>(TIFFGetA(pixel))};
    for (int c = 0; c < channels; ++c) pixels[i * channels + c] = rgba[sources[c]] / 255.0f;
  }
  return true;
}

[[noreturn]] void throw_tiff_error(const std::string& name, const TiffInput& state) {
  throw Error(ErrorCode::format, name + " is not a readable TIFF image (" +
                                     (state.error[0] ? printable(state.error, 160)
                                                     : std::string("libtiff cannot read it")) +
                                     "); it is truncated or corrupt, export it again");
}

}  // namespace

bool is_tiff(std::span<const unsigned char> first) {
  // Little- or big-endian, classic TIFF (42) or BigTIFF (43).
  return first.size() >= 4 && ((first[0] == 'I' && first[1] == 'I' &&
                                (first[2] == 42 || first[2] == 43) && first[3] == 0) ||
                               (first[0] == 'M' && first[1] == 'M' && first[2] == 0 &&
                                (first[3] == 42 || first[3] == 43)));
}

ImageF read_tiff(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  TiffInput state{&input};
  const std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions*)> options(TIFFOpenOptionsAlloc(),
                                                                             TIFFOpenOptionsFree);
  if (!options) throw std::bad_alloc();
  TIFFOpenOptionsSetMaxSingleMemAlloc(options.get(), kMaxTiffAllocation);
  TIFFOpenOptionsSetErrorHandlerExtR(options.get(), on_tiff_error, &state);
  TIFFOpenOptionsSetWarningHandlerExtR(options.get(), on_tiff_warning, &state);
  // "m": no memory mapping; the file is read through the Input's stream.
  const std::unique_ptr<TIFF, TiffCloser> tiff(
      TIFFClientOpenExt(input.stream_name.c_str(), "rm", &state, read_tiff_bytes, write_tiff_bytes,
                        seek_tiff, close_tiff, tiff_size, nullptr, nullptr, options.get()));
  if (!tiff) throw_tiff_error(input.name, state);
  TIFF* t = tiff.get();

  TiffLayout layout;
  if (!TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &layout.width) ||
      !TIFFGetField(t, TIFFTAG_IMAGELENGTH, &layout.height))
    throw_tiff_error(input.name, state);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &layout.samples);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &layout.bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &layout.format);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &layout.planar);
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &layout.compression);
  TIFFGetFieldDefaulted(t, TIFFTAG_ORIENTATION, &layout.orientation);
  if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &layout.photometric))
    layout.photometric = layout.samples >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK;
  std::uint16_t* extra_types = nullptr;
  TIFFGetFieldDefaulted(t, TIFFTAG_EXTRASAMPLES, &layout.extra_samples, &extra_types);
  check_size(input.name, layout.width, layout.height, limits);
  check_fits_file(input.name, layout.width, layout.height, minimum_tiff_bytes(layout), input.bytes);

  const bool direct = layout.direct();
  char message[1024] = {};
  if (!direct && !TIFFRGBAImageOK(t, message))
    throw Error(ErrorCode::format, input.name + " has a TIFF layout stochtex cannot read (" +
                                       printable(message, 160) +
                                       "); save it as 8- or 16-bit grey or RGB(A)");
  // Through the RGBA interface, grey stays grey (its red channel).
  const bool grey =
      layout.photometric == PHOTOMETRIC_MINISBLACK || layout.photometric == PHOTOMETRIC_MINISWHITE;
  const int channels = direct ? layout.samples : (grey ? 1 : 3) + (layout.extra_samples > 0);
  check_declared(layout.width, layout.height, channels, limits);

  // The colour is resolved before the pixels are decoded, so that a profile refused costs no time.
  std::unique_ptr<IccColour> icc;
  const bool floats = direct && layout.format == SAMPLEFORMAT_IEEEFP;
  if (colour && !floats) {
    std::uint32_t profile_bytes = 0;
    void* profile = nullptr;
    if (TIFFGetField(t, TIFFTAG_ICCPROFILE, &profile_bytes, &profile) && profile &&
        profile_bytes > 0)
      icc = std::make_unique<IccColour>(
          std::span<const unsigned char>(static_cast<const unsigned char*>(profile), profile_bytes),
          channels, input.name);
  }

  ImageF image(static_cast<int>(layout.width), static_cast<int>(layout.height), channels);
  if (!(direct ? read_direct(t, layout, image) : read_rgba(t, layout, image)))
    throw_tiff_error(input.name, state);
  if (colour) {
    if (icc) icc->convert(image);
    colour->space = floats ? ColourSpace::linear : ColourSpace::srgb;
    colour->origin = floats ? "TIFF floats: linear" : icc ? icc->origin() : "TIFF: sRGB by default";
  }
  // The RGBA interface has already placed the rows top first, the columns left first.
  return direct ? oriented(std::move(image), layout.orientation) : image;
}

}  // namespace stochtex
