#pragma once
// What the values of an image or a model are (docs/design.md §14, "Colour"): the colour space a
// file declares or a user gives (`--colour-space`), kept in the model, and what a render's values
// and an output file's values mean.

#include <optional>
#include <string_view>

namespace stochtex {

// data:   numbers that are not colour (heights, slopes, roughness, ambient occlusion): filtered as
//         they are, never decoded or encoded, written as they are.
// linear: linear light (OpenEXR, PFM, a PNG that says so): filtered as it is; a PNG output
//         encodes it with the sRGB transfer function.
// srgb:   values encoded with the sRGB transfer function (IEC 61966-2-1), an ordinary photo: a
//         model keeps them, renders linear light (each filtered value the expectation of the
//         decoded colour over its footprint), and a PNG output encodes it again.
// An alpha channel (the last of 2 or 4) is data whatever its image's colour space.
enum class ColourSpace { data, linear, srgb };

// "data", "linear" or "srgb", as `--colour-space`, model files and `stochtex info` write them.
std::string_view colour_space_name(ColourSpace space);
// The colour space named `name` (colour_space_name's names), or none.
std::optional<ColourSpace> colour_space_from_name(std::string_view name);

// Whether channel `channel` of an image of `channels` channels (1 to 4) carries its colour: every
// channel but the alpha of a grey + alpha or RGBA image.
constexpr bool is_colour_channel(int channel, int channels) {
  return !((channels == 2 || channels == 4) && channel == channels - 1);
}

}  // namespace stochtex
