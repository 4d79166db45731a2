#pragma once
// What `stochtex report` writes once everything is measured: the HTML pages (report_html.cpp) and
// the JSON summary (report_json.cpp). Both iterate the measure table (report/measures.hpp).

#include <string>
#include <vector>

#include "report/comparison.hpp"
#include "report/measure_all.hpp"

namespace stochtex::cli {

// One finished report run.
struct ReportRun {
  const std::vector<ExemplarResults>& exemplars;
  const std::vector<std::string>& methods;
  const ReportSettings& settings;
  int threads = 0;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
  int failures = 0;
};

// DIR/NAME.html: one exemplar's pictures and measures.
std::string exemplar_page(const ExemplarResults& exemplar, const ReportSettings& settings);
// DIR/index.html: the gallery and one table per measure.
std::string index_page(const ReportRun& run);
// DIR/report.json (and stdout with --json): the numbers, indented by 2, without a final newline.
std::string summary_json(const ReportRun& run);

}  // namespace stochtex::cli
