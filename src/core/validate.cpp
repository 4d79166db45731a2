// Exemplar validation (docs/design.md §9): every unusable exemplar gets one sentence that names
// it.

#include <cmath>
#include <string>

#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {

void validate_exemplar(ImageView<const float> exemplar, const std::string& source_name,
                       int max_channels) {
  const std::string name = "'" + source_name + "'";
  if (exemplar.channels < 1 || exemplar.channels > max_channels)
    throw Error(ErrorCode::invalid_input, name + " has " + std::to_string(exemplar.channels) +
                                              " channels; an exemplar needs 1 to " +
                                              std::to_string(max_channels));
  if (exemplar.width < 2 || exemplar.height < 2)
    throw Error(ErrorCode::invalid_input,
                name + " is " + std::to_string(exemplar.width) + "x" +
                    std::to_string(exemplar.height) +
                    " pixels; an exemplar needs at least 2x2 pixels (64x64 or more recommended)");
  bool varies = false;
  for (int y = 0; y < exemplar.height; ++y)
    for (int x = 0; x < exemplar.width; ++x)
      for (int c = 0; c < exemplar.channels; ++c) {
        const float value = exemplar.at(x, y, c);
        if (!std::isfinite(value))
          throw Error(ErrorCode::invalid_input,
                      name + " contains a NaN or infinite value at pixel (" + std::to_string(x) +
                          ", " + std::to_string(y) + "); replace it with a finite value");
        if (std::abs(value) > kMaxExemplarValue)
          throw Error(ErrorCode::invalid_input,
                      name + " has a value beyond +-1e6 (the largest exemplar value) at pixel (" +
                          std::to_string(x) + ", " + std::to_string(y) + "); rescale the image");
        varies = varies || value != exemplar.at(0, 0, c);
      }
  if (!varies)
    throw Error(ErrorCode::invalid_input,
                name + " is constant (zero variance): there is no texture to analyse");
}

}  // namespace stochtex
