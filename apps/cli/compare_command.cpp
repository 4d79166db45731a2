// `stochtex compare EXEMPLAR IMAGE`: the quality measures of docs/design.md §8 (the rows of
// report/measures.hpp that have a compare label), beside an ADSN sample's and the exemplar's
// floor where the measure has them.

#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "report/compare.hpp"
#include "report/measures.hpp"

namespace stochtex::cli {
namespace {

void print_text(const ComparisonReport& report) {
  fmt::print("{:<28}{:>12}{:>12}{:>12}\n", "measure", "image", "ADSN", "floor");
  for (const Measure& measure : measures()) {
    if (measure.compare_label.empty()) continue;
    std::string line =
        fmt::format("{:<28}{:>12.4f}", measure.compare_label, report.image.*measure.value);
    if (!measure.adsn_key.empty()) {
      line += fmt::format("{:>12.4f}", report.adsn.*measure.value);
      line += measure.floor_key.empty() ? fmt::format("{:>12}", "")
                                        : fmt::format("{:>12.4f}", report.histogram_error_floor);
    }
    fmt::print("{}\n", line);
  }
}

nlohmann::ordered_json json(const ComparisonReport& report, const std::string& exemplar,
                            const std::string& image) {
  nlohmann::ordered_json doc{{"exemplar", exemplar}, {"image", image}};
  doc.update(comparison_json(report));
  return doc;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  struct Options {
    std::string exemplar;
    std::string image;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("compare", "quality of IMAGE against EXEMPLAR");
  command->add_option("EXEMPLAR", options->exemplar, "the exemplar")->required();
  command->add_option("IMAGE", options->image, "the synthesised image")->required();
  command->add_flag("--json", options->json, "print one JSON document");
  return {command, [options] {
            const ImageF exemplar = load_exemplar(options->exemplar);
            const ImageF image = read_image(options->image);
            const ComparisonReport report =
                compare_checked(exemplar.view(), options->exemplar, image.view(), options->image);
            if (options->json)
              fmt::print("{}\n", json(report, options->exemplar, options->image).dump(2));
            else
              print_text(report);
            return 0;
          }};
}

}  // namespace stochtex::cli
