#include "rover/runtime/executor.hpp"

#include <algorithm>
#include <exception>
#include <limits>

#include "rover/base/log.hpp"

namespace rover {
namespace {
constexpr dds_attach_t kGuardToken = -1;
// Under a simulated clock the loop cannot sleep until a run-clock deadline (time moves only when
// sim/clock samples arrive, and they wake the loop); it still wakes this often to notice stops.
constexpr Duration kMaxIdleWait = std::chrono::milliseconds(200);
}  // namespace

Result<std::unique_ptr<Executor>> Executor::Create(const dds::Participant& participant,
                                                   const Clock& clock) {
  auto ws = dds::WaitSet::Create(participant);
  if (!ws.ok()) return ws.status();
  auto guard = dds::GuardCondition::Create(participant);
  if (!guard.ok()) return guard.status();
  std::unique_ptr<Executor> e(new Executor(clock, std::move(*ws), std::move(*guard)));
  ROVER_RETURN_IF_ERROR(e->waitset_.Attach(e->guard_.handle(), kGuardToken));
  return e;
}

Executor::Executor(const Clock& clock, dds::WaitSet ws, dds::GuardCondition guard)
    : clock_(clock), waitset_(std::move(ws)), guard_(std::move(guard)) {}

Executor::~Executor() = default;

Executor::TimerId Executor::AddTimer(Duration period, std::function<void()> callback,
                                     TimerBase base, bool always) {
  ROVER_DEMAND(period.count() > 0);
  Timer t{next_timer_id_++, period, std::move(callback), base, always};
  timers_.push_back(std::move(t));
  return timers_.back().id;
}

void Executor::CancelTimer(TimerId id) {
  timers_.erase(std::remove_if(timers_.begin(), timers_.end(),
                               [id](const Timer& t) { return t.id == id; }),
                timers_.end());
}

Status Executor::AddSubscription(dds_entity_t handle, const std::string& topic,
                                 std::function<void()> drain, std::function<void()> stash,
                                 bool always, dds::TopicSeam* seam) {
  Subscription s{handle, topic, std::move(drain), std::move(stash), always, seam,
                 dds::lockstep::CatalogIndex(topic)};
  s.attached = always || active_;
  subscriptions_.push_back(std::move(s));
  return SyncWaitset(subscriptions_.size() - 1);
}

Status Executor::SyncWaitset(std::size_t i) {
  Subscription& s = subscriptions_[i];
  const bool want = s.attached && (s.always || !strict_);
  if (want && !s.in_waitset) {
    ROVER_RETURN_IF_ERROR(waitset_.Attach(s.handle, static_cast<dds_attach_t>(i)));
  } else if (!want && s.in_waitset) {
    ROVER_RETURN_IF_ERROR(waitset_.Detach(s.handle));
  }
  s.in_waitset = want;
  return Status::Ok();
}

Status Executor::SetActive(bool active) {
  active_ = active;
  for (std::size_t i = 0; i < subscriptions_.size(); ++i) {
    Subscription& s = subscriptions_[i];
    if (s.always) continue;
    s.attached = active;
    ROVER_RETURN_IF_ERROR(SyncWaitset(i));
  }
  for (Timer& t : timers_) {
    if (!t.always) t.armed = false;  // re-armed from "now" on the next run
  }
  return Status::Ok();
}

void Executor::Invoke(const std::string& what, const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    ++callback_errors_;
    log::Error("callback threw; sample ignored", {{"source", what}, {"error", e.what()}});
  } catch (...) {
    ++callback_errors_;
    log::Error("callback threw a non-standard exception; sample ignored", {{"source", what}});
  }
}

Time Executor::TimerNow(const Timer& t) const {
  return t.base == TimerBase::kWall ? wall_.Now() : clock_.Now();
}

void Executor::RunDueTimers() {
  const Time run_now = clock_.Now();
  // A simulator reset moves the run clock backwards: re-arm run-clock timers from the new time.
  const bool went_back = run_now < last_run_clock_;
  last_run_clock_ = run_now;
  // Copy ids: callbacks may add or cancel timers.
  std::vector<TimerId> ids;
  ids.reserve(timers_.size());
  for (const Timer& t : timers_) ids.push_back(t.id);
  for (TimerId id : ids) {
    auto it = std::find_if(timers_.begin(), timers_.end(), [id](const Timer& t) { return t.id == id; });
    if (it == timers_.end()) continue;
    if (!it->always && !active_) continue;
    if (it->base == TimerBase::kRunClock && !clock_.valid()) continue;
    const Time now = TimerNow(*it);
    if (!it->armed || (went_back && it->base == TimerBase::kRunClock)) {
      it->next = now + it->period;
      it->armed = true;
      continue;
    }
    if (now < it->next) continue;
    // Fire once, even if several periods were missed; keep the phase when not overrun.
    it->next = it->next + it->period;
    if (it->next <= now) it->next = now + it->period;
    auto callback = it->callback;  // the timer may be cancelled by its own callback
    Invoke("timer", callback);
  }
}

void Executor::SpinOnce(Duration max_wait) {
  // How long may we sleep? Until the earliest wall-based deadline, capped by max_wait.
  Duration wait = max_wait;
  const Time wall_now = wall_.Now();
  for (const Timer& t : timers_) {
    if (!t.always && !active_) continue;
    if (!t.armed) {
      wait = Duration::zero();
      break;
    }
    const bool wall_based = t.base == TimerBase::kWall || !clock_.simulated();
    if (wall_based) {
      const Time now = t.base == TimerBase::kWall ? wall_now : clock_.Now();
      wait = std::min(wait, std::max(Duration::zero(), t.next - now));
    }
  }
  if (auto pump = dds::CurrentSeamPump()) {
    if (auto due = pump->NextDue()) {
      // Held samples fall due on the run clock; under wall time that is a wall deadline.
      // (At least 1 ms: a process whose faults run on another clock (the simulator's) must not
      // spin while a held sample waits for that clock.)
      wait = std::min(wait, clock_.simulated() ? kMaxIdleWait
                                               : std::max(Duration{std::chrono::milliseconds(1)},
                                                          *due - clock_.Now()));
    }
  }
  if (clock_.simulated()) wait = std::min(wait, kMaxIdleWait);

  const auto tokens = waitset_.Wait(wait.count());
  for (dds_attach_t token : tokens) {
    if (token == kGuardToken) {
      guard_.TakeTriggered();
      continue;
    }
    const auto idx = static_cast<std::size_t>(token);
    if (idx >= subscriptions_.size() || !subscriptions_[idx].attached) continue;
    Subscription& s = subscriptions_[idx];
    if (strict_ && !s.always) {
      Invoke(s.topic, s.stash);
    } else {
      s.drain();
    }
  }
  if (strict_) {
    if (clock_.valid() && active_ && (!last_tick_ || clock_.Now() != *last_tick_)) {
      ServeTick(clock_.Now());
    } else {
      RunDueTimers();  // wall timers (the heartbeat); no run-clock timer is newly due
      if (after_spin_) Invoke("after-spin", after_spin_);  // may repeat an acknowledgement
    }
    return;
  }
  RunSeams();
  RunDueTimers();
  if (after_spin_) Invoke("after-spin", after_spin_);
}

void Executor::DrainAll() {
  for (auto& s : subscriptions_) {
    if (s.attached) s.drain();
  }
}

void Executor::SetStrictTicks(bool strict) {
  ROVER_DEMAND(!strict || clock_.simulated());
  strict_ = strict;
  if (strict) dds::lockstep::SetWriteTick(last_tick_ ? last_tick_->ns : 0);
  for (std::size_t i = 0; i < subscriptions_.size(); ++i) {
    const Status s = SyncWaitset(i);
    if (!s.ok()) log::Error("wait set", {{"error", s.message()}});
  }
}

void Executor::NoteServed() {
  reads_ = 0;
  std::int64_t due = std::numeric_limits<std::int64_t>::max();
  for (const Subscription& s : subscriptions_) {
    if (!s.attached || s.always) continue;
    // A topic outside the catalog has no frontier; samples held by a fault seam fall due on
    // their own schedule: serve every tick.
    if (s.topic_index < 0 || (s.seam != nullptr && s.seam->Holding())) due = 0;
    reads_ |= dds::lockstep::TopicBit(s.topic_index);
  }
  for (const Timer& t : timers_) {
    if (t.base != TimerBase::kRunClock || (!t.always && !active_)) continue;
    due = std::min(due, t.armed ? t.next.ns : std::int64_t{0});
  }
  if (auto pump = dds::CurrentSeamPump()) {
    if (auto d = pump->NextDue()) due = std::min(due, d->ns);
  }
  next_due_ns_ = due;
}

void Executor::ServeTick(Time now) {
  dds::lockstep::SetWriteTick(now.ns);
  dds::lockstep::SetReadGate(now.ns);
  if (auto pump = dds::CurrentSeamPump()) Invoke("fault seam", [&] { pump->Pump(); });
  for (auto& s : subscriptions_) {
    if (s.attached && s.seam != nullptr && s.seam->Holding() && s.seam->HasDue()) {
      Invoke(s.topic, s.stash);
    }
  }
  for (auto& s : subscriptions_) {
    if (s.attached && !s.always) s.drain();
  }
  RunDueTimers();
  dds::lockstep::SetReadGate(dds::lockstep::kOff);
  last_tick_ = now;
  NoteServed();
  if (after_spin_) Invoke("after-spin", after_spin_);
}

void Executor::RunSeams() {
  if (auto pump = dds::CurrentSeamPump()) Invoke("fault seam", [&] { pump->Pump(); });
  for (auto& s : subscriptions_) {
    if (s.attached && s.seam != nullptr && s.seam->Holding() && s.seam->HasDue()) s.drain();
  }
}

void Executor::Spin() {
  while (!stop_.load()) {
    Duration wait = std::chrono::seconds(1);
    if (work_ && active_) {
      Duration next = wait;
      Invoke("work", [&] { next = work_(); });
      wait = std::clamp(next, Duration::zero(), wait);
    }
    SpinOnce(wait);
  }
}

void Executor::Stop() {
  stop_.store(true);
  guard_.Trigger();
}

}  // namespace rover
