#pragma once
// `stochtex report EXEMPLAR... -o DIR`: every method on every exemplar, side by side, as an HTML
// page that opens offline (DIR/index.html, one page per exemplar, PNG pictures) and, with --json,
// one JSON summary on stdout (also written to DIR/report.json).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace stochtex::cli {

struct ReportOptions {
  std::vector<std::string> exemplars;
  std::string output;
  std::string size = "256x256";
  std::uint32_t seed = 1;
  std::vector<std::string> methods;  // empty: all
  int threads = 0;
  int thumbnail = 0;  // largest side of DIR/thumbnails/*.png; 0: none
  bool json = false;
};

// Adds the subcommand and its options to `app`, storing them into `options`.
CLI::App* add_report_command(CLI::App& app, ReportOptions& options);

// Runs the report; returns the exit code (0, or 1 when some method failed on some exemplar: the
// report is still written and shows which). Throws std::invalid_argument for usage errors and
// stochtex::Error for unreadable exemplars and unwritable outputs, before any long work.
int run_report(const ReportOptions& options);

}  // namespace stochtex::cli
