#pragma once
// A text file compiled into the program by CMake (cmake/embed_files.cmake): the GLSL of src/ for
// the GPU backend, the README templates of src/gl/readme/ for `export-shader` and the web pages of
// web/ for `stochtex studio` and `export-web`.

#include <span>
#include <string_view>

namespace stochtex {

struct EmbeddedFile {
  std::string_view name;  // its path under the embedded folder, with '/' separators
  std::string_view text;
};

// The file called `name` among `files`, or nullptr.
inline const EmbeddedFile* find_embedded(std::span<const EmbeddedFile> files,
                                         std::string_view name) {
  for (const EmbeddedFile& file : files)
    if (file.name == name) return &file;
  return nullptr;
}

}  // namespace stochtex
