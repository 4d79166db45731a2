// Tiled, mip-mapped OpenEXR files written strip by strip (io/tiled_exr.hpp): every level, read
// back with OpenEXR, is bit for bit the plain render of its grid (the same origin at scale * 2^k),
// and read_image reads level 0 of a tiled file.

#include "io/tiled_exr.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfTiledInputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::tiled_exr_test {
namespace {

using TiledExrTest = test_support::FolderTest;

const Model& test_model() {
  static const Model model = test_support::white_noise_model("tiling");
  return model;
}

ImageF plain_render(const Grid& grid) {
  ImageF out(grid.width, grid.height, test_model().channels());
  RenderOptions options;
  options.threads = 2;
  render(test_model(), grid, 5, out.view(), options);
  return out;
}

void write_file(const std::filesystem::path& path, const Grid& grid,
                const TiledExrOptions& options) {
  write_tiled_exr(path, grid, test_model().channels(), options,
                  [](const Grid& strip, ImageView<float> out) {
                    RenderOptions render_options;
                    render_options.threads = 2;
                    render_options.tile_size = 16;
                    render(test_model(), strip, 5, out, render_options);
                  });
}

ImageF read_level(Imf::TiledInputFile& file, int level) {
  const Imath::Box2i window = file.dataWindowForLevel(level);
  const int width = window.max.x - window.min.x + 1;
  const int height = window.max.y - window.min.y + 1;
  ImageF image(width, height, 3);
  Imf::FrameBuffer frame_buffer;
  const char* names[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c)
    frame_buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels().data() + c, window,
                                                   sizeof(float) * 3, sizeof(float) * 3 * width));
  file.setFrameBuffer(frame_buffer);
  file.readTiles(0, file.numXTiles(level) - 1, 0, file.numYTiles(level) - 1, level);
  return image;
}

TEST_F(TiledExrTest, EveryMipLevelIsThePlainRenderAtItsScale) {
  // Not a multiple of the tile side, and a height that reaches 1 before the width does.
  const Grid grid{{-20.5, 7.25}, 1.5, 150, 70};
  const std::vector<Grid> levels = tiled_exr_levels(grid, true);
  ASSERT_EQ(levels.size(), 8u);  // 150 x 70 down to 1 x 1
  EXPECT_EQ(levels[2].width, 37);
  EXPECT_EQ(levels[2].height, 17);
  EXPECT_EQ(levels[7].width, 1);
  EXPECT_EQ(levels[7].height, 1);
  EXPECT_EQ(tiled_exr_pixels(grid, true),
            150u * 70 + 75 * 35 + 37 * 17 + 18 * 8 + 9 * 4 + 4 * 2 + 2 * 1 + 1 * 1);
  const auto path = file("mip.exr");
  write_file(path, grid, {true, false, 2});
  Imf::TiledInputFile file(path.c_str());
  ASSERT_EQ(file.numLevels(), static_cast<int>(levels.size()));
  EXPECT_EQ(file.tileXSize(), static_cast<unsigned>(kExrTileSide));
  EXPECT_EQ(file.header().channels().findChannel("R")->type, Imf::FLOAT);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    SCOPED_TRACE("level " + std::to_string(k));
    EXPECT_EQ(levels[k].scale, grid.scale * std::ldexp(1.0, static_cast<int>(k)));
    EXPECT_TRUE(
        test_support::same_bytes(read_level(file, static_cast<int>(k)), plain_render(levels[k])));
  }
  // read_image reads level 0.
  EXPECT_TRUE(test_support::same_bytes(read_image(path), plain_render(grid)));
}

TEST_F(TiledExrTest, ARegionIsThoseCellsOfTheWholeRender) {
  const Grid whole{{3.0, -4.0}, 2.0, 100, 150};
  const Grid region{whole.origin, whole.scale, 40, 90, 30, 45};
  const auto path = file("region.exr");
  write_file(path, region, {});
  const ImageF expected = plain_render(whole);
  const ImageF written = read_image(path);
  ASSERT_EQ(written.width(), 40);
  ASSERT_EQ(written.height(), 90);
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(written.at(x, y, c), expected.at(x + 30, y + 45, c));
  EXPECT_THROW(tiled_exr_levels(region, true), std::invalid_argument);
}

TEST_F(TiledExrTest, HalfPixelsAreTheRenderRoundedToHalf) {
  const Grid grid{{0.0, 0.0}, 1.0, 70, 65};
  const auto path = file("half.exr");
  write_file(path, grid, {false, true, 1});
  Imf::TiledInputFile file(path.c_str());
  EXPECT_EQ(file.header().channels().findChannel("G")->type, Imf::HALF);
  EXPECT_EQ(file.numLevels(), 1);
  const ImageF expected = plain_render(grid);
  const ImageF written = read_image(path);
  for (std::size_t i = 0; i < expected.pixels().size(); ++i)
    ASSERT_EQ(written.pixels()[i], static_cast<float>(Imath::half(expected.pixels()[i])));
}

TEST_F(TiledExrTest, AFailedRenderLeavesNoFile) {
  const Grid grid{{0.0, 0.0}, 1.0, 30, 200};
  EXPECT_THROW(write_tiled_exr(file("failed.exr"), grid, 3, {},
                               [](const Grid& strip, ImageView<float>) {
                                 if (strip.first_pixel_y > 64) throw std::runtime_error("stop");
                               }),
               Error);
  EXPECT_TRUE(folder_contents().empty());
}

TEST_F(TiledExrTest, SeveralFilesTakeTheirChannelsOfOneStrip) {
  // A material's maps (write_tiled_exrs): a strip of 3 + 1 channels, the plain render then each
  // pixel's level-grid coordinate sum, half pixels, every level; each file holds its own.
  const Grid grid{{2.0, -3.0}, 1.25, 90, 140};
  const std::vector<TiledExrFile> files{{file("albedo.exr"), 3}, {file("height.exr"), 1}};
  write_tiled_exrs(files, grid, {true, true, 1}, [](const Grid& strip, ImageView<float> out) {
    ImageF colour(strip.width, strip.height, 3);
    render(test_model(), strip, 5, colour.view());
    for (int y = 0; y < strip.height; ++y)
      for (int x = 0; x < strip.width; ++x) {
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = colour.at(x, y, c);
        out.at(x, y, 3) = static_cast<float>(x + strip.first_pixel_y + y);
      }
  });
  const std::vector<Grid> levels = tiled_exr_levels(grid, true);
  Imf::TiledInputFile albedo(files[0].path.c_str());
  Imf::TiledInputFile height(files[1].path.c_str());
  ASSERT_EQ(albedo.numLevels(), static_cast<int>(levels.size()));
  ASSERT_EQ(height.numLevels(), static_cast<int>(levels.size()));
  EXPECT_EQ(height.header().channels().findChannel("Y")->type, Imf::HALF);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    SCOPED_TRACE("level " + std::to_string(k));
    const ImageF expected = plain_render(levels[k]);
    const ImageF written = read_level(albedo, static_cast<int>(k));
    for (std::size_t i = 0; i < expected.pixels().size(); ++i)
      ASSERT_EQ(written.pixels()[i], static_cast<float>(Imath::half(expected.pixels()[i])));
  }
  const ImageF sums = read_image(files[1].path);
  ASSERT_EQ(sums.channels(), 1);
  for (int y = 0; y < grid.height; y += 13)
    for (int x = 0; x < grid.width; x += 7) ASSERT_EQ(sums.at(x, y, 0), static_cast<float>(x + y));
  // A failure half way leaves neither file.
  const std::vector<TiledExrFile> failing{{file("a.exr"), 2}, {file("b.exr"), 4}};
  EXPECT_THROW(write_tiled_exrs(failing, grid, {},
                                [](const Grid& strip, ImageView<float>) {
                                  if (strip.first_pixel_y > 64) throw std::runtime_error("stop");
                                }),
               Error);
  EXPECT_FALSE(std::filesystem::exists(failing[0].path));
  EXPECT_FALSE(std::filesystem::exists(failing[1].path));
}

}  // namespace
}  // namespace stochtex::tiled_exr_test
