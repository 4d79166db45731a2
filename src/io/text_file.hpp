#pragma once
// Text files (HTML, JSON, GLSL, READMEs) written like images: to a temporary name in the same
// folder, then renamed, so a failure never leaves a partial file. Failures throw stochtex::Error
// with a sentence naming the file.

#include <filesystem>
#include <string_view>

namespace stochtex {

void write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace stochtex
