#pragma once
// A progress bar on stderr, shown only when stdout is a terminal (never in pipes, CI or --json).

#include <string>

namespace stochtex::cli {

class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void operator()(double fraction);
  void message(const std::string& text) const;

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  int last_percent_ = -1;
};

}  // namespace stochtex::cli
