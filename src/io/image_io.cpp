#include "io/image_io.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <openexr.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cinttypes>
#include <climits>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/file_message.hpp"
#include "core/input_file.hpp"
#include "core/srgb.hpp"
#include "io/compression.hpp"
#include "io/decoding.hpp"
#include "io/image_streams.hpp"
#include "io/png_sample.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// ---------------------------------------------------------------------------------------------
// PNG. libpng reports errors by longjmp, which would skip C++ destructors: every function that
// calls setjmp below holds only trivially destructible locals, and the objects that own memory
// live in its caller's frame, which the longjmp never leaves.

// The colour chunks a PNG reader honours, in the order of precedence of the PNG specification
// (3rd edition, §4.3): each of kPngColourChunks' names, at the index of its PngColourChunk.
enum PngColourChunk { kCicp, kIccp, kSrgb, kGama, kPngColourChunkCount };
constexpr std::array<const char*, kPngColourChunkCount> kPngColourChunks = {"cICP", "iCCP", "sRGB",
                                                                            "gAMA"};
// Each name with its article, as a message writes it.
constexpr std::array<const char*, kPngColourChunkCount> kPngColourChunkPhrases = {
    "a cICP chunk", "an iCCP chunk", "an sRGB chunk", "a gAMA chunk"};

struct PngErrorMessage {
  char text[256] = {};
  // libpng's last warning about each colour chunk ("iCCP: profile 'x': ..."), which says why it
  // dropped one, and whether one was a bad checksum, after which libpng keeps an ancillary chunk.
  char colour_warning[kPngColourChunkCount][200] = {};
  bool colour_crc_error[kPngColourChunkCount] = {};
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngErrorMessage*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof error->text, "%s", message);
  png_longjmp(png, 1);
}

// Warnings (unknown colour profiles, ancillary chunks with bad checksums) do not affect the pixels;
// those about a colour chunk are kept for the message that refuses it.
void on_png_warning(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngErrorMessage*>(png_get_error_ptr(png));
  for (int chunk = 0; chunk < kPngColourChunkCount; ++chunk)
    if (std::strncmp(message, kPngColourChunks[chunk], 4) == 0 && message[4] == ':') {
      const char* text = message + 5 + (message[5] == ' ');
      std::snprintf(error->colour_warning[chunk], sizeof error->colour_warning[chunk], "%s", text);
      if (std::strcmp(text, "CRC error") == 0) error->colour_crc_error[chunk] = true;
    }
}

void read_png_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
  if (std::fread(data, 1, length, file) != length)
    png_error(png, std::feof(file) ? "the file ends too early" : "read error");
}

// Where libpng's output goes, and what the stream threw: an exception must not cross libpng's C
// frames, so it is kept here and rethrown once png_error's longjmp has left them.
struct PngOutput {
  Imf::OStream& stream;
  std::exception_ptr failure;
};

void write_png_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* output = static_cast<PngOutput*>(png_get_io_ptr(png));
  try {
    write_all(output->stream, data, length);
    return;
  } catch (...) {
    output->failure = std::current_exception();
  }
  png_error(png, "the output failed");
}

// The streams are flushed when the file is committed; libpng's default flush would take its
// output for a FILE.
void flush_png(png_structp) {}

struct PngReader {
  PngErrorMessage error;
  png_structp png = nullptr;
  png_infop info = nullptr;

  PngReader() {
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
    if (png) info = png_create_info_struct(png);
    if (!png || !info) {
      png_destroy_read_struct(&png, &info, nullptr);
      throw std::bad_alloc();
    }
  }
  ~PngReader() { png_destroy_read_struct(&png, &info, nullptr); }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;
};

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int channels = 0;
  int bit_depth = 0;
  png_size_t row_bytes = 0;
  int stored_bits_per_pixel = 0;  // as compressed in the file, before the expansions below
};

// libpng buffers each ancillary chunk (text, colour profile) whole and caches up to a count of
// them; both are capped, like the image sides, so that a declared chunk length is refused rather
// than allocated (docs/design.md §9). Real colour profiles are well under 8 MiB.
constexpr png_alloc_size_t kMaxPngChunkBytes = png_alloc_size_t{8} << 20;
constexpr png_uint_32 kMaxPngAncillaryChunks = 1000;

void set_png_limits(png_structp png, const ImageReadLimits& limits) {
  const auto side = static_cast<png_uint_32>(
      std::clamp<std::int64_t>(limits.max_pixels, 1, std::int64_t{PNG_UINT_31_MAX}));
  png_set_user_limits(png, side, side);
  png_set_chunk_malloc_max(png, kMaxPngChunkBytes);
  png_set_chunk_cache_max(png, kMaxPngAncillaryChunks);
}

// Reads the chunks before the pixels and asks libpng for 8 or 16 bits per sample with palettes
// and transparency keys expanded, so 1 to 4 channels remain. With `colour`, libpng keeps the
// cICP (which libpng 1.6.39 does not know), sRGB and gAMA chunks as they are, for png_colour to
// read (libpng's own checks of them would drop an iCCP after an sRGB chunk), reads the iCCP chunk
// (decompressed within the chunk limit, its header checked) and discards cHRM, which stochtex
// ignores.
bool read_png_layout(PngReader& reader, std::FILE* file, PngLayout& layout, bool colour) {
  if (setjmp(png_jmpbuf(reader.png))) return false;
  png_set_read_fn(reader.png, file, read_png_bytes);
  if (colour) {
    static constexpr png_byte kKept[] = "cICP\0sRGB\0gAMA";
    static constexpr png_byte kDiscarded[] = "cHRM";
    png_set_keep_unknown_chunks(reader.png, PNG_HANDLE_CHUNK_ALWAYS, kKept, 3);
    png_set_keep_unknown_chunks(reader.png, PNG_HANDLE_CHUNK_NEVER, kDiscarded, 1);
  }
  png_read_info(reader.png, reader.info);
  layout.stored_bits_per_pixel =
      png_get_bit_depth(reader.png, reader.info) * png_get_channels(reader.png, reader.info);
  const int color_type = png_get_color_type(reader.png, reader.info);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(reader.png);
  if (color_type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(reader.png, reader.info) < 8)
    png_set_expand_gray_1_2_4_to_8(reader.png);
  if (png_get_valid(reader.png, reader.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(reader.png);
  png_set_interlace_handling(reader.png);
  png_read_update_info(reader.png, reader.info);
  layout.width = png_get_image_width(reader.png, reader.info);
  layout.height = png_get_image_height(reader.png, reader.info);
  layout.channels = png_get_channels(reader.png, reader.info);
  layout.bit_depth = png_get_bit_depth(reader.png, reader.info);
  layout.row_bytes = png_get_rowbytes(reader.png, reader.info);
  return true;
}

// Reading up to the end chunk also checks the checksums after the pixels, so a truncated file is
// reported rather than silently accepted.
bool read_png_pixels(PngReader& reader, png_bytepp rows) {
  if (setjmp(png_jmpbuf(reader.png))) return false;
  png_read_image(reader.png, rows);
  png_read_end(reader.png, nullptr);
  return true;
}

[[noreturn]] void throw_png_read_error(const std::string& name, const PngReader& reader) {
  throw Error(ErrorCode::format, name + " is not a readable PNG image (" + reader.error.text +
                                     "); it is truncated or corrupt, export it again");
}

// libpng allocates an ancillary chunk's declared length before reading it: every chunk must fit
// in the file, whatever the limits above allow (docs/design.md §9). Returns which colour chunks
// come before the pixels (the first IDAT chunk), for png_colour to tell a chunk libpng dropped
// from a chunk that is not there.
std::array<bool, kPngColourChunkCount> check_png_chunks(const Input& input) {
  constexpr std::uintmax_t kSignatureBytes = 8;
  constexpr std::uintmax_t kChunkFrameBytes = 12;  // length, type and checksum
  std::array<bool, kPngColourChunkCount> colour_chunks{};
  bool before_pixels = true;
  std::uintmax_t position = kSignatureBytes;
  std::array<char, 8> length_and_type{};
  while (position + 8 <= input.bytes) {  // a chunk's length and type are there
    if (fseeko(input.file, static_cast<off_t>(position), SEEK_SET) != 0 ||
        std::fread(length_and_type.data(), 1, length_and_type.size(), input.file) !=
            length_and_type.size())
      throw Error(ErrorCode::io, "cannot read " + input.name + ": " + errno_message(errno));
    const auto byte = [&](int i) { return static_cast<unsigned char>(length_and_type[i]); };
    const std::uintmax_t data_bytes = std::uintmax_t{byte(0)} << 24 |
                                      std::uintmax_t{byte(1)} << 16 | std::uintmax_t{byte(2)} << 8 |
                                      byte(3);
    if (kChunkFrameBytes + data_bytes > input.bytes - position)
      throw Error(ErrorCode::format, input.name + " declares a chunk of " +
                                         std::to_string(data_bytes) +
                                         " bytes past the end of the file; it is truncated or "
                                         "corrupt");
    const char* type = length_and_type.data() + 4;
    if (std::memcmp(type, "IDAT", 4) == 0) before_pixels = false;
    for (int chunk = 0; chunk < kPngColourChunkCount; ++chunk)
      if (before_pixels && std::memcmp(type, kPngColourChunks[chunk], 4) == 0)
        colour_chunks[chunk] = true;
    position += kChunkFrameBytes + data_bytes;
  }
  if (std::fseek(input.file, 0, SEEK_SET) != 0)
    throw Error(ErrorCode::io, "cannot read " + input.name + ": " + errno_message(errno));
  return colour_chunks;
}

// ---------------------------------------------------------------------------------------------
// PNG colour (docs/design.md §14): what the colour chunks say the values are, and how they become
// sRGB-encoded or linear ones (include/stochtex/io.hpp).

// What a PNG's colour chunks make of its values: the space they are read in, the phrase saying
// why, and the conversion to apply, if any.
struct PngColour {
  ColourSpace space = ColourSpace::srgb;
  std::string origin;
  double gamma_exponent = 0.0;     // > 0: each colour value v becomes srgb_encode(v^gamma_exponent)
  std::unique_ptr<IccColour> icc;  // null when the values need no conversion
};

// A colour chunk libpng kept as it is (read_png_layout), or none.
const png_unknown_chunk* kept_png_chunk(const PngReader& reader, const char* type) {
  png_unknown_chunkp chunks = nullptr;
  const int count = png_get_unknown_chunks(reader.png, reader.info, &chunks);
  for (int i = 0; i < count; ++i)
    if (std::memcmp(chunks[i].name, type, 4) == 0 && (chunks[i].location & PNG_AFTER_IDAT) == 0)
      return &chunks[i];
  return nullptr;
}

// "0.45455" for a gAMA chunk's 45455: its value / 100000, without trailing zeros, at least one
// decimal.
std::string png_gamma_text(std::uint32_t gamma) {
  std::string text =
      std::to_string(gamma / 100000) + "." + std::to_string(100000 + gamma % 100000).substr(1);
  while (text.back() == '0' && text[text.size() - 2] != '.') text.pop_back();
  return text;
}

// What a cICP chunk stochtex does not read declares, for the message refusing it: the transfer
// function first when it is HDR (as it says the most), then the primaries, the matrix, the range.
std::string cicp_refusal(std::span<const png_byte, 4> cicp) {
  const auto field = [&](const char* what, int index) {
    return std::string(" (cICP ") + what + " " + std::to_string(cicp[index]) + ")";
  };
  if (cicp[1] == 16) return "HDR PQ colour" + field("transfer", 1);
  if (cicp[1] == 18) return "HDR HLG colour" + field("transfer", 1);
  if (cicp[0] != 1)
    return (cicp[0] == 9    ? std::string("BT.2020 primaries")
            : cicp[0] == 12 ? std::string("Display P3 primaries")
                            : std::string("primaries other than sRGB's")) +
           field("primaries", 0);
  if (cicp[2] != 0) return "colour coded as luma and chroma" + field("matrix coefficients", 2);
  if (cicp[3] != 1) return "narrow-range (video) values" + field("full range flag", 3);
  return "a transfer function other than sRGB's or linear" + field("transfer", 1);
}

// Resolves a PNG's colour from its colour chunks before its pixels (`present`: which are in the
// file, check_png_chunks), in the PNG specification's order: cICP, iCCP, sRGB, gAMA, none.
// Refuses a chunk libpng dropped (a bad checksum, a profile its checks refuse), a malformed one
// and a colour stochtex does not read.
PngColour png_colour(const Input& input, const PngReader& reader, const PngLayout& layout,
                     const std::array<bool, kPngColourChunkCount>& present) {
  const auto corrupt = [&](const std::string& problem) {
    return Error(ErrorCode::format,
                 input.name + " has " + problem + "; the file is corrupt, export it again");
  };
  const auto unreadable = [&](int chunk) {
    const char* warning =
        reader.error.colour_crc_error[chunk] ? "CRC error" : reader.error.colour_warning[chunk];
    return corrupt(std::string(kPngColourChunkPhrases[chunk]) + " that cannot be read (" +
                   (warning[0] ? printable(warning, 160) : "libpng dropped it") + ")");
  };
  const auto kept = [&](int chunk, std::size_t bytes) {
    const png_unknown_chunk* found = kept_png_chunk(reader, kPngColourChunks[chunk]);
    if (!found || reader.error.colour_crc_error[chunk]) throw unreadable(chunk);
    if (found->size != bytes)
      throw corrupt(std::string(kPngColourChunkPhrases[chunk]) + " of " +
                    std::to_string(found->size) + " bytes (" + std::to_string(bytes) +
                    " expected)");
    return std::span<const png_byte>(found->data, found->size);
  };

  PngColour colour;
  if (present[kCicp]) {
    const std::span<const png_byte> cicp = kept(kCicp, 4);
    if (cicp[0] == 1 && cicp[2] == 0 && cicp[3] == 1 && (cicp[1] == 13 || cicp[1] == 8)) {
      colour.space = cicp[1] == 8 ? ColourSpace::linear : ColourSpace::srgb;
      colour.origin = cicp[1] == 8 ? "cICP: linear" : "cICP: sRGB";
      return colour;
    }
    throw Error(ErrorCode::format,
                input.name + " declares " + cicp_refusal(cicp.first<4>()) +
                    ", which stochtex does not read; convert it to sRGB or save it as OpenEXR");
  }
  if (present[kIccp]) {
    png_charp profile_name = nullptr;
    int compression = 0;
    png_bytep profile = nullptr;
    png_uint_32 profile_bytes = 0;
    if (!png_get_iCCP(reader.png, reader.info, &profile_name, &compression, &profile,
                      &profile_bytes) ||
        !profile) {
      const char* warning = reader.error.colour_warning[kIccp];
      // libpng drops a grey profile on RGB, or an RGB one on grey, saying so.
      if (std::strstr(warning, "color space not permitted on")) {
        colour.origin = mismatched_profile_origin(layout.channels);
        return colour;
      }
      throw Error(ErrorCode::format,
                  input.name + " carries an ICC profile stochtex cannot use (" +
                      (warning[0] ? printable(warning, 160) : "libpng dropped it") +
                      "); convert the image to sRGB");
    }
    if (reader.error.colour_crc_error[kIccp]) throw unreadable(kIccp);
    colour.icc = std::make_unique<IccColour>(std::span<const png_byte>(profile, profile_bytes),
                                             layout.channels, input.name);
    colour.origin = colour.icc->origin();
    return colour;
  }
  if (present[kSrgb]) {
    kept(kSrgb, 1);
    colour.origin = "sRGB chunk";
    return colour;
  }
  if (present[kGama]) {
    const std::span<const png_byte> bytes = kept(kGama, 4);
    const std::uint32_t gamma = std::uint32_t{bytes[0]} << 24 | std::uint32_t{bytes[1]} << 16 |
                                std::uint32_t{bytes[2]} << 8 | bytes[3];
    if (gamma == 0 || gamma > PNG_UINT_31_MAX)
      throw corrupt("a gAMA chunk declaring a gamma of " + std::to_string(gamma) +
                    " / 100000, which is not a gamma");
    if (gamma == 100000) {
      colour.space = ColourSpace::linear;
      colour.origin = "gAMA 1.0: linear";
    } else {
      colour.gamma_exponent = 100000.0 / gamma;
      colour.origin = "gAMA " + png_gamma_text(gamma) + ", converted to sRGB";
    }
    return colour;
  }
  colour.origin = "no colour chunk: sRGB by default";
  return colour;
}

ImageF read_png(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  const std::array<bool, kPngColourChunkCount> colour_chunks = check_png_chunks(input);
  PngReader reader;
  set_png_limits(reader.png, limits);
  PngLayout layout;
  if (!read_png_layout(reader, input.file, layout, colour != nullptr))
    throw_png_read_error(input.name, reader);
  check_size(input.name, layout.width, layout.height, limits);
  // The pixels are one zlib stream (PNG specification §10).
  check_fits_file(input.name, layout.width, layout.height,
                  static_cast<double>(layout.width) * layout.height * layout.stored_bits_per_pixel /
                      8.0 / kMaxDeflateRatio,
                  input.bytes);
  const bool sixteen_bit = layout.bit_depth == 16;
  if (layout.channels < 1 || layout.channels > 4 || (layout.bit_depth != 8 && !sixteen_bit) ||
      layout.row_bytes != std::size_t{layout.width} * layout.channels * (sixteen_bit ? 2 : 1))
    throw Error(ErrorCode::format, input.name + " has an unsupported PNG pixel layout (" +
                                       std::to_string(layout.channels) + " channels of " +
                                       std::to_string(layout.bit_depth) +
                                       " bits); convert it to 8- or 16-bit grey or RGB(A)");
  check_declared(layout.width, layout.height, layout.channels, limits);
  // The colour is resolved before the pixels are decoded, so that a colour refused costs no time.
  std::optional<PngColour> png_colour_found;
  if (colour) png_colour_found.emplace(png_colour(input, reader, layout, colour_chunks));

  std::vector<png_byte> bytes(layout.row_bytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = bytes.data() + y * layout.row_bytes;
  if (!read_png_pixels(reader, rows.data())) throw_png_read_error(input.name, reader);

  ImageF image(static_cast<int>(layout.width), static_cast<int>(layout.height), layout.channels);
  std::span<float> pixels = image.pixels();
  if (sixteen_bit) {
    // PNG stores 16-bit samples big-endian.
    for (std::size_t i = 0; i < pixels.size(); ++i)
      pixels[i] = static_cast<float>((bytes[2 * i] << 8) | bytes[2 * i + 1]) / 65535.0f;
  } else {
    for (std::size_t i = 0; i < pixels.size(); ++i)
      pixels[i] = static_cast<float>(bytes[i]) / 255.0f;
  }
  if (!png_colour_found) return image;

  PngColour& found = *png_colour_found;
  if (found.gamma_exponent > 0.0) {
    // A stored sample has one of 256 or 65536 values: each colour value is converted once.
    const unsigned maximum = sixteen_bit ? 65535 : 255;
    std::vector<float> converted(maximum + 1);
    for (unsigned sample = 0; sample <= maximum; ++sample)
      converted[sample] = static_cast<float>(
          srgb_encode(std::pow(static_cast<double>(sample) / maximum, found.gamma_exponent)));
    for (std::size_t i = 0; i < pixels.size(); ++i)
      if (is_colour_channel(static_cast<int>(i % layout.channels), layout.channels))
        pixels[i] = converted[sixteen_bit ? ((bytes[2 * i] << 8) | bytes[2 * i + 1]) : bytes[i]];
  }
  if (found.icc) found.icc->convert(image);
  colour->space = found.space;
  colour->origin = std::move(found.origin);
  return image;
}

struct PngWriter {
  PngErrorMessage error;
  png_structp png = nullptr;
  png_infop info = nullptr;

  PngWriter() {
    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
    if (png) info = png_create_info_struct(png);
    if (!png || !info) {
      png_destroy_write_struct(&png, &info);
      throw std::bad_alloc();
    }
  }
  ~PngWriter() { png_destroy_write_struct(&png, &info); }
  PngWriter(const PngWriter&) = delete;
  PngWriter& operator=(const PngWriter&) = delete;
};

// libpng's steps of writing a file, each under its own setjmp so that a PNG can be written by
// more than one thread in turn. Each returns false after png_error.
//
// `srgb_chunk`: the file says its values are sRGB-encoded. png_set_sRGB_gAMA_and_cHRM writes the
// sRGB chunk and, as the PNG specification recommends beside it, the gAMA (0.45455) and cHRM
// (sRGB's primaries) chunks for decoders that do not know sRGB (73 bytes in all); stochtex's
// reader takes sRGB first. Perceptual: the rendering intent of photographs.
bool begin_png(PngWriter& writer, PngOutput& output, png_uint_32 width, png_uint_32 height,
               int color_type, int bit_depth, bool srgb_chunk) {
  if (setjmp(png_jmpbuf(writer.png))) return false;
  png_set_write_fn(writer.png, &output, write_png_bytes, flush_png);
  png_set_IHDR(writer.png, writer.info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (srgb_chunk) png_set_sRGB_gAMA_and_cHRM(writer.png, writer.info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_set_filter(writer.png, PNG_FILTER_TYPE_BASE, kPngFilters);
  png_set_compression_strategy(writer.png, kPngZlibStrategy);
  png_write_info(writer.png, writer.info);
  return true;
}

bool write_png_rows(PngWriter& writer, png_bytepp rows, png_uint_32 count) {
  if (setjmp(png_jmpbuf(writer.png))) return false;
  png_write_rows(writer.png, rows, count);
  return true;
}

bool end_png(PngWriter& writer) {
  if (setjmp(png_jmpbuf(writer.png))) return false;
  png_write_end(writer.png, nullptr);
  return true;
}

// One row of `width` pixels of `channels` values as PNG samples of `bit_depth` bits (16: big-
// endian) into `out`: linear values of colour channels are encoded with the sRGB transfer
// function before they are rounded (`space`); the others are rounded as they are.
void png_samples(const float* values, int width, int channels, int bit_depth, ColourSpace space,
                 png_bytep out) {
  const SrgbSamples8& srgb8 = SrgbSamples8::get();
  for (int c = 0; c < channels; ++c) {
    const bool encoded = space == ColourSpace::linear && is_colour_channel(c, channels);
    const auto count = static_cast<std::size_t>(width);
    const float* in = values + c;
    const auto step = static_cast<std::size_t>(channels);
    if (bit_depth == 16) {
      png_bytep sample_bytes = out + 2 * c;
      for (std::size_t x = 0; x < count; ++x, in += step, sample_bytes += 2 * step) {
        const unsigned sample = png_sample(encoded ? srgb_encode(*in) : *in, 65535);
        sample_bytes[0] = static_cast<png_byte>(sample >> 8);
        sample_bytes[1] = static_cast<png_byte>(sample & 0xff);
      }
    } else if (encoded) {
      for (std::size_t x = 0; x < count; ++x, in += step)
        out[c + x * step] = static_cast<png_byte>(srgb8(*in));
    } else {
      for (std::size_t x = 0; x < count; ++x, in += step)
        out[c + x * step] = static_cast<png_byte>(png_sample(*in, 255));
    }
  }
}

// A PNG of float images' rows, written rows after rows: its header when made, then each call's
// rows (png_samples), then its end. Every step throws what failed: the stream's exception, or
// std::runtime_error with libpng's message. `space`: linear values are encoded with the sRGB
// transfer function (colour channels) before they are rounded; linear and srgb images get the
// sRGB chunk; data is written as it is.
class PngEncoder {
 public:
  PngEncoder(Imf::OStream& stream, int width, int height, int channels, int bit_depth,
             ColourSpace space)
      : output_{stream, nullptr}, bit_depth_(bit_depth), space_(space) {
    constexpr std::array<int, 4> color_types = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                                PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
    check(begin_png(writer_, output_, static_cast<png_uint_32>(width),
                    static_cast<png_uint_32>(height), color_types[channels - 1], bit_depth,
                    space != ColourSpace::data));
  }
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;

  // The next rows.height rows of the image (rows.width pixels of its channels).
  void write(ImageView<const float> rows) {
    const std::size_t row_bytes =
        static_cast<std::size_t>(rows.width) * rows.channels * (bit_depth_ == 16 ? 2 : 1);
    bytes_.resize(row_bytes * rows.height);
    pointers_.resize(rows.height);
    for (int y = 0; y < rows.height; ++y) {
      pointers_[y] = bytes_.data() + y * row_bytes;
      png_samples(rows.row(y), rows.width, rows.channels, bit_depth_, space_, pointers_[y]);
    }
    check(write_png_rows(writer_, pointers_.data(), static_cast<png_uint_32>(rows.height)));
  }

  void finish() { check(end_png(writer_)); }

 private:
  void check(bool written) {
    if (written) return;
    if (output_.failure) std::rethrow_exception(output_.failure);
    throw std::runtime_error(writer_.error.text);
  }

  PngWriter writer_;
  PngOutput output_;
  int bit_depth_;
  ColourSpace space_;
  std::vector<png_byte> bytes_;
  std::vector<png_bytep> pointers_;
};

void write_png(Imf::OStream& stream, ImageView<const float> image, int bit_depth,
               ColourSpace space) {
  PngEncoder encoder(stream, image.width, image.height, image.channels, bit_depth, space);
  encoder.write(image);
  encoder.finish();
}

// ---------------------------------------------------------------------------------------------
// OpenEXR.

// What OpenEXR's core library reads a header from, and the message of its last error.
struct ExrHeaderInput {
  const Input& input;
  char error[256] = {};
};

void on_exr_error(exr_const_context_t context, exr_result_t, const char* message) {
  void* user_data = nullptr;
  if (exr_get_user_data(context, &user_data) == EXR_ERR_SUCCESS && user_data)
    std::snprintf(static_cast<ExrHeaderInput*>(user_data)->error, sizeof(ExrHeaderInput::error),
                  "%s", message);
}

// The core library's reads, as pread: up to `size` bytes at `offset`, fewer at the end. It is
// called from C, so it reports a failure through `error` rather than by throwing.
std::int64_t read_exr_bytes(exr_const_context_t context, void* user_data, void* buffer,
                            std::uint64_t size, std::uint64_t offset,
                            exr_stream_error_func_ptr_t error) {
  const Input& input = static_cast<ExrHeaderInput*>(user_data)->input;
  if (offset >= input.bytes) return 0;
  std::clearerr(input.file);
  if (fseeko(input.file, static_cast<off_t>(offset), SEEK_SET) != 0) {
    error(context, EXR_ERR_READ_IO, "Unable to seek to requested position");
    return -1;
  }
  const std::size_t got = std::fread(buffer, 1, size, input.file);
  if (got < size && std::ferror(input.file)) {
    error(context, EXR_ERR_READ_IO, "Unable to read %" PRIu64 " bytes: %s", size,
          std::strerror(errno));
    return -1;
  }
  return static_cast<std::int64_t>(got);
}

std::int64_t exr_input_bytes(exr_const_context_t, void* user_data) {
  return static_cast<std::int64_t>(static_cast<ExrHeaderInput*>(user_data)->input.bytes);
}

[[noreturn]] void throw_exr_read_error(const std::string& name, const std::string& problem) {
  throw Error(ErrorCode::format, name + " is not a readable OpenEXR image (" + problem +
                                     "); it is truncated or corrupt, export it again");
}

// The most a chunk of each OpenEXR compression can expand: RLE codes a run of at most 128 bytes
// in 2; ZIP and PXR24 are zlib (PXR24 after storing floats in 24 bits); PIZ's Huffman coder
// codes a run of 256 values in 10 bits at best, under the zlib bound; B44 keeps at least 3 of every
// 32 bytes; DWA codes an 8x8 block's DC alone and zlib-compresses it.
double max_exr_expansion(exr_compression_t compression) {
  switch (compression) {
    case EXR_COMPRESSION_NONE:
      return 1.0;
    case EXR_COMPRESSION_RLE:
      return 64.0;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A:
      return 32.0 / 3.0;
    case EXR_COMPRESSION_PXR24:
      return kMaxDeflateRatio * 4.0 / 3.0;
    case EXR_COMPRESSION_DWAA:
    case EXR_COMPRESSION_DWAB:
      return kMaxDeflateRatio * 64.0;
    default:
      return kMaxDeflateRatio;
  }
}

// The OpenEXR C++ reader allocates from what the header declares (attribute values, the chunk
// offset tables, a chunk's buffer) as it opens a file, before it reads any pixel. The headers are
// therefore checked first with the C core library, which parses only them and bounds each
// attribute by the file size: any problem it reports refuses the file, and every part's chunks
// must fit in the file: an 8-byte offset and an 8-byte chunk header each, and their pixels at
// the best ratio of the part's compression. A chunk's buffer is allocated at its nominal size (a
// whole tile or block of lines, even past the data window): beyond a small allowance it must be
// one the file could fill (docs/design.md §9).
void check_exr_header(const Input& input, const ImageReadLimits& limits) {
  ExrHeaderInput header{input};
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = on_exr_error;
  init.user_data = &header;
  init.read_fn = read_exr_bytes;
  init.size_fn = exr_input_bytes;
  struct Context {
    exr_context_t handle = nullptr;
    ~Context() { exr_finish(&handle); }
  } context;
  const exr_result_t started = exr_start_read(&context.handle, input.stream_name.c_str(), &init);
  if (started != EXR_ERR_SUCCESS || header.error[0])
    throw_exr_read_error(input.name,
                         header.error[0] ? header.error : exr_get_default_error_message(started));
  int parts = 0;
  if (exr_get_count(context.handle, &parts) != EXR_ERR_SUCCESS || parts < 1)
    throw_exr_read_error(input.name, "no image part");
  for (int part = 0; part < parts; ++part) {
    exr_attr_box2i_t window{};
    if (exr_get_data_window(context.handle, part, &window) != EXR_ERR_SUCCESS)
      throw_exr_read_error(input.name, "no data window");
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    check_size(input.name, width, height, limits);
    exr_storage_t storage{};
    exr_compression_t compression{};
    std::int32_t chunks = 0;
    std::uint64_t chunk_bytes = 0;
    const exr_attr_chlist_t* channels = nullptr;
    if (exr_get_channels(context.handle, part, &channels) != EXR_ERR_SUCCESS ||
        exr_get_storage(context.handle, part, &storage) != EXR_ERR_SUCCESS ||
        exr_get_compression(context.handle, part, &compression) != EXR_ERR_SUCCESS ||
        exr_get_chunk_count(context.handle, part, &chunks) != EXR_ERR_SUCCESS ||
        exr_get_chunk_unpacked_size(context.handle, part, &chunk_bytes) != EXR_ERR_SUCCESS)
      throw_exr_read_error(input.name, "no chunk layout");
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED)
      throw Error(ErrorCode::format, input.name +
                                         " holds deep data, which is not supported; save it as "
                                         "a flat image");
    double pixel_bytes = 0.0;
    for (int c = 0; c < channels->num_channels; ++c) {
      const exr_attr_chlist_entry_t& channel = channels->entries[c];
      pixel_bytes += static_cast<double>(width / std::max(channel.x_sampling, 1)) *
                     static_cast<double>(height / std::max(channel.y_sampling, 1)) *
                     (channel.pixel_type == EXR_PIXEL_HALF ? 2.0 : 4.0);
    }
    const double expansion = max_exr_expansion(compression);
    constexpr double kChunkAllowance = 16 << 20;
    check_fits_file(input.name, width, height,
                    std::max(16.0 * chunks + pixel_bytes / expansion,
                             (static_cast<double>(chunk_bytes) - kChunkAllowance) / expansion),
                    input.bytes);
  }
}

// Y, (Y, A), (R, G, B) or (R, G, B, A), in that order.
std::vector<const char*> exr_channel_names(const std::string& name, const Imf::ChannelList& list) {
  std::vector<const char*> names;
  if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
    names = {"R", "G", "B"};
  } else if (list.findChannel("Y")) {
    if (list.findChannel("RY") || list.findChannel("BY"))
      throw Error(ErrorCode::format, name +
                                         " stores colour as luminance and chroma (Y, RY, BY), "
                                         "which is not supported; save it as R, G, B");
    names = {"Y"};
  } else {
    std::string found;
    for (auto channel = list.begin(); channel != list.end(); ++channel)
      found += (found.empty() ? "" : ", ") + std::string(channel.name());
    throw Error(ErrorCode::format, name + " has no Y or R, G, B channels (it has: " +
                                       (found.empty() ? "none" : found) +
                                       "); save the image with R, G, B or Y channels");
  }
  if (list.findChannel("A")) names.push_back("A");
  for (const char* channel_name : names) {
    const Imf::Channel& channel = *list.findChannel(channel_name);
    if (channel.xSampling != 1 || channel.ySampling != 1)
      throw Error(ErrorCode::format, name + " has a subsampled " + channel_name +
                                         " channel, which is not supported; save it at full "
                                         "resolution");
  }
  return names;
}

ImageF read_exr(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  check_exr_header(input, limits);
  try {
    FileInputStream stream(input.file, input.bytes, input.stream_name.c_str());
    Imf::InputFile file(stream);
    const Imath::Box2i window = file.header().dataWindow();
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    check_size(input.name, width, height, limits);
    const std::vector<const char*> names = exr_channel_names(input.name, file.header().channels());
    const int channels = static_cast<int>(names.size());
    check_declared(width, height, channels, limits);
    ImageF image(static_cast<int>(width), static_cast<int>(height), channels);
    Imf::FrameBuffer frame_buffer;
    const std::size_t pixel_stride = sizeof(float) * channels;
    for (int c = 0; c < channels; ++c)
      frame_buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels().data() + c, window,
                                                     pixel_stride, pixel_stride * width));
    file.setFrameBuffer(frame_buffer);
    file.readPixels(window.min.y, window.max.y);
    if (colour) *colour = {ColourSpace::linear, "OpenEXR: linear"};
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::invalid_argument&) {  // a caller's check_declared
    throw;
  } catch (const std::exception& e) {
    throw_exr_read_error(input.name, e.what());
  }
}

// An sRGB-encoded image's colour channels decoded to linear light, which the float formats hold.
ImageF srgb_decoded(ImageView<const float> image) {
  ImageF linear(image.width, image.height, image.channels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < image.channels; ++c)
        linear.at(x, y, c) = is_colour_channel(c, image.channels) ? srgb_decode(image.at(x, y, c))
                                                                  : image.at(x, y, c);
  return linear;
}

void write_exr(Imf::OStream& stream, ImageView<const float> image) {
  const auto& names = exr_written_channel_names(image.channels);
  Imf::Header header(image.width, image.height);
  header.compression() = kExrFloatCompression;
  Imf::FrameBuffer frame_buffer;
  const Imath::Box2i window = header.dataWindow();
  for (int c = 0; c < image.channels; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame_buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.data + c, window,
                                                   sizeof(float) * image.channels,
                                                   sizeof(float) * image.row_stride));
  }
  Imf::OutputFile output(stream, header);
  output.setFrameBuffer(frame_buffer);
  output.writePixels(image.height);
}

// ---------------------------------------------------------------------------------------------
// PFM: "PF" (RGB) or "Pf" (grey), width, height and a scale whose sign gives the byte order
// (negative: little-endian), each followed by one whitespace character; then float32 rows from
// the bottom of the image to the top.

bool is_pfm_space(int character) {
  return character == ' ' || character == '\t' || character == '\n' || character == '\r';
}

// The next header field: leading whitespace skipped, then at most 32 characters up to and
// including the single whitespace that ends it.
bool read_pfm_field(std::FILE* file, std::string& field) {
  field.clear();
  int character = std::fgetc(file);
  while (is_pfm_space(character)) character = std::fgetc(file);
  while (character != EOF && !is_pfm_space(character)) {
    if (field.size() == 32) return false;
    field.push_back(static_cast<char>(character));
    character = std::fgetc(file);
  }
  return !field.empty() && character != EOF;
}

template <typename T>
bool parse_number(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return error == std::errc{} && stop == end;
}

ImageF read_pfm(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  std::FILE* file = input.file;
  const auto corrupt = [&](const std::string& problem) {
    return Error(ErrorCode::format, input.name + " is not a readable PFM image (" + problem +
                                        "); it is truncated or corrupt, export it again");
  };
  std::string magic, width_text, height_text, scale_text;
  if (!read_pfm_field(file, magic) || !read_pfm_field(file, width_text) ||
      !read_pfm_field(file, height_text) || !read_pfm_field(file, scale_text))
    throw corrupt("incomplete or invalid header");
  if (magic != "PF" && magic != "Pf") throw corrupt("unknown type '" + magic + "'");
  std::int64_t width = 0;
  std::int64_t height = 0;
  if (!parse_number(width_text, width) || !parse_number(height_text, height))
    throw corrupt("invalid size '" + width_text + " " + height_text + "'");
  float scale = 0.0f;
  if (!parse_number(scale_text, scale) || !std::isfinite(scale) || scale == 0.0f)
    throw corrupt("invalid scale '" + scale_text + "'");
  check_size(input.name, width, height, limits);

  const int channels = magic == "PF" ? 3 : 1;
  const std::size_t row_bytes = static_cast<std::size_t>(width) * channels * sizeof(float);
  const std::size_t pixel_bytes = row_bytes * static_cast<std::size_t>(height);
  const off_t header_bytes = ftello(file);
  if (header_bytes < 0)
    throw Error(ErrorCode::io, "cannot read " + input.name + ": " + errno_message(errno));
  // Uncompressed: the pixels need exactly their size after the header.
  check_fits_file(input.name, width, height,
                  static_cast<double>(header_bytes) + static_cast<double>(pixel_bytes),
                  input.bytes);

  const bool little_endian = scale < 0.0f;
  check_declared(width, height, channels, limits);
  ImageF image(static_cast<int>(width), static_cast<int>(height), channels);
  std::vector<unsigned char> bytes(row_bytes);
  for (int y = image.height() - 1; y >= 0; --y) {
    if (std::fread(bytes.data(), 1, row_bytes, file) != row_bytes)
      throw corrupt("the file ends too early");
    float* row = image.view().row(y);
    for (std::size_t i = 0; i < row_bytes / 4; ++i) {
      const unsigned char* b = bytes.data() + 4 * i;
      const std::uint32_t word = little_endian
                                     ? std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 |
                                           std::uint32_t{b[2]} << 16 | std::uint32_t{b[3]} << 24
                                     : std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 |
                                           std::uint32_t{b[1]} << 16 | std::uint32_t{b[0]} << 24;
      row[i] = std::bit_cast<float>(word);
    }
  }
  if (colour) *colour = {ColourSpace::linear, "PFM: linear"};
  return image;
}

void write_pfm(Imf::OStream& stream, ImageView<const float> image) {
  const std::string header = std::string(image.channels == 3 ? "PF" : "Pf") + "\n" +
                             std::to_string(image.width) + " " + std::to_string(image.height) +
                             "\n-1.0\n";
  const std::size_t row_values = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<unsigned char> bytes(row_values * 4);
  write_all(stream, header.data(), header.size());
  for (int y = image.height - 1; y >= 0; --y) {
    const float* row = image.row(y);
    for (std::size_t i = 0; i < row_values; ++i) {
      const auto word = std::bit_cast<std::uint32_t>(row[i]);
      for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<unsigned char>(word >> (8 * b));
    }
    write_all(stream, bytes.data(), bytes.size());
  }
}

// ---------------------------------------------------------------------------------------------
// The formats. read_image and decode_image give an image to the first row that recognises its
// first bytes; write_image picks the row of its path's extension, encode_image the row of its
// format. A new format is one row; one that is only read has no encoder (nullptr), and
// write_image refuses its extension.

// How many of an image's first bytes the rows' signatures look at (a TGA header's 18).
constexpr std::size_t kSignatureBytes = 18;

// The float formats hold linear light: an srgb image is decoded before it is written.
template <void (*write)(Imf::OStream&, ImageView<const float>)>
void write_linear(Imf::OStream& stream, ImageView<const float> image, int, ColourSpace space) {
  if (space == ColourSpace::srgb) {
    const ImageF linear = srgb_decoded(image);
    write(stream, linear.view());
  } else {
    write(stream, image);
  }
}

struct Codec {
  ImageFormat format;     // of a format write_image writes (`encode`); png for the others
  const char* name;       // in messages: "PNG"
  const char* extension;  // what write_image writes the format for, in lower case: ".png"
  bool (*recognises)(std::span<const unsigned char> first_bytes);
  // `colour`: see read_image.
  ImageF (*decode)(const Input& input, const ImageReadLimits& limits, ImageColour* colour);
  // `space`: see write_image.
  void (*encode)(Imf::OStream& stream, ImageView<const float> image, int png_bit_depth,
                 ColourSpace space);
};

const std::array<Codec, 7> kCodecs = {{
    {ImageFormat::png, "PNG", ".png",
     [](std::span<const unsigned char> first) {
       return first.size() >= 8 && png_sig_cmp(first.data(), 0, 8) == 0;
     },
     read_png, write_png},
    {ImageFormat::exr, "OpenEXR", ".exr",
     [](std::span<const unsigned char> first) {
       return first.size() >= 4 && first[0] == 0x76 && first[1] == 0x2f && first[2] == 0x31 &&
              first[3] == 0x01;
     },
     read_exr, write_linear<write_exr>},
    {ImageFormat::pfm, "PFM", ".pfm",
     [](std::span<const unsigned char> first) {
       return first.size() >= 2 && first[0] == 'P' && (first[1] == 'F' || first[1] == 'f');
     },
     read_pfm, write_linear<write_pfm>},
    // Read only: what photos and paint programs write. TGA has no signature and comes last.
    {ImageFormat::png, "JPEG", ".jpg", is_jpeg, read_jpeg, nullptr},
    {ImageFormat::png, "TIFF", ".tif", is_tiff, read_tiff, nullptr},
    {ImageFormat::png, "WebP", ".webp", is_webp, read_webp, nullptr},
    {ImageFormat::png, "TGA", ".tga", is_tga, read_tga, nullptr},
}};

// The rows' `field` that `keep` keeps, as "a, b or c".
template <typename Keep>
std::string one_of(const char* Codec::*field, Keep keep) {
  std::vector<const char*> words;
  for (const Codec& codec : kCodecs)
    if (keep(codec)) words.push_back(codec.*field);
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) text += i + 1 == words.size() ? " or " : ", ";
    text += words[i];
  }
  return text;
}

bool is_written(const Codec& codec) {
  return codec.encode != nullptr;
}

const Codec& output_codec(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const Codec& codec : kCodecs)
    if (is_written(codec) && extension == codec.extension) return codec;
  throw std::invalid_argument("cannot write " + quoted(path) + ": unsupported extension '" +
                              extension + "'; use " + one_of(&Codec::extension, is_written));
}

[[noreturn]] void throw_empty(const std::string& name) {
  throw Error(ErrorCode::format, name + " is empty (0 bytes), not an image");
}

ImageF decode(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  std::array<unsigned char, kSignatureBytes> first{};
  const std::size_t first_bytes = std::fread(first.data(), 1, first.size(), input.file);
  if (std::ferror(input.file))
    throw Error(ErrorCode::io, "cannot read " + input.name + ": " + errno_message(errno));
  if (first_bytes == 0) throw_empty(input.name);
  if (std::fseek(input.file, 0, SEEK_SET) != 0)
    throw Error(ErrorCode::io, "cannot read " + input.name + ": " + errno_message(errno));
  for (const Codec& codec : kCodecs)
    if (codec.recognises({first.data(), first_bytes})) return codec.decode(input, limits, colour);
  const std::string formats = one_of(&Codec::name, [](const Codec&) { return true; });
  throw Error(ErrorCode::format, input.name + " is not a " + formats +
                                     " image (its first bytes match none of them); convert it to "
                                     "one of these formats");
}

// The checks of write_image's and encode_image's arguments, in that order; each message begins
// with `cannot` ("cannot write 'out.png'").
void check_image_shape(int width, int height, int channels, bool has_pixels,
                       const std::string& cannot) {
  if (!has_pixels || width < 1 || height < 1 || channels < 1 || channels > 4)
    throw std::invalid_argument(cannot + ": the image is " + std::to_string(width) + "x" +
                                std::to_string(height) + " pixels with " +
                                std::to_string(channels) +
                                " channels; it needs at least one pixel and 1 to 4 channels");
}

void check_image_shape(ImageView<const float> image, const std::string& cannot) {
  check_image_shape(image.width, image.height, image.channels, image.data != nullptr, cannot);
}

void check_bit_depth(const Codec& codec, int png_bit_depth, const std::string& cannot) {
  if (codec.format == ImageFormat::png && png_bit_depth != 8 && png_bit_depth != 16)
    throw std::invalid_argument(cannot + ": PNG bit depth " + std::to_string(png_bit_depth) +
                                " is not supported; use 8 or 16");
}

void check_channels(const Codec& codec, int channels, const std::string& cannot) {
  if (codec.format == ImageFormat::pfm && channels != 1 && channels != 3)
    throw Error(ErrorCode::invalid_input,
                cannot + ": PFM holds 1 or 3 channels and the image has " +
                    std::to_string(channels) + "; write .exr or .png instead");
}

}  // namespace

ImageF read_image(const fs::path& path, const ImageReadLimits& limits, ImageColour* colour) {
  const InputFile file(path, "an image");
  return decode({file.stream(), file.size(), quoted(path), path.string()}, limits, colour);
}

ImageF decode_image(std::span<const std::uint8_t> bytes, const std::string& name,
                    const ImageReadLimits& limits, ImageColour* colour) {
  if (name.empty())
    throw std::invalid_argument("decode_image: the bytes need a name for the messages");
  if (bytes.empty()) throw_empty(name);
  // fmemopen takes a void *; a stream opened for reading never writes through it.
  File file(fmemopen(const_cast<std::uint8_t*>(bytes.data()), bytes.size(), "rb"));
  if (!file) throw std::bad_alloc();
  return decode({file.get(), bytes.size(), name, name}, limits, colour);
}

namespace {

// Checks what write_image checks, then encodes `image` into the temporary `open` gives.
void write_image_to(const fs::path& path, ImageView<const float> image, int png_bit_depth,
                    ColourSpace space, const std::function<AtomicFile&()>& open) {
  const std::string cannot = "cannot write " + quoted(path);
  check_image_shape(image, cannot);
  const Codec& codec = output_codec(path);
  check_bit_depth(codec, png_bit_depth, cannot);
  check_channels(codec, image.channels, cannot);

  AtomicFile& file = open();
  try {
    FileOutputStream stream(file.stream(), file.temporary().c_str());
    codec.encode(stream, image, png_bit_depth, space);
  } catch (const std::exception& e) {
    throw Error(ErrorCode::io, cannot + ": " + e.what());
  }
  file.finish();
}

}  // namespace

void write_image(const fs::path& path, ImageView<const float> image, int png_bit_depth,
                 ColourSpace space) {
  std::optional<AtomicFile> file;
  write_image_to(path, image, png_bit_depth, space,
                 [&]() -> AtomicFile& { return file.emplace(path); });
  file->commit();
}

void write_image(AtomicFileSet& files, const fs::path& path, ImageView<const float> image,
                 int png_bit_depth, ColourSpace space) {
  write_image_to(path, image, png_bit_depth, space,
                 [&]() -> AtomicFile& { return files.open(path); });
}

void write_png_strips(const fs::path& path, int width, int height, int channels, int png_bit_depth,
                      ColourSpace space, const StripMaker& make_strip) {
  const std::string cannot = "cannot write " + quoted(path);
  check_image_shape(width, height, channels, true, cannot);
  const Codec& codec = output_codec(path);
  if (codec.format != ImageFormat::png)
    throw std::invalid_argument(cannot + ": write_png_strips writes PNG files only");
  check_bit_depth(codec, png_bit_depth, cannot);

  // The encoder's steps fail as write_image's do; make_strip's failures pass as they are.
  const auto encoding = [&](const auto& step) {
    try {
      step();
    } catch (const std::exception& e) {
      throw Error(ErrorCode::io, cannot + ": " + e.what());
    }
  };
  AtomicFile file(path);
  FileOutputStream stream(file.stream(), file.temporary().c_str());
  std::optional<PngEncoder> encoder;
  encoding([&] { encoder.emplace(stream, width, height, channels, png_bit_depth, space); });
  // Strip k is made into strips[k % 2] while strip k - 1 is encoded from the other; the encoder
  // of strip k - 2 had finished before k - 1's began.
  std::array<ImageF, 2> strips = {ImageF(width, std::min(kPngStripRows, height), channels),
                                  ImageF(width, std::min(kPngStripRows, height), channels)};
  std::future<void> encoded;  // destroyed first: waits for the strip in flight
  for (int first_row = 0, k = 0; first_row < height; first_row += kPngStripRows, ++k) {
    const ImageView<float> strip = strips[static_cast<std::size_t>(k % 2)].view().sub(
        0, 0, width, std::min(kPngStripRows, height - first_row));
    make_strip(first_row, strip);
    if (encoded.valid()) encoding([&] { encoded.get(); });
    encoded = std::async(std::launch::async, [&encoder, strip] { encoder->write(strip); });
  }
  encoding([&] {
    encoded.get();
    encoder->finish();
  });
  file.finish();
  file.commit();
}

std::vector<std::uint8_t> encode_image(ImageView<const float> image, ImageFormat format,
                                       int png_bit_depth, ColourSpace space) {
  const auto codec = std::find_if(kCodecs.begin(), kCodecs.end(), [&](const Codec& row) {
    return row.format == format && is_written(row);
  });
  if (codec == kCodecs.end())
    throw std::invalid_argument("encode_image: no encoder for image format " +
                                std::to_string(static_cast<int>(format)));
  const std::string cannot = std::string("cannot encode the image as ") + codec->name;
  check_image_shape(image, cannot);
  check_bit_depth(*codec, png_bit_depth, cannot);
  check_channels(*codec, image.channels, cannot);

  BufferOutputStream stream("the encoded image");
  try {
    codec->encode(stream, image, png_bit_depth, space);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorCode::io, cannot + ": " + e.what());
  }
  return stream.take();
}

ImageFormat output_image_format(const fs::path& path) {
  return output_codec(path).format;
}

bool is_exr_output(const fs::path& path) {
  return output_image_format(path) == ImageFormat::exr;
}

void check_output_channels(const fs::path& path, int channels) {
  check_channels(output_codec(path), channels, "cannot write " + quoted(path));
}

void check_output_path(const fs::path& path, bool image, const std::vector<fs::path>& inputs) {
  if (image) output_codec(path);
  check_output_target(path);
  for (const fs::path& input : inputs)
    if (!input.empty()) check_output_is_not_input(path, input);
}

}  // namespace stochtex
