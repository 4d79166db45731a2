#include "core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace stochtex::parallel_test {
namespace {

// A cancelled progress hook (Ctrl-C in the Python module) stops the work like a failed task:
// the tasks already started finish, no other starts.
TEST(ParallelFor, ExceptionFromOnDoneStopsTheWork) {
  for (const int threads : {1, 2, 4}) {
    std::atomic<int> started{0};
    const auto task = [&](std::size_t) {
      ++started;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    };
    const auto on_done = [](std::size_t done) {
      if (done >= 2) throw std::runtime_error("stop");
    };
    EXPECT_THROW(parallel_for(1000, threads, task, on_done), std::runtime_error);
    EXPECT_LT(started.load(), 500) << threads << " threads";  // (1000 before the fix)
  }
}

TEST(ParallelFor, ExceptionFromATaskStopsTheWork) {
  std::atomic<int> started{0};
  const auto task = [&](std::size_t i) {
    ++started;
    if (i == 0) throw std::runtime_error("fail");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  EXPECT_THROW(parallel_for(1000, 2, task), std::runtime_error);
  EXPECT_LT(started.load(), 500);
}

TEST(ParallelFor, RunsEveryTaskOnceAndReportsTheTotal) {
  std::vector<std::atomic<int>> runs(100);
  std::size_t last = 0;
  parallel_for(
      runs.size(), 3, [&](std::size_t i) { ++runs[i]; }, [&](std::size_t done) { last = done; });
  for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
  EXPECT_EQ(last, runs.size());
}

}  // namespace
}  // namespace stochtex::parallel_test
