// `stochtex compare EXEMPLAR IMAGE...`: the quality measures of docs/design.md §8 (the rows of
// report/measures.hpp that have a compare label), beside ADSN samples' and the exemplar's floor
// where the measure has them. Several images (renders of one model with different seeds) give the
// mean of each measure and the error of their averaged spectrum (bias apart from shot noise).

#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "progress.hpp"
#include "report/compare.hpp"
#include "report/measures.hpp"

namespace stochtex::cli {
namespace {

void print_text(const ComparisonReport& report) {
  if (report.images > 1)
    fmt::print("{} images, each beside its own ADSN sample: the means of their measures\n",
               report.images);
  fmt::print("{:<28}{:>12}{:>12}{:>12}\n", "measure", report.images > 1 ? "images" : "image",
             "ADSN", "floor");
  for (const Measure& measure : measures()) {
    if (measure.compare_label.empty() || (measure.several_renders && report.images < 2)) continue;
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
                            const std::vector<std::string>& images) {
  nlohmann::ordered_json doc{{"exemplar", exemplar}};
  if (images.size() == 1)
    doc["image"] = images.front();
  else
    doc["images"] = images;
  doc.update(comparison_json(report));
  return doc;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  struct Options {
    std::string exemplar;
    std::vector<std::string> images;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "compare",
      "quality of IMAGE against EXEMPLAR; several IMAGEs (one model, different seeds) also give "
      "the error of their averaged spectrum, which tells bias from shot noise");
  command->add_option("EXEMPLAR", options->exemplar, "the exemplar")->required();
  command->add_option("IMAGE", options->images, "the synthesised image(s), all of one size")
      ->required();
  command->add_flag("--json", options->json, "print one JSON document");
  return {command, [options] {
            // Each image's declared size against the budget of the measures, before decoding.
            const auto budget = [](std::uint64_t exemplar_pixels, int width, int height,
                                   int channels, const std::string& path) {
              check_memory_budget(
                  compare_peak_bytes(exemplar_pixels, static_cast<std::uint64_t>(width) * height,
                                     channels),
                  fmt::format("comparing the {}x{} image '{}'", width, height, path),
                  "compare smaller images");
            };
            const ImageF exemplar =
                load_exemplar(options->exemplar, [&](int width, int height, int channels) {
                  budget(0, width, height, channels, options->exemplar);
                });
            // The bar ends (its destructor) before the report is printed.
            const ComparisonReport report = [&] {
              Progress progress("compare");
              progress.message(fmt::format("measuring {} image(s) against {}...",
                                           options->images.size(), options->exemplar));
              Comparison comparison(exemplar.view());
              for (const std::string& path : options->images) {
                progress(static_cast<double>(comparison.images()) /
                         static_cast<double>(options->images.size()));
                ImageReadLimits limits;
                limits.check_declared = [&](int width, int height, int channels) {
                  budget(exemplar.pixel_count(), width, height,
                         std::max(channels, exemplar.channels()), path);
                };
                const ImageF image = read_image(path, limits);
                add_checked(comparison, exemplar.view(), options->exemplar, image.view(), path);
              }
              progress(1.0);
              return comparison.report();
            }();
            if (options->json)
              fmt::print("{}\n", json(report, options->exemplar, options->images).dump(2));
            else
              print_text(report);
            return 0;
          }};
}

}  // namespace stochtex::cli
