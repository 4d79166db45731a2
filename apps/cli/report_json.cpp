#include <nlohmann/json.hpp>

#include "report/measures.hpp"
#include "report_output.hpp"

namespace stochtex::cli {

std::string summary_json(const ReportRun& run) {
  auto exemplars = nlohmann::ordered_json::array();
  for (const ExemplarResults& exemplar : run.exemplars) {
    auto syntheses = nlohmann::ordered_json::array();
    for (const Outcome& outcome : exemplar.outcomes) {
      nlohmann::ordered_json item{{"name", outcome.name}};
      if (outcome.error) {
        item["error"] = *outcome.error;
      } else {
        for (const Measure& measure : measures())
          if (!measure.method_only || outcome.name != "gaussian")
            item[std::string(measure.key)] = outcome.quality.*measure.value;
      }
      syntheses.push_back(item);
    }
    nlohmann::ordered_json item{{"name", exemplar.name},
                                {"file", exemplar.path},
                                {"width", exemplar.image.width()},
                                {"height", exemplar.image.height()},
                                {"channels", exemplar.image.channels()},
                                {"welch_crop", exemplar.crop}};
    for (const Measure& measure : measures())
      if (!measure.floor_key.empty())
        item[std::string(measure.floor_key)] = exemplar.histogram_error_floor;
    const MethodChoice& choice = exemplar.choice;
    item["auto"] = {{"method", choice.method},
                    {"reason", choice.reason},
                    {"band_kurtosis", choice.band_kurtosis},
                    {"band_scale", choice.band_scale},
                    {"peak_fraction", choice.peak_fraction},
                    {"wrap_step", choice.wrap_step}};
    item["page"] = exemplar.name + ".html";
    item["syntheses"] = syntheses;
    exemplars.push_back(item);
  }
  const ReportSettings& settings = run.settings;
  const nlohmann::ordered_json summary{{"settings",
                                        {{"width", settings.width},
                                         {"height", settings.height},
                                         {"seed", settings.seed},
                                         {"averaged_seeds", settings.averaged_seeds},
                                         {"methods", run.methods},
                                         {"threads", run.threads},
                                         {"stationarity_side", settings.stationarity_side},
                                         {"stationarity_step", settings.stationarity_step},
                                         {"stationarity_seeds", settings.stationarity_seeds},
                                         {"stationarity_block", settings.stationarity_block}}},
                                       {"wall_seconds", run.wall_seconds},
                                       {"cpu_seconds", run.cpu_seconds},
                                       {"failures", run.failures},
                                       {"exemplars", exemplars}};
  return summary.dump(2);
}

}  // namespace stochtex::cli
