#pragma once
// The image files of include/stochtex/io.hpp, and what the CLI adds to them.

#include <filesystem>

#include "stochtex/io.hpp"

namespace stochtex {

// Checks, before any long work, that `path` can be an output: its folder exists, it is missing or
// a regular file (core/atomic_file.hpp), it is not the file `input` (when one is given) and, for
// an image (`image` true), its extension is .png, .exr or .pfm. Throws like write_image would,
// and std::invalid_argument when the output is the input.
void check_output_path(const std::filesystem::path& path, bool image,
                       const std::filesystem::path& input = {});

// The format write_image writes `path` in, by its extension (.png, .exr or .pfm in any case);
// std::invalid_argument for an extension it does not know.
ImageFormat output_image_format(const std::filesystem::path& path);

// Whether `path` names an OpenEXR output (output_image_format is exr).
bool is_exr_output(const std::filesystem::path& path);

// Checks that an image of `channels` channels can be written to `path` (PFM holds 1 or 3), so
// that a render to a format that cannot hold it is refused before the render.
void check_output_channels(const std::filesystem::path& path, int channels);

}  // namespace stochtex
