// Running independent tasks on a few threads. Callers keep results deterministic by writing each
// task's result to its own slot and combining them in index order afterwards.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rangefill {

/// The threads the hardware runs at once (at least 1): the default of the options that fill holes
/// in parallel, whose results do not depend on it.
inline int hardware_threads() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Runs task(i) for i in [0, count) on `threads` threads (at most `count`; 1 runs them in order on
/// the calling thread). Tasks are handed out in increasing i. When tasks throw, no task is started
/// after the first throw, the running ones finish, and the exception of the lowest i among those
/// that threw is rethrown on the calling thread (the same one at any thread count when every task
/// before it ran).
template <typename Task>
void parallel_for(int count, int threads, Task task) {
  threads = std::clamp(threads, 1, std::max(1, count));
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  int failed_index = count;
  std::exception_ptr failure;
  auto work = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (i < failed_index) {
          failed_index = i;
          failure = std::current_exception();
        }
        failed = true;
      }
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();  // the calling thread is a worker too
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
}

/// A pass over the elements of a mesh split into this many ranges (range_begin), whatever the
/// thread count, so that results joined in range order are the same at any thread count.
inline constexpr int kMeshRanges = 32;

/// The threads for a pass over `elements` elements of a mesh: one below 100 000, where starting
/// threads costs more than it saves, else hardware_threads().
inline int mesh_pass_threads(long long elements) {
  return elements >= 100000 ? hardware_threads() : 1;
}

/// The first element of range r of [0, count) split into kMeshRanges ranges of about equal size;
/// range r is [range_begin(count, r), range_begin(count, r + 1)).
inline int range_begin(int count, int r) {
  return static_cast<int>(static_cast<long long>(count) * r / kMeshRanges);
}

}  // namespace rangefill
