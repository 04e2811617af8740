#include "worker_pool.hpp"

#include <exception>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace rover::dl::stereo::internal {
namespace {

// Polls before sleeping: the first kPausePolls with a CPU pause (~microseconds in total), the
// rest yielding the CPU, so that a spinning thread does not starve our other thread when both
// share one core on a busy machine.
constexpr int kPausePolls = 256;
constexpr int kHelperPolls = kPausePolls + 64;
constexpr int kCallerPolls = kPausePolls + 256;

inline void Pause(int poll) {
  if (poll >= kPausePolls) {
    std::this_thread::yield();
    return;
  }
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

std::uint32_t Generation(std::uint64_t ticket) { return static_cast<std::uint32_t>(ticket >> 32); }

// Task index of a ticket whose job is being set up: nobody may take a task.
constexpr std::uint32_t kClosed = 0xFFFFFFFFu;
bool IsOpen(std::uint64_t ticket) { return static_cast<std::uint32_t>(ticket) != kClosed; }

// Takes the next task of job `generation` from the ticket, or returns -1 if that job has no
// task left or a later job has started.
int TakeTask(std::atomic<std::uint64_t>& ticket, std::uint32_t generation, int num_tasks) {
  std::uint64_t cur = ticket.load();
  while (true) {
    if (Generation(cur) != generation) return -1;
    const auto index = static_cast<std::uint32_t>(cur);
    if (index >= static_cast<std::uint32_t>(num_tasks)) return -1;
    if (ticket.compare_exchange_weak(cur, cur + 1)) return static_cast<int>(index);
  }
}

}  // namespace

WorkerPool::WorkerPool(int helpers) {
  for (int i = 1; i <= helpers; ++i) {
    try {
      threads_.emplace_back(&WorkerPool::Loop, this, i);
    } catch (const std::exception&) {
      break;  // run with the helpers we have
    }
  }
}

WorkerPool::~WorkerPool() {
  stopping_.store(true);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

void WorkerPool::Run(int num_tasks, const Task& fn) {
  if (num_tasks <= 0) return;
  if (threads_.empty() || num_tasks == 1) {
    for (int t = 0; t < num_tasks; ++t) fn(t, 0);
    return;
  }
  const std::uint32_t generation = ++generation_;
  // Close the ticket first (a helper still holding the previous generation, or reading fn_ and
  // num_tasks_ while they change, can then take nothing), set the job up, then open it.
  // Helpers read fn_ and num_tasks_ only after seeing the open ticket of their generation and
  // call fn only for a task they took in it, i.e. while this Run is still waiting.
  ticket_.store((static_cast<std::uint64_t>(generation) << 32) | kClosed);
  fn_.store(&fn);
  num_tasks_.store(num_tasks);
  done_.store(0);
  ticket_.store(static_cast<std::uint64_t>(generation) << 32);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    sleep_gen_ = generation;
  }
  wake_.notify_all();
  for (int t = TakeTask(ticket_, generation, num_tasks); t >= 0;
       t = TakeTask(ticket_, generation, num_tasks)) {
    fn(t, 0);
    done_.fetch_add(1);
  }
  for (int i = 0; i < kCallerPolls && done_.load() < num_tasks; ++i) Pause(i);
  if (done_.load() < num_tasks) {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [&] { return done_.load() == num_tasks; });
  }
}

void WorkerPool::Work(std::uint32_t generation, int id) {
  const std::uint64_t ticket = ticket_.load();
  if (Generation(ticket) != generation || !IsOpen(ticket)) return;
  const Task* fn = fn_.load();
  const int n = num_tasks_.load();
  // If fn_ / num_tasks_ already belong to a later job, TakeTask fails: that job closed the
  // ticket under another generation before changing them. A task taken here means job
  // `generation` is still running, so fn and n are its own.
  for (int t = TakeTask(ticket_, generation, n); t >= 0; t = TakeTask(ticket_, generation, n)) {
    (*fn)(t, id);
    if (done_.fetch_add(1) + 1 == n) {
      // Taking the lock orders this with the caller's predicate check (no lost wake-up).
      { std::lock_guard<std::mutex> sync(mutex_); }
      idle_.notify_all();
    }
  }
}

void WorkerPool::Loop(int id) {
  std::uint32_t seen = 0;
  while (true) {
    // Spin a little: the next job of the same frame usually follows within microseconds.
    for (int i = 0; i < kHelperPolls && !stopping_.load(); ++i) {
      const std::uint64_t ticket = ticket_.load();
      if (Generation(ticket) != seen && IsOpen(ticket)) {
        seen = Generation(ticket);
        Work(seen, id);
        i = 0;
      }
      Pause(i);
    }
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [&] { return stop_ || sleep_gen_ != seen; });
    if (stop_) return;
    seen = sleep_gen_;
    lock.unlock();
    Work(seen, id);
  }
}

}  // namespace rover::dl::stereo::internal
