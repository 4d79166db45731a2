#pragma once
// The part of a photo a method analyses (docs/design.md §9): a crop, then a downscale, chosen by
// the user or, for an image larger than the method analyses by default, by its registry row's
// analysis side. The downscale averages linear light, so that a photo's colour survives it.

#include <optional>
#include <string>

#include "stochtex/colour.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

// A rectangle of an image, as ImageMagick's geometry writes it: WIDTHxHEIGHT+X+Y.
struct Crop {
  int width = 0, height = 0, x = 0, y = 0;
};

// "512x512+100+40" (the offsets may be left out: +0+0); std::invalid_argument of one sentence
// naming `option` for any other text.
Crop parse_crop(const std::string& text, const std::string& option);

struct ExemplarRegion {
  std::optional<Crop> crop{};
  // > 0: the factor the (cropped) image is scaled by, at most 1; 0: scaled to `max_side` on its
  // longer side when it is longer, else as it is.
  double scale = 0.0;
};

struct RegionSize {
  int width = 0, height = 0;
  double scale = 1.0;  // the factor applied after the crop
};

// The size analysed of a width x height image. std::invalid_argument (one sentence naming `name`)
// for a crop that is not inside the image or a scale outside (0, 1].
RegionSize region_size(int width, int height, const ExemplarRegion& region, int max_side,
                       const std::string& name);

// The region of `image` (values in `space`): cropped, then resampled (Mitchell filter, stb_image_
// resize, reflected at the borders) in linear light where `space` is srgb. `note` gets the start of
// a sentence when the image was scaled without the user asking (ExemplarRegion::scale 0), saying
// by how much and why, for the front end to end with how its user chooses; empty otherwise.
ImageF exemplar_region(ImageF image, ColourSpace space, const ExemplarRegion& region, int max_side,
                       const std::string& name, const std::string& method, std::string* note);

}  // namespace stochtex
