#pragma once
// Tiled, optionally mip-mapped OpenEXR files rendered and written strip by strip, so that an image
// larger than memory is baked with memory for one strip (one row of tiles) of its width, whatever
// its height (docs/large-renders.md). The file goes through an AtomicFile like write_image's.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/render.hpp"

namespace stochtex {

// The side of the file's square tiles, and so the height of a strip.
inline constexpr int kExrTileSide = 64;

struct TiledExrOptions {
  // MIPMAP_LEVELS with ROUND_DOWN: level k is max(1, floor(W / 2^k)) x max(1, floor(H / 2^k))
  // pixels, down to 1 x 1. Otherwise one level.
  bool mipmap = false;
  bool half = false;  // HALF pixels, ZIP-compressed; FLOAT uncompressed otherwise
  int threads = 1;    // OpenEXR's threads, which compress a strip's tiles
};

// The grid of each level of a file of `grid`: level 0 is `grid`; with mipmap, level k samples the
// same origin at scale * 2^k with the level's size, i.e. it is what a render of that grid gives
// (the texture seen zoomed out, with the method's own filtering). A mip-mapped grid must start at
// its first pixel (first_pixel_x and first_pixel_y 0): std::invalid_argument otherwise.
std::vector<Grid> tiled_exr_levels(const Grid& grid, bool mipmap);

// The pixels of every level of the file together.
std::uint64_t tiled_exr_pixels(const Grid& grid, bool mipmap);

// Renders one strip: `out` is strip.width x strip.height pixels of the file's channels.
using StripRenderer = std::function<void(const Grid& strip, ImageView<float> out)>;

// Writes the tiled file of `grid` (1 to 4 channels) to `path`: for each level in turn, each strip
// of kExrTileSide rows (fewer at the bottom) from the top is rendered by `render_strip` as the
// level's grid with first_pixel_y advanced to the strip, then compressed and written. Failures
// throw like write_image's: Error(io) with one sentence naming the file, which is not left behind.
void write_tiled_exr(const std::filesystem::path& path, const Grid& grid, int channels,
                     const TiledExrOptions& options, const StripRenderer& render_strip);

// One of the files of write_tiled_exrs: its path and channel count (1 to 4).
struct TiledExrFile {
  std::filesystem::path path;
  int channels = 0;
};

// write_tiled_exr of several files of the same grid from one render: each strip has the files'
// channels one after another (the first file's, then the second's...), and each file takes its
// own (a material's maps, docs/materials.md). A failure while rendering or writing leaves none of
// them behind.
void write_tiled_exrs(std::span<const TiledExrFile> files, const Grid& grid,
                      const TiledExrOptions& options, const StripRenderer& render_strip);

}  // namespace stochtex
