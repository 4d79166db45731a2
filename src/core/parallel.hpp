#pragma once
// Work distribution. Results never depend on the thread count: each task writes its own outputs.

#include <cstddef>
#include <functional>

namespace stochtex {

int resolve_thread_count(int requested);

// Runs task(i) for i in [0, count) on `threads` threads (the caller's thread included); tasks are
// taken in increasing order. `on_done(done)` is called from the calling thread as tasks complete.
// The first exception thrown by a task or by on_done stops the work (tasks already started finish,
// no other starts) and is rethrown once every thread has stopped.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                  const std::function<void(std::size_t)>& on_done = {});

}  // namespace stochtex
