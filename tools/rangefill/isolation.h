// Jobs run each in a child process of its own, so that one that crashes, hangs or runs out of time
// is recorded and the others go on (rangefill bench: one method on one hole per job).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace rangefill::cli {

/// How a job run in a child process ended.
struct ChildResult {
  bool completed = false;  // the child returned its output and exited with 0
  std::string output;      // what the job returned (when completed)
  std::string failure;     // else why not: "timed out after 30 s", "crashed (signal 11: ...)", ...
  double seconds = 0;      // wall time from fork to the end
};

/// Runs job(i) for every i in [0, count), each in a forked child process, at most `parallel` at
/// once, started in increasing i; a child still running `timeout` seconds after it started (0:
/// no limit) is killed. The output of job(i) comes back through a pipe; a job that throws exits
/// with 1. Children die with the parent (an interrupt ends them too). `done(i, result)` runs in the
/// parent as each job ends, in the order they end. Returns the results by index. Throws
/// std::system_error when a pipe or process cannot be made.
std::vector<ChildResult> run_in_children(int count, int parallel, double timeout,
                                         const std::function<std::string(int)>& job,
                                         const std::function<void(int, const ChildResult&)>& done);

}  // namespace rangefill::cli
