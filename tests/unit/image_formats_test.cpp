// The formats read but not written (issue 37): JPEG, TIFF, WebP and TGA read as their libraries
// write them, their colour (ICC profiles, floats linear), a JPEG's EXIF orientation, and one clear
// error for bad files, before anything proportional to a declared size is allocated; then the
// region of a photo a method analyses (io/exemplar_region.hpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/srgb.hpp"
#include "image_files.hpp"
#include "io/exemplar_region.hpp"
#include "io/image_io.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "test_support.hpp"

namespace stochtex::image_formats_test {
namespace {

namespace fs = std::filesystem;
using test_support::FileBytes;
using ImageFormatsTest = test_support::FolderTest;

// Values on the 8-bit grid (so that 8-bit formats hold them exactly), seeded.
ImageF grid_image(int width, int height, int channels, std::uint32_t seed = 7) {
  ImageF image(width, height, channels);
  std::mt19937 random(seed);
  for (float& value : image.pixels()) value = static_cast<float>(random() % 256) / 255.0f;
  return image;
}

float max_difference(const ImageF& a, const ImageF& b) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  EXPECT_EQ(a.channels(), b.channels());
  if (a.pixels().size() != b.pixels().size()) return INFINITY;
  float largest = 0.0f;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    largest = std::max(largest, std::abs(a.pixels()[i] - b.pixels()[i]));
  return largest;
}

// The image and colour of `bytes`, read from a file and from memory alike.
ImageF read_bytes(const fs::path& path, const FileBytes& bytes, ImageColour* colour = nullptr) {
  {
    std::ofstream stream(path, std::ios::binary | std::ios::trunc);
    stream.write(reinterpret_cast<const char*>(bytes.data()),
                 static_cast<std::streamsize>(bytes.size()));
  }
  ImageF image = read_image(path, {}, colour);
  ImageColour memory_colour;
  const ImageF from_memory =
      decode_image(bytes, "the upload", {}, colour ? &memory_colour : nullptr);
  EXPECT_TRUE(test_support::same_bytes(image, from_memory)) << path;
  if (colour) {
    EXPECT_EQ(memory_colour.origin, colour->origin);
  }
  return image;
}

// The one-sentence error reading `bytes` gives, with its code; the message names the file.
Error read_error(const fs::path& path, const FileBytes& bytes) {
  try {
    read_bytes(path, bytes);
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path.filename().string()), std::string::npos)
        << error.what();
    return error;
  }
  ADD_FAILURE() << "reading " << path << " did not throw";
  return Error(ErrorCode::numerical, "");
}

TEST_F(ImageFormatsTest, LosslessFormatsReadExactly) {
  for (int channels : {1, 2, 3, 4}) {
    const ImageF image = grid_image(37, 21, channels);
    SCOPED_TRACE(channels);
    for (bool tiled : {false, true})
      for (int compression : {COMPRESSION_NONE, COMPRESSION_LZW, COMPRESSION_ADOBE_DEFLATE})
        EXPECT_EQ(max_difference(
                      image, read_bytes(file("a.tif"),
                                        test_support::tiff_file(
                                            image, folder_,
                                            {.bits = 8,
                                             .compression = static_cast<std::uint16_t>(compression),
                                             .tiled = tiled}))),
                  0.0f);
    if (channels != 2) {  // TGA has no grey and alpha
      for (bool run_length : {false, true})
        EXPECT_EQ(max_difference(
                      image, read_bytes(file("a.tga"), test_support::tga_file(image, run_length))),
                  0.0f);
    }
    if (channels >= 3) {  // WebP is colour
      EXPECT_EQ(
          max_difference(image, read_bytes(file("a.webp"), test_support::webp_file(image, true))),
          0.0f);
    }
  }
  // 16-bit TIFF on its own grid, and floats as they are, negative and above 1 included.
  ImageF sixteen(9, 5, 3);
  ImageF floats(9, 5, 3);
  for (std::size_t i = 0; i < sixteen.pixels().size(); ++i) {
    sixteen.pixels()[i] = static_cast<float>((i * 7919) % 65536) / 65535.0f;
    floats.pixels()[i] = static_cast<float>(i) * 0.37f - 2.0f;
  }
  EXPECT_EQ(
      max_difference(sixteen, read_bytes(file("16.tif"),
                                         test_support::tiff_file(sixteen, folder_, {.bits = 16}))),
      0.0f);
  ImageColour colour;
  EXPECT_EQ(max_difference(floats, read_bytes(file("f.tif"),
                                              test_support::tiff_file(floats, folder_,
                                                                      {.bits = 32, .tiled = true}),
                                              &colour)),
            0.0f);
  EXPECT_EQ(colour.space, ColourSpace::linear);
  EXPECT_EQ(colour.origin, "TIFF floats: linear");
}

TEST_F(ImageFormatsTest, JpegReadsWithinItsQuantisation) {
  // A smooth image: at quality 100 baseline and progressive JPEG hold it within a few levels.
  for (int channels : {1, 3}) {
    ImageF image(64, 48, channels);
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < channels; ++c)
          image.at(x, y, c) =
              std::round(255.0f *
                         (0.5f + 0.4f * std::sin(0.1f * float(x) + 0.07f * float(y) + float(c)))) /
              255.0f;
    for (bool progressive : {false, true}) {
      ImageColour colour;
      const ImageF read = read_bytes(
          file("a.jpg"), test_support::jpeg_file(image, {.progressive = progressive}), &colour);
      EXPECT_LE(max_difference(image, read), 4.0f / 255.0f) << channels << progressive;
      EXPECT_EQ(colour.space, ColourSpace::srgb);
      EXPECT_EQ(colour.origin, "JPEG: sRGB by default");
    }
  }
}

TEST_F(ImageFormatsTest, JpegExifOrientationIsApplied) {
  // Flat 8x8 blocks of distinct greys survive JPEG: each orientation must put the stored first
  // row and column where the tag says (TIFF 6.0, Orientation).
  constexpr int kW = 3, kH = 2;
  ImageF stored(8 * kW, 8 * kH, 1);
  const auto level = [](int bx, int by) {
    return static_cast<float>(40 + 60 * by + 20 * bx) / 255.0f;
  };
  for (int y = 0; y < 8 * kH; ++y)
    for (int x = 0; x < 8 * kW; ++x) stored.at(x, y, 0) = level(x / 8, y / 8);
  for (int orientation = 1; orientation <= 8; ++orientation) {
    SCOPED_TRACE(orientation);
    const ImageF read =
        read_bytes(file("o.jpg"), test_support::jpeg_file(stored, {.orientation = orientation}));
    const bool transposed = orientation >= 5;
    ASSERT_EQ(read.width(), 8 * (transposed ? kH : kW));
    ASSERT_EQ(read.height(), 8 * (transposed ? kW : kH));
    // Where the stored block (bx, by) is shown.
    for (int by = 0; by < kH; ++by)
      for (int bx = 0; bx < kW; ++bx) {
        const int mx = kW - 1 - bx, my = kH - 1 - by;
        int x = bx, y = by;
        switch (orientation) {
          case 2:
            x = mx;
            break;
          case 3:
            x = mx, y = my;
            break;
          case 4:
            y = my;
            break;
          case 5:
            x = by, y = bx;
            break;
          case 6:
            x = my, y = bx;
            break;
          case 7:
            x = my, y = mx;
            break;
          case 8:
            x = by, y = mx;
            break;
        }
        EXPECT_NEAR(read.at(8 * x + 4, 8 * y + 4, 0), level(bx, by), 1.5f / 255.0f)
            << "block " << bx << "," << by;
      }
  }
}

TEST_F(ImageFormatsTest, EmbeddedProfilesAreConvertedToSrgb) {
  const ImageF image = grid_image(16, 16, 3);
  const FileBytes icc = test_support::wide_rgb_icc();
  // The same conversion as a PNG's: a saturated green moves, and every format says why.
  const std::vector<std::pair<std::string, FileBytes>> files = {
      {"p.jpg", test_support::jpeg_file(image, {.icc = icc})},
      {"p.tif", test_support::tiff_file(image, folder_, {.icc = icc})},
      {"p.webp", test_support::webp_file(image, true, icc)},
  };
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    ImageColour colour;
    const ImageF converted = read_bytes(file(name), bytes, &colour);
    EXPECT_EQ(colour.space, ColourSpace::srgb);
    EXPECT_TRUE(colour.origin.ends_with(", converted to sRGB")) << colour.origin;
    EXPECT_GT(max_difference(read_bytes(file(name), bytes), converted), 0.02f);
  }
}

TEST_F(ImageFormatsTest, BadFilesAreRefusedInOneSentence) {
  const ImageF image = grid_image(40, 30, 3);
  const std::vector<std::pair<std::string, FileBytes>> good = {
      {"t.jpg", test_support::jpeg_file(image)},
      {"t.tif", test_support::tiff_file(image, folder_)},
      {"t.webp", test_support::webp_file(image, false)},
      {"t.tga", test_support::tga_file(image, false)},
  };
  for (const auto& [name, bytes] : good) {
    SCOPED_TRACE(name);
    // Cut in half: a format error, never a crash or an image half black.
    FileBytes cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
    EXPECT_EQ(read_error(file(name), cut).code(), ErrorCode::format);
  }
  // A file far larger than its image can take is refused before it is read whole.
  FileBytes padded = test_support::tga_file(grid_image(2, 2, 3), false);
  padded.resize(padded.size() + (std::size_t{2} << 20));
  const std::string large = read_error(file("padded.tga"), padded).what();
  EXPECT_NE(large.find("more than its format can hold"), std::string::npos) << large;
  // A CMYK JPEG says what it is and what to do.
  ImageF four = grid_image(16, 8, 4);
  const std::string cmyk =
      read_error(file("cmyk.jpg"), test_support::jpeg_file(four, {.cmyk = true})).what();
  EXPECT_NE(cmyk.find("(CMYK)"), std::string::npos) << cmyk;
  EXPECT_TRUE(cmyk.ends_with("convert it to RGB or grey")) << cmyk;
}

TEST_F(ImageFormatsTest, TinyFilesDeclaringHugeImagesAreRefusedBeforeAllocating) {
  const ImageF image = grid_image(16, 16, 3);
  // JPEG: the frame header's height and width (after SOF0's length and precision).
  FileBytes jpeg = test_support::jpeg_file(image);
  const std::array<unsigned char, 2> frame_marker = {0xff, 0xc0};
  const auto sof = std::search(jpeg.begin(), jpeg.end(), frame_marker.begin(), frame_marker.end());
  ASSERT_NE(sof, jpeg.end());
  // 8000 x 8000: within the pixel limit, far beyond what the file's bytes can code.
  const std::array<unsigned char, 4> jpeg_size = {0x1f, 0x40, 0x1f, 0x40};
  std::copy(jpeg_size.begin(), jpeg_size.end(), sof + 5);
  // TGA: the header's width and height.
  FileBytes tga = test_support::tga_file(image, true);
  const std::array<unsigned char, 4> tga_size = {0x40, 0x1f, 0x40, 0x1f};
  std::copy(tga_size.begin(), tga_size.end(), tga.begin() + 12);
  for (const auto& [name, bytes] : {std::pair{"huge.jpg", jpeg}, std::pair{"huge.tga", tga}}) {
    SCOPED_TRACE(name);
    const std::string message = read_error(file(name), bytes).what();
    EXPECT_NE(message.find("but the file has"), std::string::npos) << message;
  }
  // A declared size within the file's but beyond the caller's budget is refused by the caller.
  ImageReadLimits limits;
  limits.check_declared = [](int, int, int) { throw Error(ErrorCode::invalid_input, "budget"); };
  const FileBytes tiff = test_support::tiff_file(image, folder_);
  for (const auto& bytes :
       {test_support::jpeg_file(image), tiff, test_support::webp_file(image, true),
        test_support::tga_file(image, false)})
    EXPECT_THROW(decode_image(bytes, "the upload", limits), Error);
}

TEST_F(ImageFormatsTest, RegionsAreCroppedAndDownscaledInLinearLight) {
  // A checker of sRGB black and white: downscaled 4x, each pixel is half the light, which sRGB
  // encodes as 0.7354, not 0.5 (the Mitchell filter passes 1.8% of the checker's frequency: 0.7292
  // measured).
  ImageF checker(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) checker.at(x, y, c) = static_cast<float>((x + y) % 2);
  std::string note;
  const ImageF quarter = exemplar_region(checker, ColourSpace::srgb, {.scale = 0.25}, 1024,
                                         "'c.png'", "tiling", &note);
  EXPECT_EQ(quarter.width(), 16);
  EXPECT_EQ(quarter.height(), 8);
  EXPECT_TRUE(note.empty()) << "the user chose the scale";
  for (float value : quarter.pixels()) EXPECT_NEAR(value, srgb_encode(0.5f), 0.01f);
  const ImageF data = exemplar_region(checker, ColourSpace::data, {.scale = 0.25}, 1024, "'c.png'",
                                      "tiling", nullptr);
  for (float value : data.pixels()) EXPECT_NEAR(value, 0.5f, 0.02f);

  // By default an image longer than the method's side is scaled to it, and the note says so.
  const ImageF fitted =
      exemplar_region(checker, ColourSpace::srgb, {}, 16, "'c.png'", "gabor", &note);
  EXPECT_EQ(fitted.width(), 16);
  EXPECT_EQ(fitted.height(), 8);
  EXPECT_EQ(note,
            "'c.png' is 64x32 pixels, more than gabor analyses by default (16 on the longer "
            "side): it is analysed downscaled to 16x8 (a factor of 0.25)");
  // A crop is the pixels it names; within the side, nothing else happens.
  const ImageF image = grid_image(20, 10, 2);
  const ImageF crop = exemplar_region(image, ColourSpace::srgb, {.crop = Crop{5, 4, 3, 6}}, 1024,
                                      "'i.png'", "tiling", &note);
  ASSERT_EQ(crop.width(), 5);
  ASSERT_EQ(crop.height(), 4);
  EXPECT_TRUE(note.empty());
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 2; ++c) EXPECT_EQ(crop.at(x, y, c), image.at(x + 3, y + 6, c));

  EXPECT_EQ(parse_crop("512x256+100+40", "--crop").x, 100);
  EXPECT_EQ(parse_crop("512x256", "--crop").height, 256);
  for (const char* bad : {"512", "0x5+1+1", "5x5+1", "-5x5", "5x5+1+1 "})
    EXPECT_THROW(parse_crop(bad, "--crop"), std::invalid_argument) << bad;
  EXPECT_THROW(region_size(20, 10, {.crop = Crop{5, 5, 16, 0}}, 1024, "'i.png'"),
               std::invalid_argument);
  EXPECT_THROW(region_size(20, 10, {.scale = 1.5}, 1024, "'i.png'"), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::image_formats_test
