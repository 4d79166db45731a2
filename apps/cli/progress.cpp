#include "progress.hpp"

#include <fmt/core.h>
#include <unistd.h>

#include <cstdio>
#include <utility>

namespace stochtex::cli {

Progress::Progress(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDOUT_FILENO) && isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (enabled_ && drawn_) std::fputc('\n', stderr);
}

void Progress::operator()(double fraction) {
  if (!enabled_) return;
  const int percent = static_cast<int>(fraction * 100.0);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  drawn_ = true;
  const int filled = percent * 30 / 100;
  fmt::print(stderr, "\r{} [{}{}] {:3d}%", label_,
             std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(30 - filled), ' '), percent);
  std::fflush(stderr);
}

void Progress::message(const std::string& text) const {
  if (enabled_) fmt::print(stderr, "{}\n", text);
}

}  // namespace stochtex::cli
