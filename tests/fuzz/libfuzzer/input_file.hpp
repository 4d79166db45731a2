#pragma once
// For readers that take a path: each input goes to one file of this process, written whole.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

// Writes the input to "/tmp/stochtex-<name>-fuzzer-<pid><extension>" and returns that path.
inline const std::string& write_input_file(const char* name, const char* extension,
                                           const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      std::string("/tmp/stochtex-") + name + "-fuzzer-" + std::to_string(getpid()) + extension;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  return path;
}
