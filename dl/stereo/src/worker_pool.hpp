#pragma once
// Private to dl_stereo: a small persistent pool of helper threads for data-parallel loops.
//
// Run(n, fn) executes fn(task, worker) for every task in [0, n) and returns when all are done.
// The calling thread works too (worker 0); helpers (workers 1..) take tasks from a shared
// ticket. Run never waits for a helper that has not taken a task, so a helper that is slow to be
// scheduled on a busy machine costs nothing; only tasks already taken are waited for. The ticket
// holds (job generation << 32 | next task), so a helper that wakes after its job has ended
// cannot take a task of a later job. Like OpenCV's pool, threads poll briefly before sleeping
// (pausing, then yielding the CPU), so back-to-back jobs of one frame rarely pay a wake-up.
// One Run at a time (not reentrant, not for concurrent callers).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rover::dl::stereo::internal {

class WorkerPool {
 public:
  using Task = std::function<void(int task, int worker)>;

  /// Starts `helpers` threads (fewer if the system refuses to create them).
  explicit WorkerPool(int helpers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Workers that may run tasks: the caller plus the started helpers.
  int workers() const { return 1 + static_cast<int>(threads_.size()); }

  void Run(int num_tasks, const Task& fn);

 private:
  void Loop(int id);
  // Runs the tasks of job `generation` that are left; returns when none is left to take.
  void Work(std::uint32_t generation, int id);

  std::mutex mutex_;
  std::condition_variable wake_;  // helpers: a new job or stop
  std::condition_variable idle_;  // caller: all tasks done
  std::vector<std::thread> threads_;
  bool stop_ = false;               // guarded by mutex_
  std::uint32_t sleep_gen_ = 0;     // guarded by mutex_: generation sleeping helpers look for
  std::atomic<bool> stopping_{false};
  std::atomic<const Task*> fn_{nullptr};
  std::atomic<int> num_tasks_{0};
  std::atomic<std::uint64_t> ticket_{0};
  std::atomic<int> done_{0};
  std::uint32_t generation_ = 0;  // caller only
};

}  // namespace rover::dl::stereo::internal
