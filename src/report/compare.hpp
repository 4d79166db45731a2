#pragma once
// `stochtex compare` as a library call, shared by the CLI and the Python module: each synthesis
// is checked, measured with a Comparison, and the numbers laid out as compare --json's keys.

#include <nlohmann/json.hpp>
#include <string>

#include "metrics/metrics.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

// Throws Error(invalid_input), with a sentence naming `image_name` or `exemplar_name`, when the
// image is below 2x2 pixels, holds NaN or infinite values, has another channel count than the
// exemplar (the exemplar itself is checked by validate_exemplar) or another size than the images
// added before; then adds it to `comparison`.
void add_checked(Comparison& comparison, ImageView<const float> exemplar,
                 const std::string& exemplar_name, ImageView<const float> image,
                 const std::string& image_name);

// welch_crop, then every measure of compare
// (report/measures.hpp) with its ADSN value and floor where it has them: the numbers of compare
// --json, under its keys. The measures of several renders together are left out for one image.
nlohmann::ordered_json comparison_json(const ComparisonReport& report);

}  // namespace stochtex
