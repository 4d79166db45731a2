#include "core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace stochtex {

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                  const std::function<void(std::size_t)>& on_done) {
  const auto worker_count = static_cast<std::size_t>(
      std::min<std::size_t>(static_cast<std::size_t>(resolve_thread_count(threads)), count));
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  // The first exception, from a task or from on_done, stops the work: no task starts after it.
  const auto fail = [&] {
    std::lock_guard lock(failure_mutex);
    if (!failure) failure = std::current_exception();
    next = count;
  };
  const auto report_done = [&](std::size_t finished) {
    try {
      on_done(finished);
    } catch (...) {
      fail();
    }
  };
  auto work = [&](bool report) {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        fail();
      }
      const std::size_t finished = ++done;
      if (report && on_done) report_done(finished);
    }
  };
  std::vector<std::jthread> pool;
  for (std::size_t t = 1; t < worker_count; ++t) pool.emplace_back(work, false);
  work(true);
  pool.clear();
  if (on_done) report_done(done.load());
  if (failure) std::rethrow_exception(failure);
}

}  // namespace stochtex
