// Running independent tasks on a few threads. Callers keep results deterministic by writing each
// task's result to its own slot and combining them in index order afterwards.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace rangefill {

/// Runs task(i) for i in [0, count) on `threads` threads (at most `count`; 1 runs them in order on
/// the calling thread). Tasks are handed out in increasing i.
template <typename Task>
void parallel_for(int count, int threads, Task task) {
  threads = std::clamp(threads, 1, std::max(1, count));
  if (threads == 1) {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&] {
      for (int i = next++; i < count; i = next++) task(i);
    });
  }
  for (std::thread& worker : workers) worker.join();
}

}  // namespace rangefill
