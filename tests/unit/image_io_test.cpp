// Image files: exact round trips, format detection by content, one clear error for every bad file
// (docs/design.md §6 and §9), and colour: the chunks honoured on reading, the colour written
// (§14).

#include "io/image_io.hpp"

#include <gtest/gtest.h>
#include <lcms2.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/srgb.hpp"
#include "io/png_sample.hpp"
#include "io/tiled_exr.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "test_support.hpp"

namespace stochtex::image_io_test {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

using ImageIoTest = test_support::FolderTest;

ImageF make_image(int width, int height, int channels, float (*value)(int x, int y, int c)) {
  ImageF image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y, c) = value(x, y, c);
  return image;
}

void expect_identical(const ImageF& expected, const ImageF& actual) {
  ASSERT_EQ(actual.width(), expected.width());
  ASSERT_EQ(actual.height(), expected.height());
  ASSERT_EQ(actual.channels(), expected.channels());
  for (std::size_t i = 0; i < expected.pixels().size(); ++i)
    ASSERT_EQ(actual.pixels()[i], expected.pixels()[i]) << "sample " << i;
}

void write_bytes(const fs::path& path, const Bytes& bytes) {
  std::ofstream stream(path, std::ios::binary);
  stream.write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
}

void append_u32_big_endian(Bytes& bytes, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8)
    bytes.push_back(static_cast<unsigned char>(value >> shift));
}

// The PNG chunk checksum is zlib's CRC-32.
std::uint32_t crc32(const unsigned char* data, std::size_t size) {
  return static_cast<std::uint32_t>(::crc32(0L, data, static_cast<uInt>(size)));
}

void append_chunk(Bytes& png, const std::string& type, const Bytes& data) {
  append_u32_big_endian(png, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = png.size();
  png.insert(png.end(), type.begin(), type.end());
  png.insert(png.end(), data.begin(), data.end());
  append_u32_big_endian(png, crc32(png.data() + start, png.size() - start));
}

// A PNG written by hand (so the tests can produce layouts write_image never does: palettes,
// 1- and 2-bit samples, interlacing, hostile sizes). The pixel rows, each led by its filter byte,
// go into one stored (uncompressed) deflate block.
Bytes handmade_png(std::uint32_t width, std::uint32_t height, int bit_depth, int color_type,
                   const Bytes& raw_rows, int interlace = 0, const Bytes& palette = {},
                   const Bytes& transparency = {}) {
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes header;
  append_u32_big_endian(header, width);
  append_u32_big_endian(header, height);
  header.insert(header.end(),
                {static_cast<unsigned char>(bit_depth), static_cast<unsigned char>(color_type), 0,
                 0, static_cast<unsigned char>(interlace)});
  append_chunk(png, "IHDR", header);
  if (!palette.empty()) append_chunk(png, "PLTE", palette);
  if (!transparency.empty()) append_chunk(png, "tRNS", transparency);
  const auto size = static_cast<std::uint16_t>(raw_rows.size());
  Bytes zlib = {0x78,
                0x01,
                0x01,
                static_cast<unsigned char>(size & 0xff),
                static_cast<unsigned char>(size >> 8),
                static_cast<unsigned char>(~size & 0xff),
                static_cast<unsigned char>((~size >> 8) & 0xff)};
  zlib.insert(zlib.end(), raw_rows.begin(), raw_rows.end());
  std::uint32_t a = 1, b = 0;
  for (unsigned char byte : raw_rows) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  append_u32_big_endian(zlib, b << 16 | a);
  append_chunk(png, "IDAT", zlib);
  append_chunk(png, "IEND", {});
  return png;
}

ErrorCode read_error_code(const fs::path& path, const ImageReadLimits& limits = {}) {
  try {
    read_image(path, limits);
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path.filename().string()), std::string::npos)
        << "the message names the file: " << error.what();
    return error.code();
  }
  ADD_FAILURE() << "reading " << path << " did not throw";
  return ErrorCode::numerical;
}

TEST_F(ImageIoTest, Png8BitRoundTripIsExact) {
  for (int channels = 1; channels <= 4; ++channels) {
    const ImageF image = make_image(37, 19, channels, [](int x, int y, int c) {
      return static_cast<float>((x * 7 + y * 13 + c * 29) % 256) / 255.0f;
    });
    const fs::path path = file("image8_" + std::to_string(channels) + ".png");
    write_image(path, image.view(), 8);
    expect_identical(image, read_image(path));
  }
}

TEST_F(ImageIoTest, Png16BitRoundTripIsExact) {
  for (int channels = 1; channels <= 4; ++channels) {
    const ImageF image = make_image(41, 23, channels, [](int x, int y, int c) {
      return static_cast<float>((x * 4099 + y * 1601 * 41 + c * 12345) % 65536) / 65535.0f;
    });
    const fs::path path = file("image16_" + std::to_string(channels) + ".png");
    write_image(path, image.view(), 16);
    expect_identical(image, read_image(path));
  }
}

TEST_F(ImageIoTest, PngClampsAndRoundsOutOfRangeValues) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ImageF image(5, 1, 1);
  const float values[] = {-0.5f, nan, 2.0f, 0.5f, 0.25f / 255.0f};
  for (int x = 0; x < 5; ++x) image.at(x, 0, 0) = values[x];
  write_image(file("clamped.png"), image.view());
  const ImageF read = read_image(file("clamped.png"));
  EXPECT_EQ(read.at(0, 0, 0), 0.0f);
  EXPECT_EQ(read.at(1, 0, 0), 0.0f);
  EXPECT_EQ(read.at(2, 0, 0), 1.0f);
  EXPECT_EQ(read.at(3, 0, 0), 128.0f / 255.0f);
  EXPECT_EQ(read.at(4, 0, 0), 0.0f);
}

// The PNG sample of a value as write_image has always written it (docs/design.md §14): NaN and
// values up to 0 are 0, from 1 on `maximum`, the others rounded by std::lround.
unsigned lround_sample(float value, unsigned maximum) {
  if (!(value > 0.0f)) return 0;
  if (value >= 1.0f) return maximum;
  return static_cast<unsigned>(std::lround(value * static_cast<float>(maximum)));
}

// png_sample rounds as std::lround did: halves up, on every 61st float of [0, 1] (whose products
// with 255 and 65535 meet every rounding case) and on each tie.
TEST(PngSampleTest, RoundsAsLround) {
  for (const unsigned maximum : {255u, 65535u}) {
    std::uint64_t differences = 0;
    for (std::uint32_t bits = 0; bits <= std::bit_cast<std::uint32_t>(1.0f); bits += 61) {
      const float value = std::bit_cast<float>(bits);
      differences += png_sample(value, maximum) != lround_sample(value, maximum);
    }
    for (unsigned k = 0; k < maximum; ++k)
      for (float tie = (static_cast<float>(k) + 0.5f) / static_cast<float>(maximum);
           const float value : {std::nextafter(tie, 0.0f), tie, std::nextafter(tie, 1.0f)})
        differences += png_sample(value, maximum) != lround_sample(value, maximum);
    EXPECT_EQ(differences, 0u) << maximum;
  }
}

// SrgbSamples8's table gives the formula's 8-bit sample, png_sample(srgb_encode(l), 255), on
// every float from its lowest bucket to 1, on every 31st float below, and on the values beyond.
TEST(PngSampleTest, SrgbSamplesAreTheFormulasOnEveryFloat) {
  const SrgbSamples8& table = SrgbSamples8::get();
  const auto formula = [](float linear) { return png_sample(srgb_encode(linear), 255); };
  const auto low = std::bit_cast<std::uint32_t>(SrgbSamples8::kLow);
  const auto one = std::bit_cast<std::uint32_t>(1.0f);
  std::uint64_t differences = 0;
  for (std::uint32_t bits = low; bits <= one; ++bits) {
    const float linear = std::bit_cast<float>(bits);
    differences += table(linear) != formula(linear);
  }
  for (std::uint32_t bits = 0; bits < low; bits += 31) {
    const float linear = std::bit_cast<float>(bits);
    differences += table(linear) != formula(linear);
  }
  EXPECT_EQ(differences, 0u);
  const float infinity = std::numeric_limits<float>::infinity();
  for (const float linear : {-0.0f, -1e-30f, -0.5f, -infinity, std::nextafter(1.0f, 2.0f), 1.5f,
                             1e30f, infinity, std::numeric_limits<float>::quiet_NaN()})
    EXPECT_EQ(table(linear), formula(linear)) << linear;
  EXPECT_EQ(table(0.5f), 188u);  // 0.73536 after the transfer function
}

// A render-like image: values spread over [-0.1, 1.1] (so some clamp) with a NaN now and then.
ImageF noisy_image(int width, int height, int channels, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(-0.1f, 1.1f);
  ImageF image(width, height, channels);
  for (float& sample : image.pixels())
    sample = random() % 997 == 0 ? std::numeric_limits<float>::quiet_NaN() : value(random);
  return image;
}

// Every PNG write_image and write_png_strips make decodes to the samples of the rule they were
// always written by (lround_sample of the value, sRGB-encoded by the formula for a linear image's
// colour channels), whatever the compression; write_png_strips, in strips of kPngStripRows rows
// (here 3, the last short), writes write_image's bytes.
TEST_F(ImageIoTest, PngsHoldTheSamplesOfTheRuleInStripsToo) {
  const int width = 45;
  const int height = 2 * kPngStripRows + 11;
  for (const int bit_depth : {8, 16})
    for (int channels = 1; channels <= 4; ++channels)
      for (const ColourSpace space : {ColourSpace::data, ColourSpace::linear, ColourSpace::srgb}) {
        const std::string context = std::to_string(bit_depth) + "-bit, " +
                                    std::to_string(channels) + " channels, " +
                                    std::string(colour_space_name(space));
        const ImageF image = noisy_image(width, height, channels, 7 * channels + bit_depth);
        const fs::path whole = file("whole.png");
        write_image(whole, image.view(), bit_depth, space);
        const fs::path strips = file("strips.png");
        std::vector<int> first_rows;
        write_png_strips(strips, width, height, channels, bit_depth, space,
                         [&](int first_row, ImageView<float> out) {
                           first_rows.push_back(first_row);
                           EXPECT_EQ(out.width, width);
                           EXPECT_EQ(out.height, std::min(kPngStripRows, height - first_row));
                           for (int y = 0; y < out.height; ++y)
                             for (int x = 0; x < width; ++x)
                               for (int c = 0; c < channels; ++c)
                                 out.at(x, y, c) = image.at(x, first_row + y, c);
                         });
        EXPECT_EQ(first_rows, (std::vector<int>{0, kPngStripRows, 2 * kPngStripRows})) << context;
        EXPECT_EQ(test_support::file_bytes(strips), test_support::file_bytes(whole)) << context;

        const unsigned maximum = bit_depth == 8 ? 255 : 65535;
        const ImageF read = read_image(whole);
        for (int y = 0; y < height; ++y)
          for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
              float value = image.at(x, y, c);
              if (space == ColourSpace::linear && is_colour_channel(c, channels))
                value = srgb_encode(value);
              ASSERT_EQ(read.at(x, y, c), static_cast<float>(lround_sample(value, maximum)) /
                                              static_cast<float>(maximum))
                  << context << ", pixel " << x << "," << y << " channel " << c;
            }
      }
}

TEST_F(ImageIoTest, PngStripsThatFailLeaveNoFile) {
  const fs::path path = file("strips.png");
  const auto fail_second = [](int first_row, ImageView<float> out) {
    if (first_row > 0) throw std::runtime_error("the render stopped");
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) out.at(x, y, 0) = 0.5f;
  };
  EXPECT_THROW(write_png_strips(path, 8, 3 * kPngStripRows, 1, 8, ColourSpace::data, fail_second),
               std::runtime_error);
  EXPECT_TRUE(folder_contents().empty());
  const auto unused = [](int, ImageView<float>) { ADD_FAILURE() << "a strip was made"; };
  EXPECT_THROW(write_png_strips(file("strips.exr"), 8, 8, 1, 8, ColourSpace::data, unused),
               std::invalid_argument);
  EXPECT_THROW(write_png_strips(path, 8, 8, 5, 8, ColourSpace::data, unused),
               std::invalid_argument);
  EXPECT_THROW(write_png_strips(path, 8, 8, 1, 12, ColourSpace::data, unused),
               std::invalid_argument);
  EXPECT_TRUE(folder_contents().empty());
}

TEST_F(ImageIoTest, ExrFloatRoundTripIsExact) {
  for (int channels = 1; channels <= 4; ++channels) {
    const ImageF image = make_image(29, 17, channels, [](int x, int y, int c) {
      return std::ldexp(static_cast<float>(x - 14) * 0.3183099f + static_cast<float>(c), y - 8);
    });
    const fs::path path = file("image_" + std::to_string(channels) + ".exr");
    write_image(path, image.view());
    expect_identical(image, read_image(path));
  }
}

TEST_F(ImageIoTest, PfmRoundTripIsExactForGreyAndRgb) {
  for (int channels : {1, 3}) {
    const ImageF image = make_image(13, 11, channels, [](int x, int y, int c) {
      return static_cast<float>(x * 100 + y) * 1e-3f - static_cast<float>(c) * 7.5f;
    });
    const fs::path path = file("image_" + std::to_string(channels) + ".pfm");
    write_image(path, image.view());
    expect_identical(image, read_image(path));
  }
}

TEST_F(ImageIoTest, PfmStoresRowsBottomToTopAndHonoursByteOrder) {
  // Big-endian (positive scale) grey 1x2: the first row in the file is the bottom of the image.
  Bytes pfm = {'P', 'f', '\n', '1', ' ', '2', '\n', '1', '.', '0', '\n'};
  append_u32_big_endian(pfm, 0x3f800000u);  // 1.0f
  append_u32_big_endian(pfm, 0x40000000u);  // 2.0f
  write_bytes(file("big_endian.pfm"), pfm);
  const ImageF image = read_image(file("big_endian.pfm"));
  ASSERT_EQ(image.width(), 1);
  ASSERT_EQ(image.height(), 2);
  EXPECT_EQ(image.at(0, 0, 0), 2.0f);
  EXPECT_EQ(image.at(0, 1, 0), 1.0f);
}

TEST_F(ImageIoTest, PfmRefusesTwoOrFourChannels) {
  for (int channels : {2, 4}) {
    const ImageF image(4, 4, channels, 0.5f);
    const fs::path path = file("image.pfm");
    try {
      write_image(path, image.view());
      FAIL() << "a " << channels << "-channel PFM was written";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(".exr"), std::string::npos) << error.what();
    }
    EXPECT_TRUE(folder_contents().empty());
  }
}

TEST_F(ImageIoTest, WritingAStridedViewWritesOnlyItsPixels) {
  const ImageF image = make_image(
      8, 6, 3, [](int x, int y, int c) { return static_cast<float>(x + 8 * y + 48 * c) / 255.0f; });
  const ImageView<const float> region = image.view().sub(2, 1, 4, 3);
  for (const char* name : {"region.png", "region.exr", "region.pfm"}) {
    write_image(file(name), region);
    const ImageF read = read_image(file(name));
    ASSERT_EQ(read.width(), 4);
    ASSERT_EQ(read.height(), 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(read.at(x, y, c), region.at(x, y, c)) << name << " " << x << "," << y;
  }
}

TEST_F(ImageIoTest, FormatIsRecognisedByContentNotExtension) {
  const ImageF image = make_image(
      4, 4, 3, [](int x, int y, int c) { return static_cast<float>(x + y + c) / 255.0f; });
  write_image(file("image.png"), image.view());
  fs::rename(file("image.png"), file("misnamed.exr"));
  expect_identical(image, read_image(file("misnamed.exr")));
}

TEST_F(ImageIoTest, CorpusPngsRead) {
  const ImageF grass = read_image(STOCHTEX_TEXTURE_DIR "/grass_lawn_128.png");
  EXPECT_EQ(grass.width(), 128);
  EXPECT_EQ(grass.height(), 128);
  EXPECT_EQ(grass.channels(), 3);
  float lowest = 1.0f, highest = 0.0f;
  for (float value : grass.pixels()) {
    lowest = std::min(lowest, value);
    highest = std::max(highest, value);
  }
  EXPECT_GE(lowest, 0.0f);
  EXPECT_LE(highest, 1.0f);
  EXPECT_LT(lowest, highest);

  int corpus_files = 0;
  for (const auto& entry : fs::directory_iterator(STOCHTEX_TEXTURE_DIR)) {
    if (entry.path().extension() != ".png") continue;
    const ImageF image = read_image(entry.path());
    EXPECT_TRUE(image.channels() == 1 || image.channels() == 3) << entry.path();
    EXPECT_GE(image.width(), 128) << entry.path();
    ++corpus_files;
  }
  EXPECT_GT(corpus_files, 0);
}

TEST_F(ImageIoTest, PalettesAndLowBitDepthsAreExpanded) {
  // 3x2, 2 bits per index; entry 1 is half transparent, so the image becomes RGBA.
  const Bytes palette = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
  const Bytes indices = {0, 0b00'01'10'00, 0, 0b11'10'01'00};
  write_bytes(file("palette.png"), handmade_png(3, 2, 2, 3, indices, 0, palette, {255, 128}));
  const ImageF image = read_image(file("palette.png"));
  ASSERT_EQ(image.channels(), 4);
  EXPECT_EQ(image.at(0, 0, 0), 1.0f);
  EXPECT_EQ(image.at(1, 0, 1), 1.0f);
  EXPECT_EQ(image.at(1, 0, 3), 128.0f / 255.0f);
  EXPECT_EQ(image.at(0, 1, 2), 30.0f / 255.0f);
  EXPECT_EQ(image.at(0, 1, 3), 1.0f);

  // 1-bit grey: 1 0 1 becomes 1 0 1 in [0, 1].
  write_bytes(file("bilevel.png"), handmade_png(3, 1, 1, 0, {0, 0b1010'0000}));
  const ImageF bilevel = read_image(file("bilevel.png"));
  ASSERT_EQ(bilevel.channels(), 1);
  EXPECT_EQ(bilevel.at(0, 0, 0), 1.0f);
  EXPECT_EQ(bilevel.at(1, 0, 0), 0.0f);
  EXPECT_EQ(bilevel.at(2, 0, 0), 1.0f);
}

TEST_F(ImageIoTest, InterlacedPngIsDeinterlaced) {
  // Adam7 on 2x2: pass 1 holds (0,0), pass 6 holds (1,0), pass 7 holds row 1.
  write_bytes(file("interlaced.png"), handmade_png(2, 2, 8, 0, {0, 10, 0, 20, 0, 30, 40}, 1));
  const ImageF image = read_image(file("interlaced.png"));
  EXPECT_EQ(image.at(0, 0, 0), 10.0f / 255.0f);
  EXPECT_EQ(image.at(1, 0, 0), 20.0f / 255.0f);
  EXPECT_EQ(image.at(0, 1, 0), 30.0f / 255.0f);
  EXPECT_EQ(image.at(1, 1, 0), 40.0f / 255.0f);
}

TEST_F(ImageIoTest, TruncatedFilesAreFormatErrors) {
  const ImageF image = make_image(32, 32, 3, [](int x, int y, int c) {
    return static_cast<float>((x * 37 + y * 11 + c) % 256) / 255.0f;
  });
  for (const char* name : {"whole.png", "whole.exr", "whole.pfm"}) {
    write_image(file(name), image.view());
    const Bytes whole = test_support::file_bytes(file(name));
    const fs::path truncated = file(std::string("half_") + name);
    write_bytes(truncated, Bytes(whole.begin(), whole.begin() + whole.size() / 2));
    EXPECT_EQ(read_error_code(truncated), ErrorCode::format) << name;
  }
}

TEST_F(ImageIoTest, RandomBytesAreFormatErrors) {
  std::mt19937 random(12345);
  Bytes noise(4096);
  for (auto& byte : noise) byte = static_cast<unsigned char>(random());
  noise[0] = 'x';
  write_bytes(file("noise.png"), noise);
  EXPECT_EQ(read_error_code(file("noise.png")), ErrorCode::format);

  // The same noise behind a valid PNG signature reaches libpng, which must refuse it cleanly.
  const Bytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::copy(signature.begin(), signature.end(), noise.begin());
  write_bytes(file("noise_after_signature.png"), noise);
  EXPECT_EQ(read_error_code(file("noise_after_signature.png")), ErrorCode::format);
}

TEST_F(ImageIoTest, EmptyFileIsAFormatError) {
  write_bytes(file("empty.png"), {});
  EXPECT_EQ(read_error_code(file("empty.png")), ErrorCode::format);
}

TEST_F(ImageIoTest, HugeDeclaredSizesAreRefusedBeforeAllocating) {
  // Valid headers (checksums included) claiming 100000x100000 pixels, with almost no data.
  write_bytes(file("huge.png"), handmade_png(100000, 100000, 8, 0, {0, 1}));
  EXPECT_EQ(read_error_code(file("huge.png")), ErrorCode::invalid_input);

  const std::string pfm_header = "PF\n100000 100000\n-1.0\n";
  write_bytes(file("huge.pfm"), Bytes(pfm_header.begin(), pfm_header.end()));
  EXPECT_EQ(read_error_code(file("huge.pfm")), ErrorCode::invalid_input);

  // An EXR whose data window is edited to 100000x100000 pixels.
  write_image(file("small.exr"), ImageF(2, 2, 1, 0.5f).view());
  Bytes exr = test_support::file_bytes(file("small.exr"));
  const std::string attribute = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const auto found = std::search(exr.begin(), exr.end(), attribute.begin(), attribute.end());
  ASSERT_NE(found, exr.end());
  const auto box = found + static_cast<std::ptrdiff_t>(attribute.size()) + 4;  // after the size
  const std::uint32_t last = 99999;
  for (int corner : {2, 3})  // max.x and max.y, little-endian int32
    for (int b = 0; b < 4; ++b) box[4 * corner + b] = static_cast<unsigned char>(last >> (8 * b));
  write_bytes(file("huge.exr"), exr);
  EXPECT_EQ(read_error_code(file("huge.exr")), ErrorCode::invalid_input);
}

// In a child process (a death test), reads `path` (or decodes its bytes, with `from_memory`) with
// an address space that may grow by 64 MiB only: exits 0 when the read is refused cleanly, and
// dies when anything near the declared size is allocated.
[[noreturn]] void read_with_little_memory(const fs::path& path, bool from_memory) {
  const Bytes bytes = from_memory ? test_support::file_bytes(path) : Bytes();
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  const rlim_t limit = pages * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) + (64u << 20);
  const rlimit address_space{limit, limit};
  ::setrlimit(RLIMIT_AS, &address_space);
  try {
    if (from_memory)
      decode_image(bytes, "the upload");
    else
      read_image(path);
  } catch (const Error&) {
    std::_Exit(0);
  }
  std::_Exit(1);
}

void expect_refused_without_allocating(const fs::path& path) {
  for (const bool from_memory : {false, true})
    EXPECT_EXIT(read_with_little_memory(path, from_memory), testing::ExitedWithCode(0), "")
        << path << (from_memory ? " from memory" : "");
}

void append_u32_little_endian(Bytes& bytes, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8)
    bytes.push_back(static_cast<unsigned char>(value >> shift));
}

void append_attribute(Bytes& exr, const std::string& name, const std::string& type,
                      const Bytes& value, std::uint32_t declared_size) {
  exr.insert(exr.end(), name.begin(), name.end());
  exr.push_back(0);
  exr.insert(exr.end(), type.begin(), type.end());
  exr.push_back(0);
  append_u32_little_endian(exr, declared_size);
  exr.insert(exr.end(), value.begin(), value.end());
}

// An uncompressed scanline OpenEXR header of width x height half R, G, B, A pixels, with `extra`
// attributes, up to its end: the offset table and the pixels are the caller's.
Bytes handmade_exr_header(std::uint32_t width, std::uint32_t height, const Bytes& extra = {}) {
  Bytes exr = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
  Bytes channels;
  for (const char* name : {"A", "B", "G", "R"}) {
    channels.insert(channels.end(), {static_cast<unsigned char>(name[0]), 0});
    for (std::uint32_t field : {1u, 0u, 1u, 1u}) append_u32_little_endian(channels, field);
  }
  channels.push_back(0);
  const auto add = [&](const std::string& name, const std::string& type, const Bytes& value) {
    append_attribute(exr, name, type, value, static_cast<std::uint32_t>(value.size()));
  };
  Bytes window;
  for (std::uint32_t corner : {0u, 0u, width - 1, height - 1})
    append_u32_little_endian(window, corner);
  Bytes one;
  append_u32_little_endian(one, 0x3f800000);  // 1.0f
  add("channels", "chlist", channels);
  add("compression", "compression", {0});
  add("dataWindow", "box2i", window);
  add("displayWindow", "box2i", window);
  add("lineOrder", "lineOrder", {0});
  add("pixelAspectRatio", "float", one);
  add("screenWindowCenter", "v2f", Bytes(8, 0));
  add("screenWindowWidth", "float", one);
  exr.insert(exr.end(), extra.begin(), extra.end());
  exr.push_back(0);
  return exr;
}

TEST_F(ImageIoTest, TinyFilesDeclaringHugeContentsAreRefusedWithoutAllocatingThem) {
  // A text chunk declaring 2^31 - 1 bytes, cut off after its type.
  Bytes text_bomb = handmade_png(1, 1, 8, 0, {0, 0});
  text_bomb.resize(33);  // the signature and the header chunk
  append_u32_big_endian(text_bomb, 0x7fffffff);
  text_bomb.insert(text_bomb.end(), {'t', 'E', 'X', 't'});
  write_bytes(file("text_bomb.png"), text_bomb);

  // 8192 x 8192 RGBA16 (within the pixel limit) in a few dozen bytes: 512 MiB of pixels.
  write_bytes(file("huge_rgba16.png"), handmade_png(8192, 8192, 16, 6, {0, 0}));

  // Header attributes declaring 1.6 GB, an unknown type and a string.
  Bytes attribute_bomb;
  append_attribute(attribute_bomb, "x", "opaque", {}, 1600000000u);
  Bytes string_bomb;
  append_attribute(string_bomb, "owner", "string", {}, 1600000000u);
  for (const auto& [name, extra] : {std::pair{"attribute_bomb.exr", attribute_bomb},
                                    std::pair{"string_bomb.exr", string_bomb}}) {
    Bytes exr = handmade_exr_header(1, 1, extra);
    exr.resize(exr.size() + 8, 0);
    write_bytes(file(name), exr);
  }

  // 8192 x 8192 RGBA half, uncompressed: its offset table, 64 KiB, and no pixels.
  Bytes huge_window = handmade_exr_header(8192, 8192);
  huge_window.resize(huge_window.size() + 8 * 8192, 0);
  write_bytes(file("huge_window.exr"), huge_window);

  // 4096 x 4096 RGB float declared, 16 bytes of pixels.
  const std::string pfm_header = "PF\n4096 4096\n-1.0\n";
  Bytes pfm(pfm_header.begin(), pfm_header.end());
  pfm.resize(pfm.size() + 16, 0);
  write_bytes(file("huge.pfm"), pfm);

  for (const char* name : {"text_bomb.png", "huge_rgba16.png", "attribute_bomb.exr",
                           "string_bomb.exr", "huge_window.exr", "huge.pfm"}) {
    EXPECT_EQ(read_error_code(file(name)), ErrorCode::format) << name;
    expect_refused_without_allocating(file(name));
  }
}

TEST_F(ImageIoTest, CompressedImagesWithinTheirFilesStillRead) {
  // A constant 4096 x 256 image compresses far below its size, within the zlib bound: as a PNG,
  // and as a tiled OpenEXR file of half pixels (ZIP; write_image's OpenEXR files are uncompressed).
  write_image(file("flat.png"), ImageF(4096, 256, 3, 0.5f).view());
  write_tiled_exr(file("flat.exr"), Grid{{0.0, 0.0}, 1.0, 4096, 256}, 3, {.half = true},
                  [](const Grid&, ImageView<float> out) {
                    for (int y = 0; y < out.height; ++y)
                      std::fill_n(out.row(y), out.width * out.channels, 0.5f);
                  });
  for (const char* name : {"flat.png", "flat.exr"}) {
    EXPECT_LT(fs::file_size(file(name)), 4096u * 256u * 3u / 100u) << name;
    EXPECT_EQ(read_image(file(name)).width(), 4096) << name;
  }
}

TEST_F(ImageIoTest, PixelLimitIsEnforced) {
  write_image(file("image.png"), ImageF(16, 16, 1, 0.5f).view());
  ImageReadLimits limits;
  limits.max_pixels = 255;
  EXPECT_EQ(read_error_code(file("image.png"), limits), ErrorCode::invalid_input);
  limits.max_pixels = 256;
  EXPECT_EQ(read_image(file("image.png"), limits).width(), 16);
}

TEST_F(ImageIoTest, MissingFileIsAnIoError) {
  EXPECT_EQ(read_error_code(file("absent.png")), ErrorCode::io);
  EXPECT_EQ(read_error_code(folder_), ErrorCode::io);
}

TEST_F(ImageIoTest, WritingIntoAMissingFolderFailsAndLeavesNothing) {
  const fs::path path = folder_ / "missing" / "out.png";
  try {
    write_image(path, ImageF(4, 4, 3, 0.5f).view());
    FAIL() << "writing into a missing folder succeeded";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::io);
    EXPECT_NE(std::string(error.what()).find("out.png"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(folder_ / "missing"));
  EXPECT_TRUE(folder_contents().empty());
}

TEST_F(ImageIoTest, WritingLeavesOnlyTheOutputAndReplacesAnOldOne) {
  for (const char* name : {"out.png", "out.exr", "out.pfm"}) {
    write_image(file(name), ImageF(3, 3, 3, 0.25f).view());
    write_image(file(name), ImageF(5, 2, 1, 1.0f).view());
    const ImageF read = read_image(file(name));
    EXPECT_EQ(read.width(), 5);
    EXPECT_EQ(read.at(4, 1, 0), 1.0f);
  }
  std::vector<std::string> names;
  for (const auto& path : folder_contents()) names.push_back(path.filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"out.exr", "out.pfm", "out.png"}));
}

// The error `decode_image` of `bytes` throws, its message naming the buffer "the upload".
Error decode_error(const Bytes& bytes, const ImageReadLimits& limits = {}) {
  try {
    decode_image(bytes, "the upload", limits);
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("the upload ", 0), 0u)
        << "the message begins with the buffer's name: " << error.what();
    return error;
  }
  ADD_FAILURE() << "decoding did not throw";
  return Error(ErrorCode::numerical, "");
}

TEST_F(ImageIoTest, BuffersHoldTheFilesBytes) {
  const ImageF rgba = make_image(23, 9, 4, [](int x, int y, int c) {
    return static_cast<float>((x * 4099 + y * 1601 + c * 12345) % 65536) / 65535.0f;
  });
  const ImageF rgb = make_image(13, 11, 3, [](int x, int y, int c) {
    return static_cast<float>(x * 100 + y) * 1e-3f - static_cast<float>(c) * 7.5f;
  });
  const ImageF grey = make_image(5, 7, 1, [](int x, int y, int) {
    return std::ldexp(static_cast<float>(x - 2) * 0.3183099f, y - 3);
  });
  struct Case {
    const char* name;
    ImageFormat format;
    const ImageF& image;
    int bit_depth;
  };
  for (const Case& test :
       {Case{"rgba8.png", ImageFormat::png, rgba, 8},
        Case{"rgba16.png", ImageFormat::png, rgba, 16},
        Case{"grey16.png", ImageFormat::png, grey, 16}, Case{"rgba.exr", ImageFormat::exr, rgba, 8},
        Case{"grey.exr", ImageFormat::exr, grey, 8}, Case{"rgb.pfm", ImageFormat::pfm, rgb, 8},
        Case{"grey.pfm", ImageFormat::pfm, grey, 8}}) {
    write_image(file(test.name), test.image.view(), test.bit_depth);
    const Bytes written = test_support::file_bytes(file(test.name));
    const std::vector<std::uint8_t> encoded =
        encode_image(test.image.view(), test.format, test.bit_depth);
    EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), written) << test.name;
    const ImageF decoded = decode_image(written, test.name);
    EXPECT_TRUE(test_support::same_bytes(decoded, read_image(file(test.name)))) << test.name;
  }
  EXPECT_EQ(output_image_format(file("A.PNG")), ImageFormat::png);
  EXPECT_EQ(output_image_format(file("a.Exr")), ImageFormat::exr);
  EXPECT_EQ(output_image_format(file("a.pfm")), ImageFormat::pfm);
}

TEST_F(ImageIoTest, BadBuffersAreRefusedWithASentenceNamingThem) {
  const ImageF image = make_image(32, 32, 3, [](int x, int y, int c) {
    return static_cast<float>((x * 37 + y * 11 + c) % 256) / 255.0f;
  });
  for (const ImageFormat format : {ImageFormat::png, ImageFormat::exr, ImageFormat::pfm}) {
    const std::vector<std::uint8_t> whole = encode_image(image.view(), format);
    const Bytes half(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(whole.size() / 2));
    const Error error = decode_error(half);
    EXPECT_EQ(error.code(), ErrorCode::format) << error.what();
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
  }

  // The same refusals as the files, in the same words but for the name.
  const Bytes huge_png = handmade_png(100000, 100000, 8, 0, {0, 1});
  write_bytes(file("huge.png"), huge_png);
  const std::string pfm_header = "PF\n4096 4096\n-1.0\n";
  const Bytes huge_pfm(pfm_header.begin(), pfm_header.end());
  write_bytes(file("huge.pfm"), huge_pfm);
  for (const auto& [name, bytes] :
       {std::pair{"huge.png", huge_png}, std::pair{"huge.pfm", huge_pfm}}) {
    std::string from_file;
    try {
      read_image(file(name));
    } catch (const Error& error) {
      from_file = error.what();
    }
    const std::string quoted_path = "'" + file(name).string() + "'";
    ASSERT_EQ(from_file.rfind(quoted_path, 0), 0u) << from_file;
    const Error error = decode_error(bytes);
    EXPECT_EQ(std::string(error.what()), "the upload" + from_file.substr(quoted_path.size()));
  }
  EXPECT_EQ(decode_error(huge_png).code(), ErrorCode::invalid_input);
  EXPECT_EQ(decode_error(huge_pfm).code(), ErrorCode::format);

  EXPECT_EQ(std::string(decode_error({}).what()), "the upload is empty (0 bytes), not an image");
  const Error noise = decode_error({'h', 'e', 'l', 'l', 'o'});
  EXPECT_EQ(noise.code(), ErrorCode::format);
  EXPECT_NE(
      std::string(noise.what()).find("not a PNG, OpenEXR, PFM, JPEG, TIFF, WebP or TGA image"),
      std::string::npos)
      << noise.what();
  ImageReadLimits limits;
  limits.max_pixels = 255;
  const std::vector<std::uint8_t> small =
      encode_image(ImageF(16, 16, 1, 0.5f).view(), ImageFormat::png);
  EXPECT_EQ(decode_error(Bytes(small.begin(), small.end()), limits).code(),
            ErrorCode::invalid_input);
  EXPECT_THROW(decode_image(small, ""), std::invalid_argument);
}

TEST_F(ImageIoTest, BadEncodeArgumentsAreRefused) {
  const ImageF image(2, 2, 4, 0.5f);
  EXPECT_THROW(encode_image(image.view(), ImageFormat::png, 12), std::invalid_argument);
  EXPECT_THROW(encode_image(ImageF().view(), ImageFormat::exr), std::invalid_argument);
  try {
    encode_image(image.view(), ImageFormat::pfm);
    FAIL() << "a 4-channel PFM was encoded";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::invalid_input);
    EXPECT_EQ(std::string(error.what()),
              "cannot encode the image as PFM: PFM holds 1 or 3 channels and the image has 4; "
              "write .exr or .png instead");
  }
}

TEST_F(ImageIoTest, BadWriteArgumentsAreInvalidArguments) {
  const ImageF image(2, 2, 3, 0.5f);
  EXPECT_THROW(write_image(file("out.jpg"), image.view()), std::invalid_argument);
  EXPECT_THROW(write_image(file("out.png"), image.view(), 12), std::invalid_argument);
  EXPECT_THROW(write_image(file("out.png"), ImageF().view()), std::invalid_argument);
  EXPECT_TRUE(folder_contents().empty());
}

// ---------------------------------------------------------------------------------------------
// Colour (include/stochtex/io.hpp, docs/design.md §14): the colour chunks honoured on reading with
// an ImageColour, ignored without one, and the colour written for each ColourSpace.

// The chunk types of a PNG, in order.
std::vector<std::string> png_chunk_types(const Bytes& png) {
  std::vector<std::string> types;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = std::uint32_t{png[at]} << 24 | std::uint32_t{png[at + 1]} << 16 |
                                 std::uint32_t{png[at + 2]} << 8 | png[at + 3];
    types.emplace_back(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                       png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    at += 12 + std::size_t{length};
  }
  return types;
}

bool has_chunk(const Bytes& png, const std::string& type) {
  const std::vector<std::string> types = png_chunk_types(png);
  return std::find(types.begin(), types.end(), type) != types.end();
}

// A small image whose samples are exact 8- or 16-bit values, covering dark and light ones.
ImageF stored_values(int width, int height, int channels, unsigned maximum) {
  ImageF image(width, height, channels);
  unsigned k = 0;
  for (float& value : image.pixels()) {
    value =
        static_cast<float>((k * 2654435761u >> 7) % (maximum + 1)) / static_cast<float>(maximum);
    ++k;
  }
  return image;
}

TEST_F(ImageIoTest, DataIsWrittenAsItIsWithNoColourChunk) {
  for (const int bit_depth : {8, 16}) {
    for (int channels = 1; channels <= 4; ++channels) {
      const ImageF image = stored_values(19, 7, channels, bit_depth == 8 ? 255 : 65535);
      const fs::path path = file("data.png");
      write_image(path, image.view(), bit_depth, ColourSpace::data);
      const Bytes written = test_support::file_bytes(path);
      write_image(path, image.view(), bit_depth);
      EXPECT_EQ(test_support::file_bytes(path), written) << "data is the default";
      for (const char* type : {"sRGB", "gAMA", "cHRM", "iCCP", "cICP"})
        EXPECT_FALSE(has_chunk(written, type)) << type;
      expect_identical(image, read_image(path));
    }
  }
}

// What each colour space writes, read back as stored (no ImageColour): the reader plays no part.
TEST_F(ImageIoTest, EachColourSpaceIsWrittenAsItSays) {
  ImageF image(11, 2, 4);
  for (int x = 0; x < 11; ++x)
    for (int y = 0; y < 2; ++y)
      for (int c = 0; c < 4; ++c) image.at(x, y, c) = static_cast<float>(x + 11 * y + c) / 24.0f;
  for (const int bit_depth : {8, 16}) {
    const float step = bit_depth == 8 ? 1.0f / 255.0f : 1.0f / 65535.0f;
    // srgb: the values as data writes them, and the sRGB chunk with gAMA and cHRM beside it.
    const fs::path data = file("data.png");
    const fs::path srgb = file("srgb.png");
    write_image(data, image.view(), bit_depth);
    write_image(srgb, image.view(), bit_depth, ColourSpace::srgb);
    expect_identical(read_image(data), read_image(srgb));
    const std::vector<std::string> chunks = png_chunk_types(test_support::file_bytes(srgb));
    for (const char* type : {"sRGB", "gAMA", "cHRM"})
      EXPECT_NE(std::find(chunks.begin(), chunks.end(), type), chunks.end()) << type;
    // linear: colour channels encoded before they are rounded, alpha as it is.
    const fs::path linear = file("linear.png");
    write_image(linear, image.view(), bit_depth, ColourSpace::linear);
    EXPECT_TRUE(has_chunk(test_support::file_bytes(linear), "sRGB"));
    const ImageF read = read_image(linear);
    for (int x = 0; x < 11; ++x)
      for (int y = 0; y < 2; ++y)
        for (int c = 0; c < 4; ++c) {
          const float value = image.at(x, y, c);
          ASSERT_NEAR(read.at(x, y, c), std::min(c < 3 ? srgb_encode(value) : value, 1.0f),
                      0.5f * step + 1e-6f)
              << bit_depth << "-bit (" << x << ", " << y << ") channel " << c;
        }
  }
  // The float formats hold linear light: srgb values are decoded, alpha as it is; linear and data
  // values are written as they are. The buffer holds the file's bytes.
  for (const auto& [name, format] :
       {std::pair{"out.exr", ImageFormat::exr}, std::pair{"out.pfm", ImageFormat::pfm}}) {
    const ImageF rgb = make_image(
        5, 3, 3, [](int x, int y, int c) { return static_cast<float>(x + 5 * y + 7 * c) / 30.0f; });
    const ImageView<const float> written = format == ImageFormat::exr ? image.view() : rgb.view();
    write_image(file(name), written, 8, ColourSpace::srgb);
    const std::vector<std::uint8_t> encoded = encode_image(written, format, 8, ColourSpace::srgb);
    EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), test_support::file_bytes(file(name))) << name;
    const ImageF read = read_image(file(name));
    for (int y = 0; y < written.height; ++y)
      for (int x = 0; x < written.width; ++x)
        for (int c = 0; c < written.channels; ++c)
          ASSERT_EQ(read.at(x, y, c), is_colour_channel(c, written.channels)
                                          ? srgb_decode(written.at(x, y, c))
                                          : written.at(x, y, c))
              << name << " (" << x << ", " << y << ") channel " << c;
    for (const ColourSpace space : {ColourSpace::linear, ColourSpace::data}) {
      write_image(file(name), written, 8, space);
      const ImageF as_is = read_image(file(name));
      for (int y = 0; y < written.height; ++y)
        for (int x = 0; x < written.width; ++x)
          for (int c = 0; c < written.channels; ++c)
            ASSERT_EQ(as_is.at(x, y, c), written.at(x, y, c)) << name;
    }
  }
}

// Reading: PNGs with colour chunks, made by hand.

struct Chunk {
  std::string type;
  Bytes data;
};

// `png` with `chunks` inserted after its header chunk (IHDR: 25 bytes after the 8-byte signature),
// where colour chunks belong.
Bytes with_chunks(const Bytes& png, const std::vector<Chunk>& chunks) {
  Bytes inserted;
  for (const Chunk& chunk : chunks) append_chunk(inserted, chunk.type, chunk.data);
  Bytes result(png.size() + inserted.size());
  const auto after_header = std::copy(png.begin(), png.begin() + 33, result.begin());
  std::copy(png.begin() + 33, png.end(), std::copy(inserted.begin(), inserted.end(), after_header));
  return result;
}

Chunk gama_chunk(std::uint32_t gamma) {
  Bytes data;
  append_u32_big_endian(data, gamma);
  return {"gAMA", data};
}

Chunk cicp_chunk(int primaries, int transfer, int matrix, int full_range) {
  return {"cICP",
          {static_cast<unsigned char>(primaries), static_cast<unsigned char>(transfer),
           static_cast<unsigned char>(matrix), static_cast<unsigned char>(full_range)}};
}

const Chunk kSrgbChunk = {"sRGB", {0}};

// An iCCP chunk holding `profile`: a name, its terminator, compression method 0 and the profile
// compressed with zlib.
Chunk iccp_chunk(const Bytes& profile) {
  uLongf compressed_bytes = compressBound(static_cast<uLong>(profile.size()));
  Bytes compressed(compressed_bytes);
  EXPECT_EQ(compress2(compressed.data(), &compressed_bytes, profile.data(),
                      static_cast<uLong>(profile.size()), 9),
            Z_OK);
  compressed.resize(compressed_bytes);
  Bytes data = {'i', 'c', 'c', 0, 0};
  data.insert(data.end(), compressed.begin(), compressed.end());
  return {"iCCP", data};
}

// The bytes of a Little CMS profile, closed after.
Bytes saved_profile(cmsHPROFILE profile) {
  cmsUInt32Number size = 0;
  EXPECT_TRUE(cmsSaveProfileToMem(profile, nullptr, &size));
  Bytes bytes(size);
  EXPECT_TRUE(cmsSaveProfileToMem(profile, bytes.data(), &size));
  cmsCloseProfile(profile);
  return bytes;
}

void set_description(cmsHPROFILE profile, const char* description) {
  cmsMLU* text = cmsMLUalloc(nullptr, 1);
  cmsMLUsetASCII(text, "en", "US", description);
  cmsWriteTag(profile, cmsSigProfileDescriptionTag, text);
  cmsMLUfree(text);
}

const cmsCIExyY kD65 = {0.3127, 0.3290, 1.0};

// An RGB profile that is not sRGB: Adobe RGB (1998)'s primaries and a pure 2.2 gamma.
cmsHPROFILE wide_rgb_profile() {
  const cmsCIExyYTRIPLE primaries = {{0.64, 0.33, 1.0}, {0.21, 0.71, 1.0}, {0.15, 0.06, 1.0}};
  cmsToneCurve* gamma = cmsBuildGamma(nullptr, 2.2);
  cmsToneCurve* curves[3] = {gamma, gamma, gamma};
  cmsHPROFILE profile = cmsCreateRGBProfile(&kD65, &primaries, curves);
  cmsFreeToneCurve(gamma);
  set_description(profile, "stochtex test wide RGB");
  return profile;
}

cmsHPROFILE grey_gamma_profile() {
  cmsToneCurve* gamma = cmsBuildGamma(nullptr, 2.2);
  cmsHPROFILE profile = cmsCreateGrayProfile(&kD65, gamma);
  cmsFreeToneCurve(gamma);
  set_description(profile, "stochtex test grey 2.2");
  return profile;
}

cmsHPROFILE srgb_profile() {
  cmsHPROFILE profile = cmsCreate_sRGBProfile();
  set_description(profile, "stochtex test sRGB");
  return profile;
}

// What read_image makes of `png` with an ImageColour, after checking that decode_image of the
// same bytes gives the same image and colour.
ImageF read_colour(const fs::path& path, const Bytes& png, ImageColour& colour) {
  write_bytes(path, png);
  ImageF image = read_image(path, {}, &colour);
  ImageColour from_memory;
  const ImageF decoded = decode_image(png, "the upload", {}, &from_memory);
  EXPECT_TRUE(test_support::same_bytes(decoded, image));
  EXPECT_EQ(from_memory.space, colour.space);
  EXPECT_EQ(from_memory.origin, colour.origin);
  return image;
}

// The message read_image with an ImageColour refuses `png` with (its code checked: format).
std::string colour_refusal(const fs::path& path, const Bytes& png) {
  write_bytes(path, png);
  ImageColour colour;
  try {
    read_image(path, {}, &colour);
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::format) << error.what();
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("'" + path.string() + "' ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.back(), '.') << "one sentence, as every refusal: " << message;
    return message;
  }
  ADD_FAILURE() << "reading " << path << " with its colour did not throw";
  return {};
}

TEST_F(ImageIoTest, SrgbPngRoundTripsAreExactAndSayTheyAreSrgb) {
  for (const int bit_depth : {8, 16}) {
    for (int channels = 1; channels <= 4; ++channels) {
      const std::string context =
          std::to_string(bit_depth) + "-bit, " + std::to_string(channels) + " channels";
      const ImageF image = stored_values(23, 9, channels, bit_depth == 8 ? 255 : 65535);
      const std::vector<std::uint8_t> plain =
          encode_image(image.view(), ImageFormat::png, bit_depth);
      ImageColour colour;
      const ImageF read = read_colour(file("plain.png"), Bytes(plain.begin(), plain.end()), colour);
      EXPECT_EQ(colour.space, ColourSpace::srgb) << context;
      EXPECT_EQ(colour.origin, "no colour chunk: sRGB by default") << context;
      expect_identical(image, read);

      const fs::path path = file("srgb.png");
      write_image(path, read.view(), bit_depth, ColourSpace::srgb);
      const Bytes written = test_support::file_bytes(path);
      const std::vector<std::uint8_t> encoded =
          encode_image(read.view(), ImageFormat::png, bit_depth, ColourSpace::srgb);
      EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), written) << context;
      EXPECT_TRUE(has_chunk(written, "sRGB")) << context;
      ImageColour again;
      expect_identical(image, read_colour(path, written, again));
      EXPECT_EQ(again.space, ColourSpace::srgb) << context;
      EXPECT_EQ(again.origin, "sRGB chunk") << context;
      expect_identical(image, read_image(path));
    }
  }
}

TEST_F(ImageIoTest, LinearPngIsEncodedWithTheSrgbTransferFunction) {
  for (const int bit_depth : {8, 16}) {
    const float maximum = bit_depth == 8 ? 255.0f : 65535.0f;
    for (const int channels : {2, 3, 4}) {
      ImageF linear(37, 3, channels);
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 37; ++x)
          for (int c = 0; c < channels; ++c)
            linear.at(x, y, c) = static_cast<float>(x + 3 * c + y) / 40.0f - 0.05f;
      const fs::path path = file("linear.png");
      write_image(path, linear.view(), bit_depth, ColourSpace::linear);
      ImageColour colour;
      const ImageF read = read_colour(path, test_support::file_bytes(path), colour);
      EXPECT_EQ(colour.space, ColourSpace::srgb);
      EXPECT_EQ(colour.origin, "sRGB chunk");
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 37; ++x)
          for (int c = 0; c < channels; ++c) {
            const float value = linear.at(x, y, c);
            const float expected =
                std::clamp(is_colour_channel(c, channels) ? srgb_encode(value) : value, 0.0f, 1.0f);
            ASSERT_NEAR(read.at(x, y, c), expected, 0.5f / maximum + 1e-6f)
                << bit_depth << "-bit, channel " << c << " of " << channels << ", linear " << value;
          }
    }
  }
}

TEST_F(ImageIoTest, WithoutAnImageColourTheColourChunksAreIgnored) {
  const Bytes rows = {0, 10, 128, 250};
  const Bytes plain = handmade_png(3, 1, 8, 0, rows);
  const Bytes cmyk = [] {
    Bytes profile = saved_profile(srgb_profile());
    std::copy_n("CMYK", 4, profile.begin() + 16);
    return profile;
  }();
  for (const std::vector<Chunk>& chunks :
       {std::vector<Chunk>{gama_chunk(45455)}, std::vector<Chunk>{cicp_chunk(9, 16, 0, 1)},
        std::vector<Chunk>{iccp_chunk(cmyk)},
        std::vector<Chunk>{iccp_chunk(saved_profile(grey_gamma_profile()))}}) {
    const fs::path path = file("chunks.png");
    write_bytes(path, with_chunks(plain, chunks));
    const ImageF image = read_image(path);
    ASSERT_EQ(image.pixels().size(), 3u) << chunks[0].type;
    EXPECT_EQ(image.at(0, 0, 0), 10.0f / 255.0f) << chunks[0].type;
    EXPECT_EQ(image.at(1, 0, 0), 128.0f / 255.0f) << chunks[0].type;
    EXPECT_EQ(image.at(2, 0, 0), 250.0f / 255.0f) << chunks[0].type;
  }
}

TEST_F(ImageIoTest, SrgbAndGamaChunks) {
  // Grey + alpha, 8-bit: 0, 128 and 255 in grey, alpha 128.
  const Bytes png = handmade_png(3, 1, 8, 4, {0, 0, 128, 128, 128, 255, 128});
  ImageColour colour;
  ImageF image = read_colour(file("srgb.png"), with_chunks(png, {kSrgbChunk}), colour);
  EXPECT_EQ(colour.space, ColourSpace::srgb);
  EXPECT_EQ(colour.origin, "sRGB chunk");
  EXPECT_EQ(image.at(1, 0, 0), 128.0f / 255.0f);

  image = read_colour(file("linear.png"), with_chunks(png, {gama_chunk(100000)}), colour);
  EXPECT_EQ(colour.space, ColourSpace::linear);
  EXPECT_EQ(colour.origin, "gAMA 1.0: linear");
  EXPECT_EQ(image.at(1, 0, 0), 128.0f / 255.0f);

  // gAMA 0.45455: decoded light is v^(1/0.45455), encoded again with sRGB's curve; alpha is data.
  image = read_colour(file("gamma.png"), with_chunks(png, {gama_chunk(45455)}), colour);
  EXPECT_EQ(colour.space, ColourSpace::srgb);
  EXPECT_EQ(colour.origin, "gAMA 0.45455, converted to sRGB");
  EXPECT_EQ(image.at(0, 0, 0), 0.0f);
  EXPECT_NEAR(image.at(1, 0, 0), srgb_encode(std::pow(128.0 / 255.0, 1.0 / 0.45455)), 1e-6);
  // Brighter than 128/255 = 0.50196: gamma 2.2 gives 0.2195 of light, sRGB's curve 0.2158.
  EXPECT_NEAR(image.at(1, 0, 0), 0.5059f, 1e-3f);
  EXPECT_NEAR(image.at(2, 0, 0), 1.0f, 1e-6f);
  for (int x = 0; x < 3; ++x) EXPECT_EQ(image.at(x, 0, 1), 128.0f / 255.0f);

  // 16-bit RGB: every sample is converted, through the same curve.
  Bytes rows16 = {0};
  for (const unsigned value : {0u, 1000u, 32768u}) {
    rows16.push_back(static_cast<unsigned char>(value >> 8));
    rows16.push_back(static_cast<unsigned char>(value & 0xff));
  }
  image = read_colour(file("gamma16.png"),
                      with_chunks(handmade_png(1, 1, 16, 2, rows16), {gama_chunk(50000)}), colour);
  EXPECT_EQ(colour.origin, "gAMA 0.5, converted to sRGB");
  EXPECT_EQ(image.at(0, 0, 0), 0.0f);
  EXPECT_NEAR(image.at(0, 0, 1), srgb_encode(std::pow(1000.0 / 65535.0, 2.0)), 1e-7);
  EXPECT_NEAR(image.at(0, 0, 2), srgb_encode(std::pow(32768.0 / 65535.0, 2.0)), 1e-6);

  // sRGB comes before gAMA whatever their order in the file.
  read_colour(file("both.png"), with_chunks(png, {gama_chunk(100000), kSrgbChunk}), colour);
  EXPECT_EQ(colour.origin, "sRGB chunk");

  // A gamma of 0 and a chunk of the wrong length are corrupt.
  const std::string zero = colour_refusal(file("zero.png"), with_chunks(png, {gama_chunk(0)}));
  EXPECT_NE(zero.find("gAMA"), std::string::npos) << zero;
  EXPECT_NE(zero.find("corrupt"), std::string::npos) << zero;
  const std::string long_srgb =
      colour_refusal(file("long.png"), with_chunks(png, {{"sRGB", {0, 0}}}));
  EXPECT_NE(long_srgb.find("an sRGB chunk of 2 bytes (1 expected)"), std::string::npos)
      << long_srgb;
}

TEST_F(ImageIoTest, CicpChunks) {
  const Bytes png = handmade_png(2, 1, 8, 2, {0, 10, 128, 250, 255, 0, 64});
  ImageColour colour;
  ImageF image = read_colour(file("srgb.png"), with_chunks(png, {cicp_chunk(1, 13, 0, 1)}), colour);
  EXPECT_EQ(colour.space, ColourSpace::srgb);
  EXPECT_EQ(colour.origin, "cICP: sRGB");
  EXPECT_EQ(image.at(0, 0, 1), 128.0f / 255.0f);

  // cICP comes before iCCP, sRGB and gAMA.
  image = read_colour(file("linear.png"),
                      with_chunks(png, {kSrgbChunk, iccp_chunk(saved_profile(wide_rgb_profile())),
                                        cicp_chunk(1, 8, 0, 1), gama_chunk(45455)}),
                      colour);
  EXPECT_EQ(colour.space, ColourSpace::linear);
  EXPECT_EQ(colour.origin, "cICP: linear");
  EXPECT_EQ(image.at(0, 0, 1), 128.0f / 255.0f);

  const fs::path pq = file("pq.png");
  EXPECT_EQ(colour_refusal(pq, with_chunks(png, {cicp_chunk(9, 16, 0, 1)})),
            "'" + pq.string() +
                "' declares HDR PQ colour (cICP transfer 16), which stochtex does not read; "
                "convert it to sRGB or save it as OpenEXR");
  const std::string p3 =
      colour_refusal(file("p3.png"), with_chunks(png, {cicp_chunk(12, 13, 0, 1)}));
  EXPECT_NE(p3.find("Display P3 primaries (cICP primaries 12)"), std::string::npos) << p3;
  const std::string video =
      colour_refusal(file("video.png"), with_chunks(png, {cicp_chunk(1, 13, 0, 0)}));
  EXPECT_NE(video.find("(cICP full range flag 0)"), std::string::npos) << video;
  const std::string bt709 =
      colour_refusal(file("bt709.png"), with_chunks(png, {cicp_chunk(1, 1, 0, 1)}));
  EXPECT_NE(bt709.find("(cICP transfer 1)"), std::string::npos) << bt709;
  const std::string short_chunk =
      colour_refusal(file("short.png"), with_chunks(png, {{"cICP", {1, 13, 0}}}));
  EXPECT_NE(short_chunk.find("a cICP chunk of 3 bytes (4 expected)"), std::string::npos)
      << short_chunk;

  // A damaged checksum: libpng drops the chunk, which refuses the file rather than reading the
  // values in a colour it does not have.
  Bytes damaged = with_chunks(png, {cicp_chunk(1, 8, 0, 1)});
  damaged[33 + 12 + 3] ^= 0xff;  // the chunk's last checksum byte (length, type, 4 data bytes)
  const std::string crc = colour_refusal(file("crc.png"), damaged);
  EXPECT_NE(crc.find("a cICP chunk that cannot be read (CRC error)"), std::string::npos) << crc;
  EXPECT_NE(crc.find("export it again"), std::string::npos) << crc;
  EXPECT_NO_THROW(read_image(file("crc.png")));
}

TEST_F(ImageIoTest, IccpWithAnSrgbProfileLeavesTheValues) {
  const Bytes png = handmade_png(2, 1, 8, 6, {0, 10, 128, 250, 77, 255, 0, 64, 1});
  ImageColour colour;
  const ImageF image = read_colour(
      file("srgb.png"), with_chunks(png, {iccp_chunk(saved_profile(srgb_profile()))}), colour);
  EXPECT_EQ(colour.space, ColourSpace::srgb);
  EXPECT_EQ(colour.origin, "ICC profile 'stochtex test sRGB': sRGB");
  expect_identical(read_image(file("srgb.png")), image);

  // A grey profile with sRGB's tone curve, on a grey image.
  const cmsFloat64Number srgb_curve[5] = {2.4, 1.0 / 1.055, 0.055 / 1.055, 1.0 / 12.92, 0.04045};
  cmsToneCurve* curve = cmsBuildParametricToneCurve(nullptr, 4, srgb_curve);
  cmsHPROFILE grey = cmsCreateGrayProfile(&kD65, curve);
  cmsFreeToneCurve(curve);
  set_description(grey, "grey sRGB curve");
  const Bytes grey_png =
      with_chunks(handmade_png(3, 1, 8, 0, {0, 10, 128, 250}), {iccp_chunk(saved_profile(grey))});
  const ImageF grey_image = read_colour(file("grey.png"), grey_png, colour);
  EXPECT_EQ(colour.origin, "ICC profile 'grey sRGB curve': sRGB");
  expect_identical(read_image(file("grey.png")), grey_image);
}

TEST_F(ImageIoTest, IccpWithAnotherProfileIsConvertedToSrgb) {
  // RGBA, 8-bit: saturated primaries, white, a mid grey and a dark colour; alpha 0, 77, 128...
  const Bytes rows = {0,   255, 0,   0,   0,   0,   255, 0,   77, 0,  0,  255, 128,
                      255, 255, 255, 200, 128, 128, 128, 255, 20, 60, 90, 3};
  const Bytes png = with_chunks(handmade_png(6, 1, 8, 6, rows),
                                {iccp_chunk(saved_profile(wide_rgb_profile())), kSrgbChunk});
  ImageColour colour;
  const ImageF image = read_colour(file("wide.png"), png, colour);
  EXPECT_EQ(colour.space, ColourSpace::srgb);
  EXPECT_EQ(colour.origin, "ICC profile 'stochtex test wide RGB', converted to sRGB");
  const ImageF stored = read_image(file("wide.png"));

  // Against Little CMS's own transform of the same values, from the profile the file holds (its
  // colorants rounded to 1/65536 when it was saved).
  const Bytes wide_bytes = saved_profile(wide_rgb_profile());
  cmsHPROFILE wide =
      cmsOpenProfileFromMem(wide_bytes.data(), static_cast<cmsUInt32Number>(wide_bytes.size()));
  cmsHPROFILE srgb = cmsCreate_sRGBProfile();
  cmsHTRANSFORM transform =
      cmsCreateTransform(wide, TYPE_RGBA_FLT, srgb, TYPE_RGBA_FLT, INTENT_RELATIVE_COLORIMETRIC, 0);
  ImageF expected = stored;
  cmsDoTransform(transform, expected.pixels().data(), expected.pixels().data(), 6);
  cmsDeleteTransform(transform);
  cmsCloseProfile(srgb);
  cmsCloseProfile(wide);
  for (int x = 0; x < 6; ++x) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(image.at(x, 0, c), expected.at(x, 0, c), 1e-6f) << x << " " << c;
    EXPECT_EQ(image.at(x, 0, 3), stored.at(x, 0, 3)) << "alpha is data, left as it is";
  }
  // Known values. Adobe RGB's red has sRGB's chromaticity and more light (Y 0.297 against
  // 0.213): red only, above 1. Its green is beyond sRGB's gamut: in sRGB's linear light it is
  // (-0.398, 1, -0.043), whose negative light the extended sRGB curve encodes (core/srgb.hpp):
  // nothing is clamped. White stays white; a grey of the same white point stays grey, its light
  // 0.5^2.2 encoded with sRGB's curve.
  EXPECT_GT(image.at(0, 0, 0), 1.1f);
  EXPECT_NEAR(image.at(0, 0, 1), 0.0f, 1e-3f);
  EXPECT_NEAR(image.at(0, 0, 2), 0.0f, 1e-3f);
  EXPECT_NEAR(image.at(1, 0, 0), srgb_encode(-0.398f), 0.01f);
  EXPECT_NEAR(image.at(1, 0, 1), 1.0f, 1e-3f);
  EXPECT_NEAR(image.at(1, 0, 2), srgb_encode(-0.043f), 0.01f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(image.at(3, 0, c), 1.0f, 1e-3f);
    EXPECT_NEAR(image.at(4, 0, c), srgb_encode(std::pow(128.0 / 255.0, 2.2)), 2e-3);
  }
  // The dark blue-grey (20, 60, 90) loses its red to the wider primaries.
  EXPECT_LT(image.at(5, 0, 0), -0.1f);

  // iCCP comes before sRGB whatever their order in the file.
  read_colour(file("srgb_first.png"),
              with_chunks(handmade_png(6, 1, 8, 6, rows),
                          {kSrgbChunk, iccp_chunk(saved_profile(wide_rgb_profile()))}),
              colour);
  EXPECT_EQ(colour.origin, "ICC profile 'stochtex test wide RGB', converted to sRGB");

  // A grey image with a grey gamma 2.2 profile: to grey with sRGB's tone curve.
  const Bytes grey_png = with_chunks(handmade_png(3, 1, 16, 0, {0, 0, 0, 128, 0, 255, 255}),
                                     {iccp_chunk(saved_profile(grey_gamma_profile()))});
  const ImageF grey = read_colour(file("grey.png"), grey_png, colour);
  EXPECT_EQ(colour.origin, "ICC profile 'stochtex test grey 2.2', converted to sRGB");
  EXPECT_NEAR(grey.at(0, 0, 0), 0.0f, 1e-4f);
  EXPECT_NEAR(grey.at(1, 0, 0), srgb_encode(std::pow(32768.0 / 65535.0, 2.2)), 1e-3);
  EXPECT_NEAR(grey.at(2, 0, 0), 1.0f, 1e-4f);
}

TEST_F(ImageIoTest, IccProfilesThatCannotBeUsedAreRefused) {
  const Bytes rgb = handmade_png(1, 1, 8, 2, {0, 10, 128, 250});
  const auto expect_refused = [&](const std::string& name, const Bytes& png,
                                  const std::string& reason) {
    const std::string message = colour_refusal(file(name), png);
    EXPECT_NE(message.find(" carries an ICC profile stochtex cannot use ("), std::string::npos)
        << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
    EXPECT_TRUE(message.ends_with("); convert the image to sRGB")) << message;
    EXPECT_NO_THROW(read_image(file(name))) << "without an ImageColour, the values as stored";
  };
  Bytes cmyk = saved_profile(wide_rgb_profile());
  std::copy_n("CMYK", 4, cmyk.begin() + 16);
  expect_refused("cmyk.png", with_chunks(rgb, {iccp_chunk(cmyk)}), "'CMYK'");
  // A profile of the wrong kind (exemplars of ours had one: sand_height_grey_512.png) is ignored,
  // as browsers do, and the values read as sRGB.
  const Bytes rgb_on_grey = with_chunks(handmade_png(1, 1, 8, 0, {0, 10}),
                                        {iccp_chunk(saved_profile(wide_rgb_profile()))});
  ImageColour ignored;
  const ImageF grey = read_colour(file("rgb_on_grey.png"), rgb_on_grey, ignored);
  EXPECT_EQ(ignored.space, ColourSpace::srgb);
  EXPECT_EQ(ignored.origin, "an RGB ICC profile on a grey image, ignored: sRGB by default");
  EXPECT_EQ(grey.at(0, 0, 0), 10.0f / 255.0f);
  // Tag data Little CMS cannot read: each tag's type signature replaced.
  Bytes damaged = saved_profile(wide_rgb_profile());
  const std::uint32_t tags = std::uint32_t{damaged[128]} << 24 | std::uint32_t{damaged[129]} << 16 |
                             std::uint32_t{damaged[130]} << 8 | damaged[131];
  for (std::uint32_t tag = 0; tag < tags; ++tag) {
    const std::size_t entry = 132 + 12 * tag;
    const std::size_t offset = std::size_t{damaged[entry + 4]} << 24 |
                               std::size_t{damaged[entry + 5]} << 16 |
                               std::size_t{damaged[entry + 6]} << 8 | damaged[entry + 7];
    std::copy_n("junk", 4, damaged.begin() + static_cast<std::ptrdiff_t>(offset));
  }
  expect_refused("damaged.png", with_chunks(rgb, {iccp_chunk(damaged)}), "Little CMS");
  // A profile whose compressed data is cut short.
  Chunk cut = iccp_chunk(saved_profile(wide_rgb_profile()));
  cut.data.resize(cut.data.size() / 2);
  expect_refused("cut.png", with_chunks(rgb, {cut}), "zlib");
}

TEST_F(ImageIoTest, FloatFormatsAreLinearAndGetSrgbImagesDecoded) {
  ImageF srgb(5, 2, 4);
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 2; ++y)
      for (int c = 0; c < 4; ++c) srgb.at(x, y, c) = static_cast<float>(x + 5 * y + c) / 12.0f;
  const fs::path exr = file("srgb.exr");
  write_image(exr, srgb.view(), 8, ColourSpace::srgb);
  const Bytes written = test_support::file_bytes(exr);
  const std::vector<std::uint8_t> encoded =
      encode_image(srgb.view(), ImageFormat::exr, 8, ColourSpace::srgb);
  EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), written);
  ImageColour colour;
  const ImageF linear = read_colour(exr, written, colour);
  EXPECT_EQ(colour.space, ColourSpace::linear);
  EXPECT_EQ(colour.origin, "OpenEXR: linear");
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 2; ++y) {
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(linear.at(x, y, c), srgb_decode(srgb.at(x, y, c))) << x << "," << y;
      EXPECT_EQ(linear.at(x, y, 3), srgb.at(x, y, 3)) << "alpha is data";
    }
  // Linear and data images are written as they are.
  for (const ColourSpace space : {ColourSpace::linear, ColourSpace::data}) {
    write_image(exr, srgb.view(), 8, space);
    expect_identical(srgb, read_image(exr, {}, &colour));
    EXPECT_EQ(colour.space, ColourSpace::linear);
  }

  const ImageF rgb = stored_values(4, 3, 3, 255);
  const fs::path pfm = file("srgb.pfm");
  write_image(pfm, rgb.view(), 8, ColourSpace::srgb);
  const ImageF pfm_linear = read_colour(pfm, test_support::file_bytes(pfm), colour);
  EXPECT_EQ(colour.space, ColourSpace::linear);
  EXPECT_EQ(colour.origin, "PFM: linear");
  for (std::size_t i = 0; i < rgb.pixels().size(); ++i)
    EXPECT_EQ(pfm_linear.pixels()[i], srgb_decode(rgb.pixels()[i]));
  write_image(pfm, rgb.view(), 8, ColourSpace::linear);
  expect_identical(rgb, read_image(pfm));
}

}  // namespace
}  // namespace stochtex::image_io_test
