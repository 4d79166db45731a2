#pragma once
// The pieces of the one-sentence messages about files (docs/design.md §9), shared by the image
// files (src/io) and the safe writes (core/atomic_file.hpp).

#include <sys/stat.h>

#include <filesystem>
#include <stdexcept>
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

// What a file of this mode is, in a sentence ("it is a FIFO"), or nullptr for a regular file: the
// files stochtex neither reads (core/input_file.hpp) nor replaces (core/atomic_file.hpp).
inline const char* kind_of_file(mode_t mode) {
  if (S_ISREG(mode)) return nullptr;
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "a device";
}

// The usage error of an output that is one of the command's input files.
inline std::invalid_argument output_is_input(const std::filesystem::path& output,
                                             const std::filesystem::path& input) {
  return std::invalid_argument("the output " + quoted(output) + " is the input file " +
                               quoted(input) + "; write the output to another path");
}

// The system's sentence for an errno value ("No such file or directory").
inline std::string errno_message(int error) {
  return std::generic_category().message(error);
}

}  // namespace stochtex
