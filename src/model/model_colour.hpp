#pragma once
// A model's colour (docs/design.md §14): the colour space of each channel, and how a render of a
// model of sRGB-encoded values becomes linear light. The model keeps the exemplar's encoded
// values, in which the methods fit it; each rendered value is the expectation of the decoded
// colour over the pixel's footprint. Tiling composes the decoding into its per-level T^-1 tables
// (methods/tiling/pyramid.cpp); the methods whose filtered value is a Gaussian's (texton, lrp,
// gabor, texton mixing) take the expectation here, after their evaluator:
//   out = D(v, r(w)),  D(m, s) = E[decode(m + s Z)], Z ~ N(0, 1),
// where v is the filtered value the evaluator returns and r(w) the deviation that a footprint of
// width w removed from the channel (removed_deviation). A point sample (w <= 1) is decoded
// exactly: D(v, 0) = decode(v).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/srgb.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

// The table of removed deviations: widths 2^(k / kRemovedStepsPerOctave), k = 0 to
// kRemovedSteps - 1 (1 to 2^20 exemplar pixels); wider footprints read the last step.
inline constexpr int kRemovedStepsPerOctave = 4;
inline constexpr int kRemovedSteps = 20 * kRemovedStepsPerOctave + 1;

struct ModelColour {
  // One per channel; empty: every channel is data (every model written before issue 36).
  std::vector<ColourSpace> spaces;
  // kRemovedSteps x channels, row-major: r(w) of each channel (measure_removed_deviation,
  // model_data.hpp); empty when no channel is decoded after evaluation (expects_any).
  std::vector<float> removed_deviation;

  // One per channel when `spaces` is not empty: the method's evaluator returns the channel as
  // linear light already (tiling's tables), so decode_expectation leaves it.
  std::vector<bool> in_tables;

  // Some channel is srgb: renders decode.
  bool decodes() const;
  ColourSpace space(int channel) const {
    return spaces.empty() ? ColourSpace::data : spaces[static_cast<std::size_t>(channel)];
  }
  // decode_expectation takes the expectation of channel `channel`.
  bool expects(int channel) const {
    return space(channel) == ColourSpace::srgb && !in_tables[static_cast<std::size_t>(channel)];
  }
  // Some channel is decoded by decode_expectation: the model needs removed_deviation.
  bool expects_any() const;
};

// A render's linear light back to sRGB-encoded values, in place: the colour channels
// (is_colour_channel) of `image`, as a PNG output holds them.
inline void encode_colour_channels(ImageView<float> image) noexcept {
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < image.channels; ++c)
        if (is_colour_channel(c, image.channels))
          image.at(x, y, c) = srgb_encode(image.at(x, y, c));
}

// What a render's values are for a model (or map) in `space`: linear light for srgb and linear
// (which a PNG output encodes), data as it is.
constexpr ColourSpace rendered_space(ColourSpace space) {
  return space == ColourSpace::data ? ColourSpace::data : ColourSpace::linear;
}

// The channels' colour spaces of an image of `channels` channels (1 to 4) in `space`: its alpha
// (2 or 4 channels) is data.
std::vector<ColourSpace> image_channel_spaces(ColourSpace space, int channels);
// The channels' colour spaces of a material's maps, in channel order.
std::vector<ColourSpace> map_channel_spaces(std::span<const MapInfo> maps);
// The colour space of a single image's colour channels (its first channel's).
ColourSpace image_colour_space(const ModelColour& colour);

// The table of D: means kExpectationMeanLow to kExpectationMeanHigh, deviations 0 to
// kExpectationDeviationHigh at the squares of kExpectationDeviationCells + 1 even steps of
// (deviation / kExpectationDeviationHigh)^(1/2): finest near 0, where D changes fastest (a mean
// near the decoding's knee at 0.04045 sees the power segment as soon as the deviation reaches it).
inline constexpr float kExpectationMeanLow = -1.0f;
inline constexpr float kExpectationMeanHigh = 2.0f;
inline constexpr int kExpectationMeanCells = 1024;
inline constexpr float kExpectationDeviationHigh = 1.5f;
inline constexpr int kExpectationDeviationCells = 128;
// Its (kExpectationDeviationCells + 1) x (kExpectationMeanCells + 1) values, row by deviation, made
// on first use (the GLSL twin's data, gl/colour.glsl).
const std::vector<float>& expectation_table();

// D(mean, deviation) = E[srgb_decode(mean + deviation Z)]: srgb_decode itself for deviation <= 0,
// else bilinear in a table of the means -1 to 2 and deviations 0 to 1.5 (clamped beyond), made
// once per process: the decoding's linear segment in closed form, its power by 48-point
// Gauss-Legendre quadrature.
float expected_decoded(float mean, float deviation) noexcept;

// r(w) of `channel` (linear in log2 w between the table's steps; 0 for w <= 1).
float removed_deviation(const ModelColour& colour, int channels, int channel,
                        double width) noexcept;

// `count` positions spread over 2^20 exemplar pixels by splitmix64 from `seed`: far enough apart
// that a model's values there are independent samples (removed deviations, tiling's calibration).
std::vector<Vec2d> spread_positions(std::size_t count, std::uint64_t seed);

// The width of a footprint for removed_deviation: the square root of the area it covers,
// |det(dpdx, dpdy)|^(1/2) (0 for a point sample).
double footprint_area_width(const Footprint& footprint) noexcept;

// The evaluator's values -> linear light, in place: each srgb channel of the first `count` pixels
// of `out` (row-major) becomes D(v, r(w)), w = width_of(i) the width of pixel i's footprint (0 for
// a point sample, decode(v)). Linear and data channels are left as they are. Neighbouring pixels
// of one width (a grid's) look r(w) up once.
template <typename WidthOf>
void decode_expectation_with(const ModelColour& colour, std::size_t count, WidthOf width_of,
                             ImageView<float> out) noexcept {
  if (!colour.expects_any()) return;
  const int channels = out.channels;
  std::array<float, kMaxChannels> removed{};
  double last_width = -1.0;
  for (std::size_t index = 0; index < count; ++index) {
    const double width = width_of(index);
    if (width != last_width) {
      for (int c = 0; c < channels; ++c)
        removed[static_cast<std::size_t>(c)] = removed_deviation(colour, channels, c, width);
      last_width = width;
    }
    const int x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const int y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    for (int c = 0; c < channels; ++c)
      if (colour.expects(c))
        out.at(x, y, c) = expected_decoded(out.at(x, y, c), removed[static_cast<std::size_t>(c)]);
  }
}

// The same for evaluate()'s footprints (footprint_area_width; empty: point samples).
inline void decode_expectation(const ModelColour& colour, std::size_t count,
                               std::span<const Footprint> footprints,
                               ImageView<float> out) noexcept {
  decode_expectation_with(
      colour, count,
      [&](std::size_t i) { return footprints.empty() ? 0.0 : footprint_area_width(footprints[i]); },
      out);
}

}  // namespace stochtex
