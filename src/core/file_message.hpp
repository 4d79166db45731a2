#pragma once
// The pieces of the one-sentence messages about files (docs/design.md §9), shared by the image
// files (src/io) and the safe writes (core/atomic_file.hpp).

#include <filesystem>
#include <string>
#include <system_error>

namespace stochtex {

// Built by appending: "'" + path.string() trips GCC 12's -Wrestrict once inlined.
inline std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += '\'';
  return text;
}

// The system's sentence for an errno value ("No such file or directory").
inline std::string errno_message(int error) {
  return std::generic_category().message(error);
}

}  // namespace stochtex
