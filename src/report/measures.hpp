#pragma once
// The one table of the quality measures (docs/design.md §8) that `stochtex compare` and
// `stochtex report` show: every output (compare's text and --json, the report's HTML tables and
// report.json) iterates it, so a measure is named, explained and formatted in one row. The JSON
// keys are read by scripts (scripts/comparison_markdown.py) and must not change.

#include <span>
#include <string_view>

#include "metrics/metrics.hpp"

namespace stochtex {

struct Measure {
  std::string_view key;            // JSON key in compare --json and report.json
  std::string_view adsn_key;       // compare --json key of the ADSN sample's value; empty: none
  std::string_view floor_key;      // JSON key of the exemplar's floor (histogram_error_floor)
  std::string_view compare_label;  // the row of compare's text output; empty: not in compare
  std::string_view title;          // the report's column header and section title
  std::string_view help;           // the report's definition of the measure
  std::string_view format;         // {fmt} format of the report's cells
  double Quality::*value;          // where the measured number is
  bool method_only;                // no value for the Gaussian version (timings)
  bool several_renders;            // a measure of renders with several seeds together: compare
                                   // shows it only when given several images
};

// The measures in the order of every output.
std::span<const Measure> measures();

}  // namespace stochtex
