#include "io/tiled_exr.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfThreading.h>
#include <ImfTileDescription.h>
#include <ImfTiledOutputFile.h>
#include <half.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#include "core/atomic_file.hpp"
#include "core/file_message.hpp"
#include "io/compression.hpp"
#include "io/image_streams.hpp"
#include "stochtex/error.hpp"

namespace stochtex {

namespace fs = std::filesystem;

std::vector<Grid> tiled_exr_levels(const Grid& grid, bool mipmap) {
  std::vector<Grid> levels = {grid};
  if (!mipmap) return levels;
  if (grid.first_pixel_x != 0 || grid.first_pixel_y != 0)
    throw std::invalid_argument(
        "a mip-mapped image is rendered from its first pixel: a region of a larger render has no "
        "mip levels of its own");
  while (levels.back().width > 1 || levels.back().height > 1) {
    Grid next = levels.back();
    next.scale *= 2.0;
    next.width = std::max(1, next.width / 2);
    next.height = std::max(1, next.height / 2);
    levels.push_back(next);
  }
  return levels;
}

std::uint64_t tiled_exr_pixels(const Grid& grid, bool mipmap) {
  std::uint64_t pixels = 0;
  for (const Grid& level : tiled_exr_levels(grid, mipmap))
    pixels += static_cast<std::uint64_t>(level.width) * static_cast<std::uint64_t>(level.height);
  return pixels;
}

void write_tiled_exr(const fs::path& path, const Grid& grid, int channels,
                     const TiledExrOptions& options, const StripRenderer& render_strip) {
  const TiledExrFile file{path, channels};
  write_tiled_exrs(std::span<const TiledExrFile>(&file, 1), grid, options, render_strip);
}

void write_tiled_exrs(std::span<const TiledExrFile> files, const Grid& grid,
                      const TiledExrOptions& options, const StripRenderer& render_strip) {
  if (files.empty()) throw std::invalid_argument("write_tiled_exrs: no file to write");
  int channels = 0;  // of a strip: every file's
  for (const TiledExrFile& file : files) {
    if (file.channels < 1 || file.channels > 4 || grid.width < 1 || grid.height < 1)
      throw std::invalid_argument("cannot write " + quoted(file.path) + ": the image is " +
                                  std::to_string(grid.width) + "x" + std::to_string(grid.height) +
                                  " pixels with " + std::to_string(file.channels) +
                                  " channels; it needs at least one pixel and 1 to 4 channels");
    channels += file.channels;
  }
  const std::vector<Grid> levels = tiled_exr_levels(grid, options.mipmap);
  const Imf::PixelType type = options.half ? Imf::HALF : Imf::FLOAT;
  const std::size_t value_bytes = options.half ? sizeof(Imath::half) : sizeof(float);
  // One strip of level 0, the widest; the strips of the other levels use its first columns.
  ImageF strip(grid.width, std::min(kExrTileSide, grid.height), channels);
  std::vector<Imath::half> halves(options.half ? strip.pixels().size() : 0);

  AtomicFileSet atomic;     // every file or none
  std::size_t current = 0;  // the file being opened or written, for the messages
  try {
    Imf::setGlobalThreadCount(options.threads);
    std::vector<std::unique_ptr<FileOutputStream>> streams;
    std::vector<std::unique_ptr<Imf::TiledOutputFile>> outputs;
    for (; current < files.size(); ++current) {
      const TiledExrFile& file = files[current];
      Imf::Header header(grid.width, grid.height);
      header.compression() = options.half ? kExrHalfCompression : kExrFloatCompression;
      header.setTileDescription(Imf::TileDescription(
          kExrTileSide, kExrTileSide, options.mipmap ? Imf::MIPMAP_LEVELS : Imf::ONE_LEVEL,
          Imf::ROUND_DOWN));
      const auto& names = exr_written_channel_names(file.channels);
      for (int c = 0; c < file.channels; ++c)
        header.channels().insert(names[c], Imf::Channel(type));
      AtomicFile& opened = atomic.open(file.path);
      streams.push_back(
          std::make_unique<FileOutputStream>(opened.stream(), opened.temporary().c_str()));
      outputs.push_back(
          std::make_unique<Imf::TiledOutputFile>(*streams.back(), header, options.threads));
    }
    for (int level = 0; level < static_cast<int>(levels.size()); ++level) {
      const Grid& level_grid = levels[static_cast<std::size_t>(level)];
      for (int row = 0; row < level_grid.height; row += kExrTileSide) {
        Grid strip_grid = level_grid;
        strip_grid.height = std::min(kExrTileSide, level_grid.height - row);
        strip_grid.first_pixel_y += row;
        const ImageView<float> out = strip.view().sub(0, 0, strip_grid.width, strip_grid.height);
        render_strip(strip_grid, out);
        // OpenEXR converts no pixel type in tiled files: half pixels are converted here.
        const char* values = reinterpret_cast<const char*>(out.data);
        std::size_t row_bytes = sizeof(float) * static_cast<std::size_t>(out.row_stride);
        if (options.half) {
          const std::size_t row_values = static_cast<std::size_t>(out.width) * channels;
          for (int y = 0; y < out.height; ++y)
            std::copy_n(out.row(y), row_values, halves.begin() + y * row_values);
          values = reinterpret_cast<const char*>(halves.data());
          row_bytes = sizeof(Imath::half) * row_values;
        }
        // The slices address the level's pixel coordinates: the strip holds rows [row, row + h),
        // each file its channels from `first`.
        const Imath::Box2i window({0, row}, {strip_grid.width - 1, row + strip_grid.height - 1});
        int first = 0;
        for (current = 0; current < files.size(); ++current) {
          const auto& names = exr_written_channel_names(files[current].channels);
          Imf::FrameBuffer frame_buffer;
          for (int c = 0; c < files[current].channels; ++c)
            frame_buffer.insert(names[c],
                                Imf::Slice::Make(type, values + (first + c) * value_bytes, window,
                                                 value_bytes * channels, row_bytes));
          first += files[current].channels;
          Imf::TiledOutputFile& output = *outputs[current];
          output.setFrameBuffer(frame_buffer);
          const int tile_row = row / kExrTileSide;
          output.writeTiles(0, output.numXTiles(level) - 1, tile_row, tile_row, level);
        }
      }
    }
  } catch (const Error&) {
    throw;
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorCode::io, "cannot write " +
                                   quoted(files[std::min(current, files.size() - 1)].path) + ": " +
                                   e.what());
  }
  atomic.commit();
}

}  // namespace stochtex
