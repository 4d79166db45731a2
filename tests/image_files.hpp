#pragma once
// Small files of the formats stochtex reads but does not write (JPEG, TIFF, WebP, TGA), written by
// the formats' own libraries (TGA by hand: it is an 18-byte header and the pixels), for the image
// tests and the fuzz test's seeds, and an ICC profile for them to carry. Samples are the image's
// values times 255 (65535 for 16-bit TIFF), rounded.

// jpeglib.h uses size_t and FILE without including their headers.
#include <cstddef>
#include <cstdio>
// clang-format off
#include <jpeglib.h>
// clang-format on
#include <lcms2.h>
#include <tiffio.h>
#include <webp/encode.h>
#include <webp/mux.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "stochtex/image.hpp"

namespace stochtex::test_support {

using FileBytes = std::vector<unsigned char>;

// An RGB profile that is not sRGB (Adobe RGB (1998)'s primaries, a 2.2 gamma), saved, so that
// reading converts.
inline FileBytes wide_rgb_icc() {
  const cmsCIExyY d65 = {0.3127, 0.3290, 1.0};
  const cmsCIExyYTRIPLE primaries = {{0.64, 0.33, 1.0}, {0.21, 0.71, 1.0}, {0.15, 0.06, 1.0}};
  cmsToneCurve* gamma = cmsBuildGamma(nullptr, 2.2);
  cmsToneCurve* curves[3] = {gamma, gamma, gamma};
  cmsHPROFILE profile = cmsCreateRGBProfile(&d65, &primaries, curves);
  cmsFreeToneCurve(gamma);
  cmsUInt32Number size = 0;
  cmsSaveProfileToMem(profile, nullptr, &size);
  FileBytes icc(size);
  cmsSaveProfileToMem(profile, icc.data(), &size);
  cmsCloseProfile(profile);
  return icc;
}

inline std::vector<unsigned char> samples8(const ImageF& image) {
  std::vector<unsigned char> samples;
  for (float value : image.pixels())
    samples.push_back(static_cast<unsigned char>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255)));
  return samples;
}

struct JpegOptions {
  int quality = 100;
  bool progressive = false;
  bool cmyk = false;    // the image's 4 channels written as CMYK
  FileBytes icc{};      // written as APP2 markers when not empty
  int orientation = 0;  // an EXIF APP1 marker with this orientation when 1 to 8
};

// A minimal EXIF block (big-endian TIFF header, one IFD of one entry: the orientation).
inline FileBytes exif_orientation_block(int orientation) {
  return {'E',  'x',
          'i',  'f',
          0,    0,
          'M',  'M',
          0,    42,
          0,    0,
          0,    8,  // header, IFD at offset 8
          0,    1,  // one entry
          0x01, 0x12,
          0,    3,
          0,    0,
          0,    1,  // orientation, SHORT, 1 value
          0,    static_cast<unsigned char>(orientation),
          0,    0,  // its value
          0,    0,
          0,    0};  // no next IFD
}

inline FileBytes jpeg_file(const ImageF& image, const JpegOptions& options = {}) {
  jpeg_compress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long bytes = 0;
  jpeg_mem_dest(&info, &buffer, &bytes);
  info.image_width = static_cast<JDIMENSION>(image.width());
  info.image_height = static_cast<JDIMENSION>(image.height());
  info.input_components = image.channels();
  info.in_color_space = options.cmyk ? JCS_CMYK : image.channels() == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, options.quality, TRUE);
  // Full-resolution chroma, so that a smooth colour image comes back within a few levels.
  for (int c = 0; c < info.num_components; ++c)
    info.comp_info[c].h_samp_factor = info.comp_info[c].v_samp_factor = 1;
  if (options.progressive) jpeg_simple_progression(&info);
  jpeg_start_compress(&info, TRUE);
  if (options.orientation >= 1 && options.orientation <= 8) {
    const FileBytes exif = exif_orientation_block(options.orientation);
    jpeg_write_marker(&info, JPEG_APP0 + 1, exif.data(), static_cast<unsigned>(exif.size()));
  }
  if (!options.icc.empty())
    jpeg_write_icc_profile(&info, options.icc.data(), static_cast<unsigned>(options.icc.size()));
  std::vector<unsigned char> samples = samples8(image);
  const std::size_t row_bytes = std::size_t(image.width()) * image.channels();
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = samples.data() + info.next_scanline * row_bytes;
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  FileBytes file(buffer, buffer + bytes);
  std::free(buffer);
  return file;
}

struct TiffOptions {
  int bits = 8;  // 8, 16, or 32 (floats)
  std::uint16_t compression = COMPRESSION_NONE;
  bool tiled = false;  // 16x16 tiles, else strips of 2 rows
  FileBytes icc{};
};

// Written through a file in `folder`, which libtiff needs to seek.
inline FileBytes tiff_file(const ImageF& image, const std::filesystem::path& folder,
                           const TiffOptions& options = {}) {
  const std::filesystem::path path = folder / "written.tif";
  TIFF* tiff = TIFFOpen(path.c_str(), "w");
  if (!tiff) throw std::runtime_error("cannot write " + path.string());
  const int channels = image.channels();
  TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, image.width());
  TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, image.height());
  TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, channels);
  TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, options.bits);
  TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT,
               options.bits == 32 ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
  TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, channels <= 2 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB);
  TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tiff, TIFFTAG_COMPRESSION, options.compression);
  if (channels == 2 || channels == 4) {
    const std::uint16_t alpha = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(tiff, TIFFTAG_EXTRASAMPLES, 1, &alpha);
  }
  if (!options.icc.empty())
    TIFFSetField(tiff, TIFFTAG_ICCPROFILE, static_cast<std::uint32_t>(options.icc.size()),
                 options.icc.data());
  const std::size_t sample_bytes = static_cast<std::size_t>(options.bits / 8);
  const auto encode = [&](int x, int y, int c, unsigned char* to) {
    const float value = image.at(x, y, c);
    if (options.bits == 8) {
      *to = static_cast<unsigned char>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255));
    } else if (options.bits == 16) {
      const auto sample =
          static_cast<std::uint16_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 65535));
      std::memcpy(to, &sample, 2);
    } else {
      std::memcpy(to, &value, 4);
    }
  };
  const std::size_t pixel_bytes = sample_bytes * channels;
  if (options.tiled) {
    constexpr int kTile = 16;
    TIFFSetField(tiff, TIFFTAG_TILEWIDTH, kTile);
    TIFFSetField(tiff, TIFFTAG_TILELENGTH, kTile);
    std::vector<unsigned char> tile(kTile * kTile * pixel_bytes);
    for (int y0 = 0; y0 < image.height(); y0 += kTile)
      for (int x0 = 0; x0 < image.width(); x0 += kTile) {
        std::fill(tile.begin(), tile.end(), 0);
        for (int y = y0; y < std::min(y0 + kTile, image.height()); ++y)
          for (int x = x0; x < std::min(x0 + kTile, image.width()); ++x)
            for (int c = 0; c < channels; ++c)
              encode(x, y, c,
                     tile.data() + ((y - y0) * kTile + (x - x0)) * pixel_bytes + c * sample_bytes);
        TIFFWriteTile(tiff, tile.data(), static_cast<std::uint32_t>(x0),
                      static_cast<std::uint32_t>(y0), 0, 0);
      }
  } else {
    TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, 2);
    std::vector<unsigned char> line(image.width() * pixel_bytes);
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x)
        for (int c = 0; c < channels; ++c)
          encode(x, y, c, line.data() + x * pixel_bytes + c * sample_bytes);
      TIFFWriteScanline(tiff, line.data(), static_cast<std::uint32_t>(y), 0);
    }
  }
  TIFFClose(tiff);
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

// A WebP of 3 or 4 channels, lossless or lossy (quality 90), with an ICCP chunk when `icc` is not
// empty.
inline FileBytes webp_file(const ImageF& image, bool lossless, const FileBytes& icc = {}) {
  const std::vector<unsigned char> samples = samples8(image);
  const int stride = image.width() * image.channels();
  WebPConfig config;
  WebPConfigInit(&config);
  config.lossless = lossless ? 1 : 0;
  config.quality = 90.0f;
  config.exact = 1;  // keep the colour of transparent pixels
  WebPPicture picture;
  WebPPictureInit(&picture);
  picture.use_argb = 1;
  picture.width = image.width();
  picture.height = image.height();
  if (image.channels() == 4)
    WebPPictureImportRGBA(&picture, samples.data(), stride);
  else
    WebPPictureImportRGB(&picture, samples.data(), stride);
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  picture.writer = WebPMemoryWrite;
  picture.custom_ptr = &writer;
  if (!WebPEncode(&config, &picture)) throw std::runtime_error("WebPEncode failed");
  WebPPictureFree(&picture);
  FileBytes file(writer.mem, writer.mem + writer.size);
  WebPMemoryWriterClear(&writer);
  if (icc.empty()) return file;
  const WebPData image_data = {file.data(), file.size()};
  WebPMux* mux = WebPMuxCreate(&image_data, 1);
  const WebPData profile = {icc.data(), icc.size()};
  WebPMuxSetChunk(mux, "ICCP", &profile, 1);
  WebPData assembled;
  WebPDataInit(&assembled);
  WebPMuxAssemble(mux, &assembled);
  FileBytes with_profile(assembled.bytes, assembled.bytes + assembled.size);
  WebPDataClear(&assembled);
  WebPMuxDelete(mux);
  return with_profile;
}

// A true-colour (3 or 4 channels, BGR(A)) or grey TGA, top row first, raw or run-length encoded
// (one raw packet of up to 128 pixels after another).
inline FileBytes tga_file(const ImageF& image, bool run_length) {
  const int channels = image.channels();
  const bool grey = channels == 1;
  const unsigned char type = static_cast<unsigned char>((grey ? 3 : 2) + (run_length ? 8 : 0));
  FileBytes file = {0,
                    0,
                    type,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    static_cast<unsigned char>(image.width()),
                    static_cast<unsigned char>(image.width() >> 8),
                    static_cast<unsigned char>(image.height()),
                    static_cast<unsigned char>(image.height() >> 8),
                    static_cast<unsigned char>(8 * channels),
                    static_cast<unsigned char>(0x20 | (channels == 4 ? 8 : 0))};  // top first
  const std::vector<unsigned char> samples = samples8(image);
  const int pixels = image.width() * image.height();
  for (int first = 0; first < pixels; first += 128) {
    const int count = std::min(128, pixels - first);
    if (run_length) file.push_back(static_cast<unsigned char>(count - 1));
    for (int p = first; p < first + count; ++p) {
      const unsigned char* s = samples.data() + std::size_t(p) * channels;
      if (grey) {
        file.push_back(s[0]);
      } else {
        file.insert(file.end(), {s[2], s[1], s[0]});
        if (channels == 4) file.push_back(s[3]);
      }
    }
  }
  return file;
}

}  // namespace stochtex::test_support
