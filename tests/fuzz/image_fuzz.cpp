// Deterministic mutation fuzzing of read_image and decode_image (docs/design.md §9): small valid
// PNG, OpenEXR and PFM files, and PNGs with colour chunks (sRGB, gAMA, cICP, an ICC profile), are
// damaged in seeded, reproducible ways, and every damaged file must either read as a consistent
// image or throw stochtex::Error, as stored and with its colour (an ImageColour), and its bytes
// must decode from memory to the same image and colour or the same error. Any other exception, or
// a crash, fails the test.

#include <gtest/gtest.h>
#include <lcms2.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "image_files.hpp"
#include "io/image_io.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "test_support.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

constexpr int kMutatedFiles = 5000;
constexpr std::uint32_t kSeed = 20240611;

Bytes read_bytes(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const Bytes& bytes) {
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  stream.write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
}

struct Seed {
  std::string name;  // with the extension of its format
  Bytes bytes;
  bool png = false;
};

// The PNG chunk checksum is zlib's CRC-32.
std::uint32_t crc32(const unsigned char* data, std::size_t size) {
  return static_cast<std::uint32_t>(::crc32(0L, data, static_cast<uInt>(size)));
}

// `png` with a chunk of `type` holding `data` after its header chunk (IHDR, 25 bytes after the
// 8-byte signature), where colour chunks belong.
Bytes with_chunk(const Bytes& png, const char* type, const Bytes& data) {
  Bytes chunk;
  for (int shift = 24; shift >= 0; shift -= 8)
    chunk.push_back(static_cast<unsigned char>(data.size() >> shift));
  chunk.insert(chunk.end(), type, type + 4);
  chunk.insert(chunk.end(), data.begin(), data.end());
  const std::uint32_t crc = crc32(chunk.data() + 4, chunk.size() - 4);
  for (int shift = 24; shift >= 0; shift -= 8)
    chunk.push_back(static_cast<unsigned char>(crc >> shift));
  Bytes result(png.size() + chunk.size());
  const auto after_header = std::copy(png.begin(), png.begin() + 33, result.begin());
  std::copy(png.begin() + 33, png.end(), std::copy(chunk.begin(), chunk.end(), after_header));
  return result;
}

// An iCCP chunk's data: a name, its terminator, compression method 0, then an RGB profile that is
// not sRGB (Adobe RGB (1998)'s primaries, gamma 2.2), compressed, so that reading converts.
Bytes wide_rgb_iccp() {
  const Bytes icc = test_support::wide_rgb_icc();
  uLongf compressed_size = compressBound(static_cast<uLong>(icc.size()));
  Bytes data = {'i', 'c', 'c', 0, 0};
  data.resize(data.size() + compressed_size);
  compress2(data.data() + 5, &compressed_size, icc.data(), static_cast<uLong>(icc.size()), 9);
  data.resize(5 + compressed_size);
  return data;
}

std::vector<Seed> make_seeds(const fs::path& folder) {
  const auto image = [](int width, int height, int channels) {
    ImageF result(width, height, channels);
    std::mt19937 random(kSeed);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& sample : result.pixels()) sample = value(random);
    return result;
  };
  struct Recipe {
    const char* name;
    ImageF image;
    int bit_depth;
  };
  const std::array<Recipe, 8> recipes = {{
      {"rgb8.png", image(7, 5, 3), 8},
      {"grey_alpha8.png", image(6, 3, 2), 8},
      {"rgba16.png", image(5, 4, 4), 16},
      {"grey16.png", image(9, 2, 1), 16},
      {"rgba.exr", image(6, 5, 4), 8},
      {"grey.exr", image(4, 7, 1), 8},
      {"rgb.pfm", image(5, 3, 3), 8},
      {"grey.pfm", image(3, 4, 1), 8},
  }};
  std::vector<Seed> seeds;
  for (const Recipe& recipe : recipes) {
    const fs::path path = folder / recipe.name;
    write_image(path, recipe.image.view(), recipe.bit_depth);
    seeds.push_back({recipe.name, read_bytes(path), path.extension() == ".png"});
  }
  // Colour: the sRGB, gAMA and cHRM chunks write_image writes for sRGB values, a gAMA to convert,
  // a cICP and an ICC profile.
  write_image(folder / "srgb8.png", image(5, 6, 3).view(), 8, ColourSpace::srgb);
  seeds.push_back({"srgb8.png", read_bytes(folder / "srgb8.png"), true});
  seeds.push_back(
      {"gama_grey_alpha8.png", with_chunk(seeds[1].bytes, "gAMA", {0, 0, 0xb1, 0x8f}), true});
  seeds.push_back({"cicp_rgba16.png", with_chunk(seeds[2].bytes, "cICP", {1, 8, 0, 1}), true});
  seeds.push_back({"iccp_rgb8.png", with_chunk(seeds[0].bytes, "iCCP", wide_rgb_iccp()), true});
  // The formats read but not written, as their libraries write them: EXIF orientation, ICC
  // profiles, progressive JPEG, compressed and tiled TIFF, lossless
  // WebP with alpha, run-length TGA.
  const Bytes icc = test_support::wide_rgb_icc();
  using namespace test_support;
  seeds.push_back({"grey.jpg", jpeg_file(image(9, 7, 1), {.quality = 80}), false});
  seeds.push_back({"rgb.jpg",
                   jpeg_file(image(12, 10, 3), {.progressive = true, .icc = icc, .orientation = 6}),
                   false});
  seeds.push_back({"rgb16.tif",
                   tiff_file(image(6, 5, 3), folder, {.bits = 16, .compression = COMPRESSION_LZW}),
                   false});
  seeds.push_back(
      {"grey_float.tif", tiff_file(image(5, 4, 1), folder, {.bits = 32, .tiled = true}), false});
  seeds.push_back({"rgb_icc.tif", tiff_file(image(4, 3, 3), folder, {.icc = icc}), false});
  seeds.push_back({"rgba.webp", webp_file(image(7, 6, 4), true), false});
  seeds.push_back({"rgb_icc.webp", webp_file(image(8, 8, 3), false, icc), false});
  seeds.push_back({"rgb_rle.tga", tga_file(image(6, 5, 3), true), false});
  seeds.push_back({"grey.tga", tga_file(image(5, 3, 1), false), false});
  return seeds;
}

// Rewrites every PNG chunk checksum, so that mutations reach the chunk parsers and the inflater
// instead of stopping at the first checksum test.
void fix_png_checksums(Bytes& png) {
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::uint32_t length = std::uint32_t{png[at]} << 24 | std::uint32_t{png[at + 1]} << 16 |
                                 std::uint32_t{png[at + 2]} << 8 | png[at + 3];
    if (length > png.size() - at - 12) return;
    const std::uint32_t crc = crc32(png.data() + at + 4, length + 4);
    for (int b = 0; b < 4; ++b)
      png[at + 8 + length + b] = static_cast<unsigned char>(crc >> (24 - 8 * b));
    at += 12 + length;
  }
}

// Values that sit on the edges parsers get wrong: zero, signs, powers of two, type limits.
constexpr std::array<std::uint32_t, 12> kInterestingNumbers = {
    0u,      1u,      2u,       0x7fu,       0x80u,       0xffu,
    0x7fffu, 0xffffu, 0x10000u, 0x7fffffffu, 0x80000000u, 0xffffffffu};

void mutate(Bytes& bytes, std::mt19937& random) {
  const auto position = [&](std::size_t size) {
    return std::uniform_int_distribution<std::size_t>(0, size == 0 ? 0 : size - 1)(random);
  };
  // Headers hold the sizes and types, so most edits land in the first bytes.
  const auto header_position = [&] { return position(std::min<std::size_t>(bytes.size(), 96)); };
  const int edits = std::uniform_int_distribution<int>(1, 4)(random);
  for (int edit = 0; edit < edits && !bytes.empty(); ++edit) {
    switch (std::uniform_int_distribution<int>(0, 6)(random)) {
      case 0: {  // bit flip
        bytes[position(bytes.size())] ^= static_cast<unsigned char>(1u << (random() % 8));
        break;
      }
      case 1: {  // byte overwrite
        bytes[header_position()] = static_cast<unsigned char>(random());
        break;
      }
      case 2: {  // truncation
        bytes.resize(position(bytes.size()));
        break;
      }
      case 3: {  // insertion of random bytes
        const std::size_t at = position(bytes.size() + 1);
        Bytes inserted(std::uniform_int_distribution<std::size_t>(1, 16)(random));
        for (auto& byte : inserted) byte = static_cast<unsigned char>(random());
        bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), inserted.begin(),
                     inserted.end());
        break;
      }
      case 4: {  // deletion of a range
        const std::size_t at = position(bytes.size());
        const std::size_t count =
            std::min(bytes.size() - at, std::uniform_int_distribution<std::size_t>(1, 16)(random));
        bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                    bytes.begin() + static_cast<std::ptrdiff_t>(at + count));
        break;
      }
      case 5: {  // a binary header number, in either byte order
        const std::size_t at = header_position();
        if (at + 4 > bytes.size()) break;
        const std::uint32_t value = kInterestingNumbers[random() % kInterestingNumbers.size()];
        const bool big_endian = random() % 2 == 0;
        for (int b = 0; b < 4; ++b)
          bytes[at + b] = static_cast<unsigned char>(value >> (big_endian ? 24 - 8 * b : 8 * b));
        break;
      }
      case 6: {  // a text header number (PFM): a digit run replaced by another number
        const std::size_t at = header_position();
        const auto is_digit = [](unsigned char c) { return c >= '0' && c <= '9'; };
        const auto start =
            std::find_if(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end(), is_digit);
        const auto stop = std::find_if_not(start, bytes.end(), is_digit);
        const std::string replacement = std::to_string(
            static_cast<std::int32_t>(kInterestingNumbers[random() % kInterestingNumbers.size()]));
        const auto offset = start - bytes.begin();
        bytes.erase(start, stop);
        bytes.insert(bytes.begin() + offset, replacement.begin(), replacement.end());
        break;
      }
    }
  }
}

// What reading gave: an image, or the code and message of the stochtex::Error thrown, with the
// file's name in the message, quoted (stochtex's words for a file) or not (OpenEXR's, and the
// name decode_image is given here), replaced by "<name>".
struct Outcome {
  ImageF image;
  ImageColour colour;
  bool refused = false;
  ErrorCode code = ErrorCode::numerical;
  std::string message;
};

template <typename Read>
Outcome outcome_of(const Read& read, const std::string& name) {
  Outcome outcome;
  try {
    outcome.image = read(outcome.colour);
  } catch (const Error& error) {
    outcome.refused = true;
    outcome.code = error.code();
    outcome.message = error.what();
    for (const std::string& spelling : {"'" + name + "'", name})
      for (std::size_t at = outcome.message.find(spelling); at != std::string::npos;
           at = outcome.message.find(spelling, at))
        outcome.message.replace(at, spelling.size(), "<name>");
  }
  return outcome;
}

TEST(ImageFuzz, MutatedFilesReadOrThrowError) {
  const fs::path folder =
      fs::temp_directory_path() / ("stochtex_image_fuzz_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::vector<Seed> seeds = make_seeds(folder);

  ImageReadLimits limits;
  limits.max_pixels = 1 << 12;
  std::mt19937 random(kSeed);
  // As stored, then with the colour (index 1).
  std::array<int, 2> images_read{};
  std::array<int, 2> errors_thrown{};
  const fs::path mutated_path = folder / "mutated";
  for (int iteration = 0; iteration < kMutatedFiles; ++iteration) {
    const Seed& seed = seeds[iteration % seeds.size()];
    Bytes bytes = seed.bytes;
    mutate(bytes, random);
    if (seed.png && random() % 2 == 0) fix_png_checksums(bytes);
    write_bytes(mutated_path, bytes);
    for (const bool with_colour : {false, true}) {
      const std::string context = "iteration " + std::to_string(iteration) + " from " + seed.name +
                                  (with_colour ? ", with its colour" : "");
      try {
        const Outcome file = outcome_of(
            [&](ImageColour& colour) {
              return read_image(mutated_path, limits, with_colour ? &colour : nullptr);
            },
            mutated_path.string());
        const Outcome memory = outcome_of(
            [&](ImageColour& colour) {
              return decode_image(bytes, mutated_path.string(), limits,
                                  with_colour ? &colour : nullptr);
            },
            mutated_path.string());
        ASSERT_EQ(memory.refused, file.refused)
            << context << ": " << file.message << memory.message;
        if (file.refused) {
          ASSERT_EQ(memory.code, file.code) << context;
          ASSERT_EQ(memory.message, file.message) << context;
          ++errors_thrown[with_colour];
          continue;
        }
        const ImageF& image = file.image;
        ASSERT_GT(image.width(), 0) << context;
        ASSERT_GT(image.height(), 0) << context;
        ASSERT_GE(image.channels(), 1) << context;
        ASSERT_LE(image.channels(), 4) << context;
        ASSERT_LE(static_cast<std::int64_t>(image.pixel_count()), limits.max_pixels) << context;
        ASSERT_EQ(image.pixels().size(), image.pixel_count() * image.channels()) << context;
        ASSERT_EQ(memory.image.width(), image.width()) << context;
        ASSERT_EQ(memory.image.height(), image.height()) << context;
        ASSERT_EQ(memory.image.channels(), image.channels()) << context;
        // OpenEXR 3.1 gives some damaged chunks the pixels of a buffer it never wrote (valgrind:
        // allocated by Imf::newCompressor), which differ from one read to the next: only the
        // pixels of the other formats are compared.
        if (!seed.name.ends_with(".exr")) {
          ASSERT_TRUE(test_support::same_bytes(memory.image, image)) << context;
        }
        if (with_colour) {
          ASSERT_NE(file.colour.space, ColourSpace::data) << context;
          ASSERT_FALSE(file.colour.origin.empty()) << context;
          ASSERT_EQ(memory.colour.space, file.colour.space) << context;
          ASSERT_EQ(memory.colour.origin, file.colour.origin) << context;
          if (seed.png) {
            for (const float value : image.pixels()) ASSERT_TRUE(std::isfinite(value)) << context;
          }
        }
        ++images_read[with_colour];
      } catch (const std::exception& e) {
        FAIL() << context << " threw something other than stochtex::Error: " << e.what();
      }
    }
  }
  fs::remove_all(folder);
  // Both outcomes occur, each way of reading, so the mutations neither always break the files
  // nor never reach them.
  for (const int colour : {0, 1}) {
    EXPECT_GT(images_read[colour], 0);
    EXPECT_GT(errors_thrown[colour], 0);
    std::printf("%d mutated files, %s: %d read, %d refused with stochtex::Error\n", kMutatedFiles,
                colour ? "with their colour" : "as stored", images_read[colour],
                errors_thrown[colour]);
  }
}

}  // namespace
}  // namespace stochtex
