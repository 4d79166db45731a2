#include "io/exemplar_region.hpp"

#include <stb/stb_image_resize.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/srgb.hpp"
#include "stochtex/colour.hpp"

namespace stochtex {
namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

std::string crop_text(const Crop& crop) {
  return size_text(crop.width, crop.height) + "+" + std::to_string(crop.x) + "+" +
         std::to_string(crop.y);
}

// A factor as a message writes it: 4 significant digits.
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace

Crop parse_crop(const std::string& text, const std::string& option) {
  static const std::regex kGeometry(R"((\d{1,6})x(\d{1,6})(?:\+(\d{1,6})\+(\d{1,6}))?)");
  std::smatch match;
  if (!std::regex_match(text, match, kGeometry) || std::stoi(match[1]) < 1 ||
      std::stoi(match[2]) < 1)
    throw std::invalid_argument(option + " '" + text +
                                "' is not a crop; write WIDTHxHEIGHT+X+Y, as 512x512+100+40");
  return {std::stoi(match[1]), std::stoi(match[2]), match[3].matched ? std::stoi(match[3]) : 0,
          match[4].matched ? std::stoi(match[4]) : 0};
}

RegionSize region_size(int width, int height, const ExemplarRegion& region, int max_side,
                       const std::string& name) {
  if (region.crop) {
    const Crop& crop = *region.crop;
    if (crop.x + crop.width > width || crop.y + crop.height > height)
      throw std::invalid_argument("the crop " + crop_text(crop) + " is not inside " + name +
                                  ", which is " + size_text(width, height) +
                                  " pixels; choose one inside it");
    width = crop.width;
    height = crop.height;
  }
  if (!(region.scale >= 0.0 && region.scale <= 1.0))
    throw std::invalid_argument("--scale-input " + number_text(region.scale) +
                                " is not a downscale; give a factor above 0 and at most 1");
  const int longer = std::max(width, height);
  const double scale = region.scale > 0.0  ? region.scale
                       : longer > max_side ? static_cast<double>(max_side) / longer
                                           : 1.0;
  if (scale == 1.0) return {width, height, 1.0};
  return {std::max(1, static_cast<int>(std::lround(width * scale))),
          std::max(1, static_cast<int>(std::lround(height * scale))), scale};
}

ImageF exemplar_region(ImageF image, ColourSpace space, const ExemplarRegion& region, int max_side,
                       const std::string& name, const std::string& method, std::string* note) {
  if (note) note->clear();
  const int full_width = image.width(), full_height = image.height();
  const RegionSize size = region_size(full_width, full_height, region, max_side, name);
  if (region.crop) {
    const Crop& crop = *region.crop;
    ImageF cropped(crop.width, crop.height, image.channels());
    const ImageView<const float> from = image.view().sub(crop.x, crop.y, crop.width, crop.height);
    for (int y = 0; y < crop.height; ++y)
      std::copy_n(from.row(y), cropped.view().row_stride, cropped.view().row(y));
    image = std::move(cropped);
  }
  if (size.scale == 1.0) return image;

  const int channels = image.channels();
  const bool decode = space == ColourSpace::srgb;
  const auto is_colour = [&](std::size_t i) {
    return is_colour_channel(static_cast<int>(i % channels), channels);
  };
  if (decode) {
    std::span<float> values = image.pixels();
    for (std::size_t i = 0; i < values.size(); ++i)
      if (is_colour(i)) values[i] = srgb_decode(values[i]);
  }
  // The Mitchell filter's negative lobes overshoot near edges: each channel is kept within the
  // range it had.
  std::vector<float> lowest(channels, INFINITY), highest(channels, -INFINITY);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    const float value = image.pixels()[i];
    lowest[i % channels] = std::min(lowest[i % channels], value);
    highest[i % channels] = std::max(highest[i % channels], value);
  }
  ImageF scaled(size.width, size.height, channels);
  if (!stbir_resize_float_generic(image.pixels().data(), image.width(), image.height(),
                                  static_cast<int>(image.view().row_stride * sizeof(float)),
                                  scaled.pixels().data(), size.width, size.height,
                                  static_cast<int>(scaled.view().row_stride * sizeof(float)),
                                  channels, STBIR_ALPHA_CHANNEL_NONE, 0, STBIR_EDGE_REFLECT,
                                  STBIR_FILTER_MITCHELL, STBIR_COLORSPACE_LINEAR, nullptr))
    throw std::bad_alloc();
  std::span<float> values = scaled.pixels();
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = std::clamp(values[i], lowest[i % channels], highest[i % channels]);
    if (decode && is_colour(i)) values[i] = srgb_encode(values[i]);
  }
  if (note && region.scale == 0.0)
    *note = name + " is " + size_text(full_width, full_height) + " pixels" +
            (region.crop ? " (" + crop_text(*region.crop) + " of it cropped)" : "") +
            ", more than " + method + " analyses by default (" + std::to_string(max_side) +
            " on the longer side): it is analysed downscaled to " +
            size_text(size.width, size.height) + " (a factor of " + number_text(size.scale) + ")";
  return scaled;
}

}  // namespace stochtex
