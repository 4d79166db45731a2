// WebP through libwebp (still images, lossy or lossless, with or without alpha), its ICC profile
// through libwebpdemux.

#include <webp/decode.h>
#include <webp/demux.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "io/decoding.hpp"
#include "stochtex/error.hpp"

namespace stochtex {

bool is_webp(std::span<const unsigned char> first) {
  return first.size() >= 12 && std::equal(first.begin(), first.begin() + 4, "RIFF") &&
         std::equal(first.begin() + 8, first.begin() + 12, "WEBP");
}

ImageF read_webp(const Input& input, const ImageReadLimits& limits, ImageColour* colour) {
  // Lossless WebP codes a pixel in at most about its 4 bytes; metadata (ICC, EXIF, XMP) in the
  // rest of 64 MiB.
  const std::vector<unsigned char> bytes =
      read_all(input, 4.5 * static_cast<double>(limits.max_pixels) + double(64 << 20));
  const auto corrupt = [&](const std::string& problem) {
    return Error(ErrorCode::format, input.name + " is not a readable WebP image (" + problem +
                                        "); it is truncated or corrupt, export it again");
  };
  WebPBitstreamFeatures features;
  if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK)
    throw corrupt("libwebp cannot read its header");
  if (features.has_animation)
    throw Error(ErrorCode::format, input.name +
                                       " is an animated WebP, which stochtex does not read; "
                                       "export one frame as a still image");
  check_size(input.name, features.width, features.height, limits);
  const int channels = features.has_alpha ? 4 : 3;
  check_declared(features.width, features.height, channels, limits);

  // The colour is resolved before the pixels are decoded, so that a profile refused costs no time.
  std::unique_ptr<IccColour> icc;
  if (colour) {
    const WebPData data = {bytes.data(), bytes.size()};
    const std::unique_ptr<WebPDemuxer, void (*)(WebPDemuxer*)> demuxer(WebPDemux(&data),
                                                                       WebPDemuxDelete);
    WebPChunkIterator chunk;
    if (demuxer && (WebPDemuxGetI(demuxer.get(), WEBP_FF_FORMAT_FLAGS) & ICCP_FLAG) &&
        WebPDemuxGetChunk(demuxer.get(), "ICCP", 1, &chunk)) {
      const std::span<const unsigned char> profile(chunk.chunk.bytes, chunk.chunk.size);
      WebPDemuxReleaseChunkIterator(&chunk);
      icc = std::make_unique<IccColour>(profile, channels, input.name);
    }
  }

  const std::size_t stride = std::size_t(features.width) * channels;
  std::vector<unsigned char> samples(stride * features.height);
  const auto decode = features.has_alpha ? WebPDecodeRGBAInto : WebPDecodeRGBInto;
  if (!decode(bytes.data(), bytes.size(), samples.data(), samples.size(), static_cast<int>(stride)))
    throw corrupt("libwebp cannot decode its pixels");
  return image_of_bytes(samples, features.width, features.height, channels, icc.get(), "WebP",
                        colour);
}

}  // namespace stochtex
