// JPEG through libjpeg-turbo (the libjpeg API), with its EXIF orientation read by libexif and its
// ICC profile by libjpeg-turbo: what a phone or a camera writes. Errors leave libjpeg by longjmp,
// so the function that calls setjmp holds only trivially destructible locals, and what owns memory
// lives in its caller's frame.

// jpeglib.h uses size_t and FILE without including their headers.
#include <cstddef>
#include <cstdio>
// clang-format off
#include <jpeglib.h>
#include <jerror.h>
// clang-format on
#include <libexif/exif-data.h>

#include <algorithm>
#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "io/decoding.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

// A progressive JPEG may hold any number of scans, each a pass over the whole image: a small file
// of many empty scans would take minutes. libjpeg-turbo's own tools stop at 500 (TurboJPEG's
// TJPARAM_SCANLIMIT); encoders write at most a few dozen.
constexpr int kMaxScans = 500;

struct JpegErrors {
  jpeg_error_mgr manager{};
  std::jmp_buf jump{};
  char text[JMSG_LENGTH_MAX] = {};
  bool truncated = false;  // libjpeg met the end of the file before the end of the image
};

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->text);
  std::longjmp(errors->jump, 1);
}

// Warnings (level -1) are corrupt data libjpeg works around, such as extraneous bytes between
// markers, which photos from real cameras have; the end of the file before the end of the image
// is kept for the message that refuses it. Trace messages (levels above 0) are dropped.
void on_jpeg_message(j_common_ptr info, int level) {
  if (level == -1 && info->err->msg_code == JWRN_JPEG_EOF)
    reinterpret_cast<JpegErrors*>(info->err)->truncated = true;
}

void on_jpeg_progress(j_common_ptr info) {
  const auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
  if (decompress->input_scan_number > kMaxScans) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    std::snprintf(errors->text, sizeof errors->text, "more than %d scans, which no encoder writes",
                  kMaxScans);
    std::longjmp(errors->jump, 1);
  }
}

struct JpegReader {
  JpegErrors errors;
  jpeg_progress_mgr progress{};
  jpeg_decompress_struct info{};

  JpegReader() {
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = on_jpeg_error;
    errors.manager.emit_message = on_jpeg_message;
    progress.progress_monitor = on_jpeg_progress;
  }
  ~JpegReader() { jpeg_destroy_decompress(&info); }
  JpegReader(const JpegReader&) = delete;
  JpegReader& operator=(const JpegReader&) = delete;
};

// Reads the header, keeping the EXIF (APP1) and ICC (APP2) markers.
bool read_jpeg_header(JpegReader& reader, std::FILE* file) {
  if (setjmp(reader.errors.jump)) return false;
  jpeg_create_decompress(&reader.info);
  reader.info.progress = &reader.progress;
  jpeg_stdio_src(&reader.info, file);
  jpeg_save_markers(&reader.info, JPEG_APP0 + 1, 0xffff);
  jpeg_save_markers(&reader.info, JPEG_APP0 + 2, 0xffff);
  jpeg_read_header(&reader.info, TRUE);
  return true;
}

// The ICC profile the APP2 markers hold, in `profile` (empty when there is none).
bool read_jpeg_icc_profile(JpegReader& reader, std::vector<unsigned char>& profile) {
  if (setjmp(reader.errors.jump)) return false;
  JOCTET* data = nullptr;
  unsigned int bytes = 0;
  if (jpeg_read_icc_profile(&reader.info, &data, &bytes) && data) {
    profile.assign(data, data + bytes);
    std::free(data);
  }
  return true;
}

// Decodes the samples into `samples` (width x height x components, row after row).
bool read_jpeg_samples(JpegReader& reader, unsigned char* samples, std::size_t row_bytes) {
  if (setjmp(reader.errors.jump)) return false;
  jpeg_start_decompress(&reader.info);
  while (reader.info.output_scanline < reader.info.output_height) {
    JSAMPROW row = samples + reader.info.output_scanline * row_bytes;
    jpeg_read_scanlines(&reader.info, &row, 1);
  }
  jpeg_finish_decompress(&reader.info);
  return true;
}

[[noreturn]] void throw_jpeg_error(const std::string& name, const JpegReader& reader) {
  throw Error(ErrorCode::format, name + " is not a readable JPEG image (" +
                                     printable(reader.errors.text, 160) +
                                     "); it is truncated or corrupt, export it again");
}

// The EXIF orientation (1 to 8) in an APP1 marker, or 1 when there is none.
int exif_orientation(const jpeg_decompress_struct& info) {
  for (jpeg_saved_marker_ptr marker = info.marker_list; marker; marker = marker->next) {
    if (marker->marker != JPEG_APP0 + 1 || marker->data_length < 6 ||
        std::memcmp(marker->data, "Exif\0\0", 6) != 0)
      continue;
    const std::unique_ptr<ExifData, void (*)(ExifData*)> exif(
        exif_data_new_from_data(marker->data, marker->data_length), exif_data_unref);
    if (!exif) continue;
    ExifEntry* entry = exif_content_get_entry(exif->ifd[EXIF_IFD_0], EXIF_TAG_ORIENTATION);
    if (!entry || entry->format != EXIF_FORMAT_SHORT || entry->components != 1 || !entry->data ||
        entry->size < 2)
      continue;
    return exif_get_short(entry->data, exif_data_get_byte_order(exif.get()));
  }
  return 1;
}

}  // namespace

bool is_jpeg(std::span<const unsigned char> first) {
  return first.size() >= 3 && first[0] == 0xff && first[1] == 0xd8 && first[2] == 0xff;
}

ImageF read_jpeg(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  JpegReader reader;
  if (!read_jpeg_header(reader, input.file)) throw_jpeg_error(input.name, reader);
  jpeg_decompress_struct& info = reader.info;
  check_size(input.name, info.image_width, info.image_height, limits);
  int channels = 0;
  if (info.num_components == 1 && info.jpeg_color_space == JCS_GRAYSCALE) {
    info.out_color_space = JCS_GRAYSCALE;
    channels = 1;
  } else if (info.num_components == 3 &&
             (info.jpeg_color_space == JCS_YCbCr || info.jpeg_color_space == JCS_RGB)) {
    info.out_color_space = JCS_RGB;
    channels = 3;
  } else {
    throw Error(ErrorCode::format,
                input.name + " is a JPEG of " + std::to_string(info.num_components) +
                    (info.num_components == 4 ? " (CMYK) channels" : " channels") +
                    ", which stochtex does not read; convert it to RGB or grey");
  }
  // With Huffman coding, every 8x8 block of the first component costs at least one bit (its DC
  // difference has a code of at least one bit): a tiny file cannot declare a huge image.
  if (!info.arith_code)
    check_fits_file(input.name, info.image_width, info.image_height,
                    ((info.image_width + 7) / 8) * double((info.image_height + 7) / 8) / 8.0,
                    input.bytes);
  check_declared(info.image_width, info.image_height, channels, limits);
  std::vector<unsigned char> profile;
  if (colour && !read_jpeg_icc_profile(reader, profile)) throw_jpeg_error(input.name, reader);
  // The profile is opened before the pixels are decoded, so that a profile refused costs no time.
  std::unique_ptr<IccColour> icc;
  if (!profile.empty()) icc = std::make_unique<IccColour>(profile, channels, input.name);

  // jpeg_finish_decompress frees the saved markers.
  const int orientation = exif_orientation(info);
  const std::size_t row_bytes = std::size_t{info.image_width} * channels;
  std::vector<unsigned char> samples(row_bytes * info.image_height);
  if (!read_jpeg_samples(reader, samples.data(), row_bytes)) throw_jpeg_error(input.name, reader);
  if (reader.errors.truncated)
    throw Error(ErrorCode::format,
                input.name + " ends before its last pixel; the JPEG is truncated, export it again");

  return oriented(
      image_of_bytes(samples, static_cast<int>(info.image_width),
                     static_cast<int>(info.image_height), channels, icc.get(), "JPEG", colour),
      orientation);
}

}  // namespace stochtex
