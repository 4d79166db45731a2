#pragma once
// The byte streams of the image codecs (image_io.cpp) and the streamed tiled OpenEXR files
// (tiled_exr.cpp), as OpenEXR's stream classes, and the channel names of an image.
//
// Decoders read a stdio stream: a file, or a buffer opened with fmemopen, so that a file and a
// buffer go through the same code; FileInputStream gives OpenEXR's reader that stream. Encoders
// write an Imf::OStream: FileOutputStream into the temporary of an AtomicFile, or
// BufferOutputStream into memory. A memory stdio stream (open_memstream) would not do for
// writing: OpenEXR seeks back to fill in its offset table, and such a stream ends at its last
// position, not at its furthest byte.

#include <Iex.h>
#include <ImfIO.h>
#include <sys/types.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace stochtex {

// Lets OpenEXR read `file`, `bytes` bytes long, from any position. A read past the end fails as
// OpenEXR's own file stream fails (Iex::InputExc "Early end of file..."), so the messages of a
// truncated file are the same whether it is read from disk or from memory.
class FileInputStream final : public Imf::IStream {
 public:
  FileInputStream(std::FILE* file, std::uint64_t bytes, const char* name)
      : Imf::IStream(name), file_(file), bytes_(bytes) {}
  bool read(char c[], int n) override {
    const auto wanted = static_cast<std::size_t>(n);
    std::size_t got = 0;
    // fmemopen's streams refuse a seek past their end, which a file allows: such a position is
    // answered here, with nothing read.
    if (position_ < bytes_) {
      if (fseeko(file_, static_cast<off_t>(position_), SEEK_SET) != 0) Iex::throwErrnoExc();
      got = std::fread(c, 1, wanted, file_);
      if (got != wanted && std::ferror(file_)) Iex::throwErrnoExc();
    }
    position_ += got;
    if (got != wanted)
      throw Iex::InputExc("Early end of file: read " + std::to_string(got) + " out of " +
                          std::to_string(n) + " requested bytes.");
    return true;
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }
  void clear() override { std::clearerr(file_); }

 private:
  std::FILE* file_;
  std::uint64_t bytes_;
  std::uint64_t position_ = 0;
};

// Lets OpenEXR (and the PNG and PFM encoders) write into the temporary file opened (and checked)
// by an AtomicFile.
class FileOutputStream final : public Imf::OStream {
 public:
  FileOutputStream(std::FILE* file, const char* name) : Imf::OStream(name), file_(file) {}
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

// An encoder's bytes in memory: writes past the end extend the buffer (a seek past it leaves
// zeros), writes before it overwrite, as in a file.
class BufferOutputStream final : public Imf::OStream {
 public:
  explicit BufferOutputStream(const char* name) : Imf::OStream(name) {}
  void write(const char data[], int count) override {
    const std::size_t end = position_ + static_cast<std::size_t>(count);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, data, static_cast<std::size_t>(count));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = static_cast<std::size_t>(position); }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

// Writes `count` bytes through an Imf::OStream, whose write takes an int count.
inline void write_all(Imf::OStream& stream, const void* data, std::size_t count) {
  const char* bytes = static_cast<const char*>(data);
  while (count > 0) {
    const std::size_t part = std::min<std::size_t>(count, INT_MAX);
    stream.write(bytes, static_cast<int>(part));
    bytes += part;
    count -= part;
  }
}

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
