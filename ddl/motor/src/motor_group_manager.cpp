#include "rover/ddl/motor/motor_group_manager.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/ddl/motor/sync_planner.hpp"

namespace rover::ddl::motor {
namespace {

constexpr std::size_t kMaxMessage = 127;  // string<127> in the IDL

std::string MotorLabel(int m) {
  return "motor " + std::to_string(m) + " (" + hw::MotorName(m) + ")";
}

// Signed difference of two uint32 sequence numbers (a - b), wrap-safe.
std::int32_t SeqDiff(std::uint32_t a, std::uint32_t b) { return static_cast<std::int32_t>(a - b); }

bool ValidMode(GroupMode m) {
  return m == GroupMode::kPosition || m == GroupMode::kVelocity || m == GroupMode::kStop;
}

}  // namespace

Result<MotorGroupManager> MotorGroupManager::Create(const HardwareConfig& config,
                                                    const MotorManagerOptions& options) {
  ROVER_RETURN_IF_ERROR(config.Validate().WithPrefix("hardware config"));
  ROVER_RETURN_IF_ERROR(options.Validate());
  return MotorGroupManager(config, options);
}

MotorGroupManager::MotorGroupManager(const HardwareConfig& config,
                                     const MotorManagerOptions& options)
    : config_(config), options_(options) {}

// ---- helpers ----------------------------------------------------------------------------------

MotorStatus MotorGroupManager::MakeStatus(std::uint32_t command_id, GroupState state,
                                          MotorFault fault, int fault_motor,
                                          const std::string& message, Time now) const {
  MotorStatus s;
  s.stamp = now;
  s.command_id = command_id;
  s.state = state;
  s.fault = fault;
  s.fault_motor = static_cast<std::int8_t>(fault_motor);
  s.message = message.size() > kMaxMessage ? message.substr(0, kMaxMessage) : message;
  if (latest_) {
    s.position = latest_->position;
    s.velocity = latest_->velocity;
    s.current = latest_->current;
    s.temperature = latest_->temperature;
  }
  return s;
}

hw::MotorGoals MotorGroupManager::NewGoals(Time now) {
  hw::MotorGoals g;
  g.stamp_ns = now.ns;
  g.command_id = next_hw_id_++;
  if (next_hw_id_ == 0) next_hw_id_ = 1;
  return g;
}

hw::MotorGoals& MotorGroupManager::GoalsOf(ManagerOutput* out, Time now) {
  if (!out->goals) out->goals = NewGoals(now);
  return *out->goals;
}

void MotorGroupManager::EndGroup(std::size_t index, GroupState state, MotorFault fault,
                                 int fault_motor, const std::string& message, bool brake, Time now,
                                 ManagerOutput* out) {
  const Group g = groups_[index];
  groups_.erase(groups_.begin() + static_cast<std::ptrdiff_t>(index));
  if (brake) {
    hw::MotorGoals& goals = GoalsOf(out, now);
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if (g.Has(m)) goals.goals[static_cast<std::size_t>(m)] = {hw::MotorMode::kBrake, 0, 0, 0};
    }
  }
  MotorStatus s = MakeStatus(g.command_id, state, fault, fault_motor, message, now);
  out->statuses.push_back(s);
  last_final_ = s;
}

// ---- commands ---------------------------------------------------------------------------------

CommandError MotorGroupManager::Check(const MotorCommand& c, std::string* message,
                                      int* motor) const {
  std::string dummy_msg;
  int dummy_motor = -1;
  if (message == nullptr) message = &dummy_msg;
  if (motor == nullptr) motor = &dummy_motor;
  *motor = -1;
  if (!ValidMode(c.mode)) {
    *message = "mode " + std::to_string(static_cast<int>(c.mode)) +
               " is not position, velocity "
               "or stop";
    return CommandError::kUnknownMode;
  }
  for (int bit = hw::kNumMotors; bit < 16; ++bit) {
    if ((c.motor_mask >> bit) & 1u) {
      *motor = bit;
      *message = "motor_mask bit " + std::to_string(bit) + " selects no motor (0.." +
                 std::to_string(hw::kNumMotors - 1) + ")";
      return CommandError::kUnknownMotor;
    }
  }
  if (!std::isfinite(c.timeout_s) || c.timeout_s < 0.0) {
    *message = "timeout_s " + FormatNumber(c.timeout_s, 4) + " must be finite and >= 0";
    return CommandError::kBadTimeout;
  }
  if (c.mode == GroupMode::kStop) return CommandError::kNone;
  if (c.motor_mask == 0) {
    *message = "motor_mask is empty";
    return CommandError::kEmptyMask;
  }
  for (int m = 0; m < hw::kNumMotors; ++m) {
    if (!((c.motor_mask >> m) & 1u)) continue;
    const auto k = static_cast<std::size_t>(m);
    const MotorSpec& spec = config_.motors[k];
    *motor = m;
    const double goal = c.goal[k];
    const double rate = c.max_rate[k];
    if (!std::isfinite(goal)) {
      *message = MotorLabel(m) + ": goal " + FormatNumber(goal, 4) + " is not finite";
      return CommandError::kNonFiniteGoal;
    }
    if (!std::isfinite(rate) || rate < 0.0) {
      *message = MotorLabel(m) + ": max_rate " + FormatNumber(rate, 4) + " must be finite and >= 0";
      return CommandError::kBadRate;
    }
    if (c.mode == GroupMode::kPosition) {
      if (rate > spec.max_rate) {
        *message = MotorLabel(m) + ": max_rate " + FormatNumber(rate, 4) +
                   " rad/s exceeds the limit " + FormatNumber(spec.max_rate, 4);
        return CommandError::kRateAboveLimit;
      }
      if (spec.HasLimits() && (goal < spec.min_angle || goal > spec.max_angle)) {
        *message = MotorLabel(m) + ": goal " + FormatNumber(goal, 4) + " rad is outside [" +
                   FormatNumber(spec.min_angle, 4) + ", " + FormatNumber(spec.max_angle, 4) + "]";
        return CommandError::kGoalOutOfRange;
      }
      if (std::abs(goal * spec.CountsPerRad()) >= 2.0e9) {
        *message =
            MotorLabel(m) + ": goal " + FormatNumber(goal, 4) + " rad is beyond the encoder range";
        return CommandError::kGoalOutOfRange;
      }
    } else if (std::abs(goal) > spec.max_rate) {
      *message = MotorLabel(m) + ": rate " + FormatNumber(goal, 4) + " rad/s exceeds the limit " +
                 FormatNumber(spec.max_rate, 4);
      return CommandError::kRateAboveLimit;
    }
  }
  *motor = -1;
  return CommandError::kNone;
}

ManagerOutput MotorGroupManager::HandleCommand(const MotorCommand& c, Time now) {
  ManagerOutput out;
  std::string msg;
  int bad_motor = -1;
  const CommandError err = Check(c, &msg, &bad_motor);
  auto reject = [&](CommandError e, MotorFault fault, const std::string& m, int motor) {
    MotorStatus s = MakeStatus(c.command_id, GroupState::kRejected, fault, motor, m, now);
    s.error = e;
    out.statuses.push_back(s);
    last_final_ = s;
  };
  if (err != CommandError::kNone) {
    reject(err, MotorFault::kBadCommand, msg, bad_motor);
    return out;
  }

  const std::uint16_t mask =
      c.mode == GroupMode::kStop && c.motor_mask == 0 ? hw::kAllMotorsMask : c.motor_mask;

  if (c.mode == GroupMode::kStop) {
    for (std::size_t i = groups_.size(); i-- > 0;) {
      if (groups_[i].mask & mask) {
        EndGroup(i, GroupState::kFault, MotorFault::kStopped, -1,
                 "stopped by command " + std::to_string(c.command_id), true, now, &out);
      }
    }
    hw::MotorGoals& goals = GoalsOf(&out, now);
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if ((mask >> m) & 1u)
        goals.goals[static_cast<std::size_t>(m)] = {hw::MotorMode::kBrake, 0, 0, 0};
    }
    MotorStatus s =
        MakeStatus(c.command_id, GroupState::kDone, MotorFault::kNone, -1, "braked motors", now);
    out.statuses.push_back(s);
    last_final_ = s;
    return out;
  }

  const bool fresh =
      latest_ && latest_rx_ && ToSeconds(now - *latest_rx_) <= options_.telemetry_timeout_s;
  if (!fresh) {
    reject(CommandError::kNoTelemetry, MotorFault::kNoTelemetry,
           "no fresh motor telemetry to plan the move from", -1);
    return out;
  }

  Group g;
  g.command_id = c.command_id;
  g.mode = c.mode;
  g.mask = mask;
  g.started = now;
  g.goal = c.goal;
  double timeout = c.timeout_s;
  if (c.mode == GroupMode::kPosition) {
    std::vector<AxisMove> axes;
    std::vector<int> index;
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      const MotorSpec& spec = config_.motors[k];
      const double d = c.goal[k] - latest_->position[k];
      g.distance[k] = std::abs(d);
      g.direction[k] = d >= 0.0 ? 1.0 : -1.0;
      const double vmax = c.max_rate[k] > 0.0 ? c.max_rate[k] : spec.default_rate;
      axes.push_back({g.distance[k], vmax, spec.max_acceleration});
      index.push_back(m);
    }
    const SyncPlan plan = PlanSynchronisedMove(axes);
    g.planned_s = plan.duration_s;
    for (std::size_t j = 0; j < index.size(); ++j) {
      const auto k = static_cast<std::size_t>(index[j]);
      g.rate[k] = plan.rates[j] > 0.0 ? plan.rates[j] : axes[j].max_rate;
    }
    if (timeout == 0.0) {
      timeout = options_.timeout_factor * g.planned_s + options_.timeout_margin_s;
    } else if (timeout < g.planned_s) {
      reject(CommandError::kTimeoutTooShort, MotorFault::kBadCommand,
             "timeout_s " + FormatNumber(timeout, 4) + " is shorter than the synchronised move (" +
                 FormatNumber(g.planned_s, 4) + " s)",
             -1);
      return out;
    }
  } else {
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      g.rate[k] = std::abs(c.goal[k]);
      g.direction[k] = c.goal[k] >= 0.0 ? 1.0 : -1.0;
    }
    if (timeout == 0.0) timeout = options_.velocity_timeout_s;
  }
  g.deadline = now + Seconds(timeout);

  // Preempt every running group that shares a motor; brake its motors not taken over.
  for (std::size_t i = groups_.size(); i-- > 0;) {
    if (groups_[i].mask & mask) {
      const std::uint16_t others = groups_[i].mask & static_cast<std::uint16_t>(~mask);
      EndGroup(i, GroupState::kFault, MotorFault::kStopped, -1,
               "preempted by command " + std::to_string(c.command_id), false, now, &out);
      hw::MotorGoals& goals = GoalsOf(&out, now);
      for (int m = 0; m < hw::kNumMotors; ++m) {
        if ((others >> m) & 1u)
          goals.goals[static_cast<std::size_t>(m)] = {hw::MotorMode::kBrake, 0, 0, 0};
      }
    }
  }

  hw::MotorGoals& goals = GoalsOf(&out, now);
  for (int m = 0; m < hw::kNumMotors; ++m) {
    if (!g.Has(m)) continue;
    const auto k = static_cast<std::size_t>(m);
    const MotorSpec& spec = config_.motors[k];
    const double cpr = spec.CountsPerRad();
    hw::MotorGoal& hg = goals.goals[k];
    hg.current_limit_ma = static_cast<std::uint16_t>(std::lround(spec.current_limit * 1000.0));
    if (c.mode == GroupMode::kPosition) {
      hg.mode = hw::MotorMode::kPosition;
      hg.position = hw::WrapCounter(std::llround(c.goal[k] * cpr));
      hg.velocity =
          static_cast<std::int32_t>(std::max<long long>(1, std::llround(g.rate[k] * cpr)));
    } else {
      hg.mode = hw::MotorMode::kVelocity;
      hg.position = hw::WrapCounter(std::llround(latest_->position[k] * cpr));
      hg.velocity = static_cast<std::int32_t>(std::llround(c.goal[k] * cpr));
    }
  }
  g.hw_id = goals.command_id;
  groups_.push_back(g);
  out.statuses.push_back(MakeStatus(
      c.command_id, GroupState::kRunning, MotorFault::kNone, -1,
      c.mode == GroupMode::kPosition ? "synchronised move of " + FormatNumber(g.planned_s, 4) + " s"
                                     : std::string("velocity move"),
      now));
  return out;
}

ManagerOutput MotorGroupManager::StopAll(Time now, const std::string& reason) {
  ManagerOutput out;
  for (std::size_t i = groups_.size(); i-- > 0;) {
    EndGroup(i, GroupState::kFault, MotorFault::kStopped, -1, reason, false, now, &out);
  }
  hw::MotorGoals& goals = GoalsOf(&out, now);
  for (auto& g : goals.goals) g = {hw::MotorMode::kBrake, 0, 0, 0};
  return out;
}

void MotorGroupManager::ForgetTelemetry() {
  ROVER_DEMAND(groups_.empty());
  latest_.reset();
  latest_rx_.reset();
}

// ---- telemetry --------------------------------------------------------------------------------

ManagerOutput MotorGroupManager::HandleTelemetry(const hw::MotorTelemetry& t, Time now) {
  ManagerOutput out;
  if (latest_ && t.stamp_ns < latest_->stamp_ns) return out;  // reordered: older than we have
  latest_ = DecodeMotorTelemetry(config_, t);
  latest_rx_ = now;
  for (std::size_t i = groups_.size(); i-- > 0;) {
    Group& g = groups_[i];
    if (!g.applied && SeqDiff(t.command_id, g.hw_id) >= 0) {
      g.applied = true;
      g.applied_at = now;
      g.start = latest_->position;
    }
    if (!g.applied) continue;
    double dt = 0.0;
    if (g.last_stamp_ns) dt = std::max<double>(0.0, (t.stamp_ns - *g.last_stamp_ns) * 1e-9);
    g.last_stamp_ns = t.stamp_ns;

    MotorFault fault = MotorFault::kNone;
    int motor = -1;
    std::string msg;
    for (int m = 0; m < hw::kNumMotors && fault == MotorFault::kNone; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      const MotorSpec& spec = config_.motors[k];
      const std::uint16_t flags = latest_->flags[k];
      const double current = latest_->current[k];
      const double temp = latest_->temperature[k];
      const double trip = spec.current_limit * (1.0 + options_.overcurrent_margin);
      g.overcurrent_s[k] = current > trip ? g.overcurrent_s[k] + dt : 0.0;
      g.overtemp_s[k] = temp > spec.max_temperature ? g.overtemp_s[k] + dt : 0.0;
      motor = m;
      if (flags & hw::kMotorFlagOverCurrent) {
        fault = MotorFault::kOverCurrent;
        msg = MotorLabel(m) + " over-current (controller trip)";
      } else if (flags & hw::kMotorFlagOverTemp) {
        fault = MotorFault::kOverTemp;
        msg = MotorLabel(m) + " over-temperature (controller trip)";
      } else if (flags & hw::kMotorFlagStall) {
        fault = MotorFault::kStall;
        msg = MotorLabel(m) + " stalled (controller trip)";
      } else if (g.overcurrent_s[k] >= options_.overcurrent_time_s) {
        fault = MotorFault::kOverCurrent;
        msg = MotorLabel(m) + " over-current: " + FormatNumber(current, 4) + " A > " +
              FormatNumber(spec.current_limit * (1.0 + options_.overcurrent_margin), 4) +
              " A for " + FormatNumber(g.overcurrent_s[k], 4) + " s";
      } else if (g.overtemp_s[k] >= options_.overtemp_time_s) {
        fault = MotorFault::kOverTemp;
        msg = MotorLabel(m) + " over-temperature: " + FormatNumber(temp, 4) + " degC > " +
              FormatNumber(spec.max_temperature, 4) + " degC";
      }
    }
    if (fault != MotorFault::kNone) {
      EndGroup(i, GroupState::kFault, fault, motor, msg, true, now, &out);
    }
  }
  return out;
}

// ---- monitor ----------------------------------------------------------------------------------

void MotorGroupManager::CheckProgress(std::size_t index, Time now, ManagerOutput* out) {
  Group& g = groups_[index];
  const std::string id = "command " + std::to_string(g.command_id);
  if (!latest_rx_ || ToSeconds(now - *latest_rx_) > options_.telemetry_timeout_s) {
    EndGroup(
        index, GroupState::kFault, MotorFault::kNoTelemetry, -1,
        "no motor telemetry for more than " + FormatNumber(options_.telemetry_timeout_s, 4) + " s",
        true, now, out);
    return;
  }
  if (!g.applied) {
    if (ToSeconds(now - g.started) > options_.apply_timeout_s) {
      EndGroup(index, GroupState::kFault, MotorFault::kNoTelemetry, -1,
               "controller did not acknowledge the goals of " + id, true, now, out);
    } else {
      out->statuses.push_back(
          MakeStatus(g.command_id, GroupState::kRunning, MotorFault::kNone, -1, "starting", now));
    }
    return;
  }

  // Done?
  if (g.mode == GroupMode::kPosition) {
    bool done = true;
    for (int m = 0; m < hw::kNumMotors && done; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      done = std::abs(latest_->position[k] - g.goal[k]) <= config_.motors[k].position_tolerance &&
             std::abs(latest_->velocity[k]) <= options_.settle_rate;
    }
    if (done) {
      EndGroup(index, GroupState::kDone, MotorFault::kNone, -1,
               "reached goals in " + FormatNumber(ToSeconds(now - g.applied_at), 4) +
                   " s (planned " + FormatNumber(g.planned_s, 4) + " s)",
               options_.brake_when_done, now, out);
      return;
    }
  }

  // Timed out?
  if (now >= g.deadline) {
    if (g.mode == GroupMode::kVelocity) {
      EndGroup(index, GroupState::kDone, MotorFault::kNone, -1, "velocity move ended (timeout)",
               true, now, out);
      return;
    }
    int worst = -1;
    double worst_err = -1.0;
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      const double e =
          std::abs(latest_->position[k] - g.goal[k]) / config_.motors[k].position_tolerance;
      if (e > worst_err) {
        worst_err = e;
        worst = m;
      }
    }
    EndGroup(index, GroupState::kFault, MotorFault::kTimeout, worst,
             id + " timed out; " + MotorLabel(worst) + " is " +
                 FormatNumber(std::abs(latest_->position[static_cast<std::size_t>(worst)] -
                                       g.goal[static_cast<std::size_t>(worst)]),
                              4) +
                 " rad from its goal",
             true, now, out);
    return;
  }

  // Stalled? Compare the progress since the tick one window ago with the planned profile's, and
  // how far the motor is behind the plan since the group started (both must say stuck).
  g.history.emplace_back(now, latest_->position);
  std::size_t ref = g.history.size();
  for (std::size_t j = 0; j < g.history.size(); ++j) {
    if (ToSeconds(now - g.history[j].first) >= options_.stall_window_s) ref = j;
  }
  if (ref < g.history.size()) {
    const Time t0 = g.history[ref].first;
    const double tau0 = ToSeconds(t0 - g.applied_at);
    const double tau1 = ToSeconds(now - g.applied_at);
    for (int m = 0; m < hw::kNumMotors; ++m) {
      if (!g.Has(m)) continue;
      const auto k = static_cast<std::size_t>(m);
      const MotorSpec& spec = config_.motors[k];
      if (g.mode == GroupMode::kPosition &&
          std::abs(latest_->position[k] - g.goal[k]) <= spec.position_tolerance) {
        continue;
      }
      const auto plan = [&](double tau) {
        return g.mode == GroupMode::kPosition
                   ? ProfilePosition(g.distance[k], g.rate[k], spec.max_acceleration, tau)
                   : RampPosition(g.rate[k], spec.max_acceleration, tau);
      };
      const double planned = plan(tau1) - plan(tau0);
      if (planned < options_.stall_min_motion) continue;
      const double moved = (latest_->position[k] - g.history[ref].second[k]) * g.direction[k];
      const double lag = plan(tau1) - (latest_->position[k] - g.start[k]) * g.direction[k];
      if (moved < options_.stall_fraction * planned && lag > options_.stall_max_lag) {
        EndGroup(index, GroupState::kFault, MotorFault::kStall, m,
                 MotorLabel(m) + " stalled: moved " + FormatNumber(moved, 4) + " rad of " +
                     FormatNumber(planned, 4) + " rad planned in " +
                     FormatNumber(ToSeconds(now - t0), 4) + " s, " + FormatNumber(lag, 3) +
                     " rad behind its plan",
                 true, now, out);
        return;
      }
    }
    g.history.erase(g.history.begin(), g.history.begin() + static_cast<std::ptrdiff_t>(ref));
  }
  out->statuses.push_back(
      MakeStatus(g.command_id, GroupState::kRunning, MotorFault::kNone, -1, "running", now));
}

ManagerOutput MotorGroupManager::Tick(Time now) {
  ManagerOutput out;
  for (std::size_t i = groups_.size(); i-- > 0;) CheckProgress(i, now, &out);
  if (groups_.empty() && out.statuses.empty()) {
    if (last_final_) {
      MotorStatus s = *last_final_;
      const MotorStatus fresh = MakeStatus(0, GroupState::kIdle, MotorFault::kNone, -1, "", now);
      s.stamp = now;
      s.position = fresh.position;
      s.velocity = fresh.velocity;
      s.current = fresh.current;
      s.temperature = fresh.temperature;
      out.statuses.push_back(s);
    } else {
      out.statuses.push_back(MakeStatus(0, GroupState::kIdle, MotorFault::kNone, -1, "idle", now));
    }
  }
  return out;
}

}  // namespace rover::ddl::motor
