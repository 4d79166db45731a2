#pragma once
// Progress on stderr: a bar when stdout and stderr are terminals; with `stochtex --progress` and
// stderr not a terminal (a log, CI), a line "analyse: 40%" at most every 2 seconds and at the end;
// otherwise nothing (pipes, --json).

#include <chrono>
#include <string>

namespace stochtex::cli {

// `stochtex --progress`: progress lines where no bar can be drawn.
void set_progress_lines(bool on);

class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void operator()(double fraction);
  void message(const std::string& text) const;

 private:
  enum class Mode { none, bar, lines };
  std::string label_;
  Mode mode_;
  bool drawn_ = false;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point last_line_;
};

}  // namespace stochtex::cli
