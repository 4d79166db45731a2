#pragma once
// What the OpenEXR writers (image_io.cpp's scanline write_exr and tiled_exr.cpp's streamed tiled
// files) share: the stream into an AtomicFile's temporary and the channel names of an image.

#include <ImfIO.h>
#include <sys/types.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <system_error>

namespace stochtex {

// Lets OpenEXR write into the temporary file opened (and checked) by an AtomicFile.
class ExrFileStream final : public Imf::OStream {
 public:
  ExrFileStream(std::FILE* file, const char* name) : Imf::OStream(name), file_(file) {}
  void write(const char data[], int count) override {
    if (std::fwrite(data, 1, static_cast<std::size_t>(count), file_) !=
        static_cast<std::size_t>(count))
      throw std::system_error(errno, std::generic_category());
  }
  std::uint64_t tellp() override {
    const off_t position = ftello(file_);
    if (position < 0) throw std::system_error(errno, std::generic_category());
    return static_cast<std::uint64_t>(position);
  }
  void seekp(std::uint64_t position) override {
    if (fseeko(file_, static_cast<off_t>(position), SEEK_SET) != 0)
      throw std::system_error(errno, std::generic_category());
  }

 private:
  std::FILE* file_;
};

// The channel names of an image of 1 to 4 channels: Y, (Y, A), (R, G, B) or (R, G, B, A).
inline const std::array<const char*, 4>& exr_written_channel_names(int channels) {
  static constexpr std::array<std::array<const char*, 4>, 4> kNames = {{
      {"Y"},
      {"Y", "A"},
      {"R", "G", "B"},
      {"R", "G", "B", "A"},
  }};
  return kNames[static_cast<std::size_t>(channels - 1)];
}

}  // namespace stochtex
