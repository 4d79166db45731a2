// Image files: exact round trips, format detection by content, one clear error for every bad file
// (docs/design.md §6 and §9), and the colour written (§14).

#include "io/image_io.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/srgb.hpp"
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

Bytes read_bytes(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
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
    const Bytes whole = read_bytes(file(name));
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
  Bytes exr = read_bytes(file("small.exr"));
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
  const Bytes bytes = from_memory ? read_bytes(path) : Bytes();
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
  // A constant 4096 x 256 image compresses far below its size, within the zlib bound.
  for (const char* name : {"flat.png", "flat.exr"}) {
    write_image(file(name), ImageF(4096, 256, 3, 0.5f).view());
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
    const Bytes written = read_bytes(file(test.name));
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
  EXPECT_NE(std::string(noise.what()).find("not a PNG, OpenEXR or PFM image"), std::string::npos)
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
// Colour (include/stochtex/io.hpp, docs/design.md §14): the colour written for each ColourSpace.

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
      const Bytes written = read_bytes(path);
      write_image(path, image.view(), bit_depth);
      EXPECT_EQ(read_bytes(path), written) << "data is the default";
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
    const std::vector<std::string> chunks = png_chunk_types(read_bytes(srgb));
    for (const char* type : {"sRGB", "gAMA", "cHRM"})
      EXPECT_NE(std::find(chunks.begin(), chunks.end(), type), chunks.end()) << type;
    // linear: colour channels encoded before they are rounded, alpha as it is.
    const fs::path linear = file("linear.png");
    write_image(linear, image.view(), bit_depth, ColourSpace::linear);
    EXPECT_TRUE(has_chunk(read_bytes(linear), "sRGB"));
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
    EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), read_bytes(file(name))) << name;
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

}  // namespace
}  // namespace stochtex::image_io_test
