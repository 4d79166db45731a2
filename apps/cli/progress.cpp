#include "progress.hpp"

#include <fmt/core.h>
#include <unistd.h>

#include <cstdio>
#include <utility>

namespace stochtex::cli {
namespace {

bool progress_lines = false;

// A line in a log at most this often: enough to see a long step move, few enough to read.
constexpr std::chrono::seconds kLineInterval{2};

}  // namespace

void set_progress_lines(bool on) {
  progress_lines = on;
}

Progress::Progress(std::string label)
    : label_(std::move(label)),
      mode_(isatty(STDOUT_FILENO) && isatty(STDERR_FILENO) ? Mode::bar
            : progress_lines                               ? Mode::lines
                                                           : Mode::none),
      last_line_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  if (mode_ == Mode::bar && drawn_) std::fputc('\n', stderr);
}

void Progress::operator()(double fraction) {
  if (mode_ == Mode::none) return;
  const int percent = static_cast<int>(fraction * 100.0);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  if (mode_ == Mode::lines) {
    const auto now = std::chrono::steady_clock::now();
    if (percent < 100 && now - last_line_ < kLineInterval) return;
    last_line_ = now;
    fmt::print(stderr, "{}: {}%\n", label_, percent);
    return;
  }
  drawn_ = true;
  const int filled = percent * 30 / 100;
  fmt::print(stderr, "\r{} [{}{}] {:3d}%", label_,
             std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(30 - filled), ' '), percent);
  std::fflush(stderr);
}

void Progress::message(const std::string& text) const {
  if (mode_ != Mode::none) fmt::print(stderr, "{}\n", text);
}

}  // namespace stochtex::cli
