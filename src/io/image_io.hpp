#pragma once
// The image files of include/stochtex/io.hpp, and what the CLI adds to them.

#include <filesystem>
#include <functional>
#include <vector>

#include "core/atomic_file.hpp"
#include "stochtex/io.hpp"

namespace stochtex {

// write_image as one file of a multi-file output, committed with the rest of `files`.
void write_image(AtomicFileSet& files, const std::filesystem::path& path,
                 ImageView<const float> image, int png_bit_depth = 8,
                 ColourSpace space = ColourSpace::data);

// The rows of a strip of write_png_strips (fewer at the bottom): speed only, never the bytes.
inline constexpr int kPngStripRows = 64;

// Makes the rows [first_row, first_row + out.height) of an image into `out`.
using StripMaker = std::function<void(int first_row, ImageView<float> out)>;

// write_image of a width x height PNG of `channels` channels, made strip by strip from the top
// by `make_strip` on the calling thread, each strip encoded on a second thread while the next is
// made, so that encoding overlaps making (a render). The file holds write_image's bytes of the
// whole image, whatever the timing; memory holds two strips, not the image. Fails as write_image
// does (and std::invalid_argument for a path that is not .png), or as make_strip throws, leaving
// no file.
void write_png_strips(const std::filesystem::path& path, int width, int height, int channels,
                      int png_bit_depth, ColourSpace space, const StripMaker& make_strip);

// Checks, before any long work, that `path` can be an output: its folder exists, it is missing or
// a regular file (core/atomic_file.hpp), it is none of the files `inputs` and, for an image
// (`image` true), its extension is .png, .exr or .pfm. Throws like write_image would, and
// std::invalid_argument when the output is an input.
void check_output_path(const std::filesystem::path& path, bool image,
                       const std::vector<std::filesystem::path>& inputs = {});

// The format write_image writes `path` in, by its extension (.png, .exr or .pfm in any case);
// std::invalid_argument for an extension it does not know.
ImageFormat output_image_format(const std::filesystem::path& path);

// Whether `path` names an OpenEXR output (output_image_format is exr).
bool is_exr_output(const std::filesystem::path& path);

// Checks that an image of `channels` channels can be written to `path` (PFM holds 1 or 3), so
// that a render to a format that cannot hold it is refused before the render.
void check_output_channels(const std::filesystem::path& path, int channels);

}  // namespace stochtex
