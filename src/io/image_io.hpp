#pragma once
// The image files of include/stochtex/io.hpp, and what the CLI adds to them.

#include <filesystem>

#include "stochtex/io.hpp"

namespace stochtex {

// Checks, before any long work, that `path` can be an output: its folder exists and, for an image
// (`image` true), its extension is .png, .exr or .pfm. Throws like write_image would.
void check_output_path(const std::filesystem::path& path, bool image);

}  // namespace stochtex
