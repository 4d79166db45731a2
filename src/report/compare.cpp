#include "report/compare.hpp"

#include <cmath>

#include "report/measures.hpp"
#include "stochtex/error.hpp"

namespace stochtex {

void add_checked(Comparison& comparison, ImageView<const float> exemplar,
                 const std::string& exemplar_name, ImageView<const float> image,
                 const std::string& image_name) {
  // The measures need crops of at least 2x2 pixels and finite values (NaN measures would print
  // as JSON nulls): anything else is refused with a sentence naming the file (§9).
  if (image.width < 2 || image.height < 2)
    throw Error(ErrorCode::invalid_input, "'" + image_name + "' is " + std::to_string(image.width) +
                                              "x" + std::to_string(image.height) +
                                              " pixels; compare needs at least 2x2 pixels");
  for (int y = 0; y < image.height; ++y)
    for (int i = 0; i < image.width * image.channels; ++i)
      if (!std::isfinite(image.row(y)[i]))
        throw Error(
            ErrorCode::invalid_input,
            "'" + image_name + "' contains NaN or infinite values; compare needs finite images");
  if (image.channels != exemplar.channels)
    throw Error(ErrorCode::invalid_input,
                "'" + image_name + "' has " + std::to_string(image.channels) +
                    " channels but the exemplar '" + exemplar_name + "' has " +
                    std::to_string(exemplar.channels) + "; compare images of the same kind");
  if (comparison.images() > 0 &&
      (image.width != comparison.width() || image.height != comparison.height()))
    throw Error(ErrorCode::invalid_input,
                "'" + image_name + "' is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " pixels but the first image is " +
                    std::to_string(comparison.width()) + "x" + std::to_string(comparison.height()) +
                    "; compare several renders of one size (one model, different seeds)");
  comparison.add(image);
}

nlohmann::ordered_json comparison_json(const ComparisonReport& report) {
  nlohmann::ordered_json doc{{"welch_crop", report.crop}};
  for (const Measure& measure : measures()) {
    if (measure.compare_label.empty() || (measure.several_renders && report.images < 2)) continue;
    doc[std::string(measure.key)] = report.image.*measure.value;
    if (!measure.adsn_key.empty()) doc[std::string(measure.adsn_key)] = report.adsn.*measure.value;
    if (!measure.floor_key.empty())
      doc[std::string(measure.floor_key)] = report.histogram_error_floor;
  }
  return doc;
}

}  // namespace stochtex
