#pragma once
// The image files of include/stochtex/io.hpp, and what the CLI adds to them.

#include <filesystem>
#include <vector>

#include "core/atomic_file.hpp"
#include "stochtex/io.hpp"

namespace stochtex {

// write_image as one file of a multi-file output, committed with the rest of `files`.
void write_image(AtomicFileSet& files, const std::filesystem::path& path,
                 ImageView<const float> image, int png_bit_depth = 8,
                 ColourSpace space = ColourSpace::data);

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
