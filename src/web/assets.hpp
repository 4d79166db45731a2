#pragma once
// The browser pages compiled into stochtex: every .html, .css and .js file under web/, embedded
// by CMake (cmake/embed_files.cmake) and served by `stochtex studio` or written by
// `stochtex export-web`.

#include <span>
#include <string_view>

#include "core/embedded_file.hpp"

namespace stochtex::web {

// Every embedded web file, named by its path under web/ ("viewer/viewer.js").
std::span<const EmbeddedFile> embedded_files();

// The HTTP Content-Type of a file from its extension (UTF-8 text for .html, .css, .js, .json;
// application/octet-stream for anything else).
std::string_view content_type(std::string_view name);

}  // namespace stochtex::web
