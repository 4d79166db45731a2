#pragma once
// The one way stochtex opens a file it reads (images, models, meshes; docs/design.md §6). The
// file is opened without blocking and examined before a byte is read: a FIFO, a device or a socket
// would block the open or the read, or never end, so only a regular file is read, and one sentence
// says what the path is instead. A program (the CLI) may also ask that no output replace a file
// it has read: protect_inputs() makes every InputFile opened afterwards a file that
// check_output_target (core/atomic_file.hpp) refuses to replace, whichever command read it.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace stochtex {

class InputFile {
 public:
  // Opens `path` for reading. Throws Error(io), one sentence naming `path` and `what` ("an
  // image", "a model file", "a mesh"), when it is missing, not a regular file or unreadable.
  InputFile(const std::filesystem::path& path, const char* what);
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  ~InputFile();

  std::FILE* stream() const { return stream_; }
  // The file's size when it was opened.
  std::uint64_t size() const { return size_; }
  // The whole file, refused (Error(invalid_input), naming `what` and `remedy`) beyond
  // `max_bytes`, before any of it is read.
  std::string read_all(std::uint64_t max_bytes, const std::string& remedy);

 private:
  std::filesystem::path path_;
  const char* what_;
  std::FILE* stream_ = nullptr;
  std::uint64_t size_ = 0;
};

// From now on, every file this process opens as an InputFile is an input that no output may
// replace (check_output_target refuses it as a usage error). For programs whose every command is
// one request (the CLI); a long-running server that rewrites the files it reads does not call it.
void protect_inputs();

// Throws std::invalid_argument ("the output 'X' is the input file 'Y'; write the output to
// another path") when inputs are protected and `target` is a file read as an InputFile.
void check_not_an_input(const std::filesystem::path& target);

}  // namespace stochtex
