// TGA (Truevision TGA 2.0: grey, colour-mapped and true-colour, raw or run-length encoded) through
// stb_image, as Debian packages it.

#include <stb/stb_image.h>

#include <array>
#include <climits>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/decoding.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

constexpr std::size_t kTgaHeaderBytes = 18;

// The header's fields the checks need.
struct TgaHeader {
  int id_bytes, colour_map_type, image_type, map_entries, map_bits, width, height, pixel_bits;

  explicit TgaHeader(std::span<const unsigned char> h)
      : id_bytes(h[0]),
        colour_map_type(h[1]),
        image_type(h[2]),
        map_entries(h[5] | h[6] << 8),
        map_bits(h[7]),
        width(h[12] | h[13] << 8),
        height(h[14] | h[15] << 8),
        pixel_bits(h[16]) {}

  bool run_length() const { return image_type >= 9; }
};

}  // namespace

bool is_tga(std::span<const unsigned char> first) {
  if (first.size() < kTgaHeaderBytes) return false;
  const TgaHeader header(first);
  const bool mapped = header.image_type == 1 || header.image_type == 9;
  const bool known_type = mapped || header.image_type == 2 || header.image_type == 3 ||
                          header.image_type == 10 || header.image_type == 11;
  const int bits = header.pixel_bits;
  return known_type && header.colour_map_type == (mapped ? 1 : 0) &&
         (bits == 8 || bits == 15 || bits == 16 || bits == 24 || bits == 32) &&
         (first[17] & 0xc0) == 0;  // the reserved bits of the descriptor
}

ImageF read_tga(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  std::array<unsigned char, kTgaHeaderBytes> first{};
  if (input.bytes < kTgaHeaderBytes ||
      std::fread(first.data(), 1, first.size(), input.file) != first.size())
    throw Error(ErrorCode::format, input.name + " ends inside its TGA header; it is truncated");
  const TgaHeader header(first);
  check_size(input.name, header.width, header.height, limits);
  // Raw pixels take their bytes each; a run-length packet repeats one pixel at most 128 times.
  const double pixel_bytes = (header.pixel_bits + 7) / 8;
  const double pixels = double(header.width) * header.height;
  const double map_bytes =
      header.colour_map_type ? header.map_entries * ((header.map_bits + 7) / 8) : 0;
  check_fits_file(input.name, header.width, header.height,
                  kTgaHeaderBytes + header.id_bytes + map_bytes +
                      (header.run_length() ? std::ceil(pixels / 128.0) * (1.0 + pixel_bytes)
                                           : pixels * pixel_bytes),
                  input.bytes);

  // stb_image counts bytes in an int; a TGA within the pixel limit is far smaller.
  if (input.bytes > INT_MAX)
    throw Error(ErrorCode::invalid_input, input.name +
                                              " is a TGA file of more than 2 GiB; save "
                                              "it as PNG, TIFF or OpenEXR");
  // At most a run-length packet per pixel, the header, its identification, a colour map and the
  // TGA 2.0 extension and developer areas (1 MiB is far more than writers put there).
  const std::vector<unsigned char> bytes =
      read_all(input, kTgaHeaderBytes + header.id_bytes + map_bytes + pixels * (1.0 + pixel_bytes) +
                          double(1 << 20));
  const auto unreadable = [&] {
    const char* reason = stbi_failure_reason();
    return Error(ErrorCode::format,
                 input.name + " is not a readable TGA image (" +
                     printable(reason ? reason : "stb_image cannot read it", 160) +
                     "); it is truncated or corrupt, export it again");
  };
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height,
                             &channels) ||
      width != header.width || height != header.height || channels < 1 || channels > 4)
    throw unreadable();
  check_declared(width, height, channels, limits);
  const std::unique_ptr<unsigned char, void (*)(void*)> samples(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height,
                            &channels, 0),
      stbi_image_free);
  if (!samples) throw unreadable();
  return image_of_bytes({samples.get(), std::size_t(width) * height * channels}, width, height,
                        channels, nullptr, "TGA", colour);
}

}  // namespace stochtex
