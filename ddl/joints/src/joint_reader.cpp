#include "rover/ddl/joints/joint_reader.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/format.hpp"

namespace rover::ddl::joints {
namespace {

// Keeps the worst health and the reason of the first problem of that severity.
void Worsen(msg::SensorHealth h, const std::string& why, JointState* s) {
  if (msg::WorseHealth(s->health, h) != s->health) {
    s->health = h;
    s->health_reason = why;
  }
}

}  // namespace

Status JointReaderOptions::Validate() const {
  auto positive = [](const char* k, double v) -> Status {
    if (!std::isfinite(v) || v <= 0.0) {
      return InvalidArgument(std::string("joint_reader.") + k + ": " + std::to_string(v) +
                             " must be finite and > 0");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive("rate_window_s", rate_window_s));
  ROVER_RETURN_IF_ERROR(positive("stale_after_s", stale_after_s));
  ROVER_RETURN_IF_ERROR(positive("pot_limit_margin", pot_limit_margin));
  ROVER_RETURN_IF_ERROR(positive("joint_limit_margin", joint_limit_margin));
  return Status::Ok();
}

Result<JointReader> JointReader::Create(const HardwareConfig& config,
                                        const JointReaderOptions& options) {
  ROVER_RETURN_IF_ERROR(config.Validate().WithPrefix("hardware config"));
  ROVER_RETURN_IF_ERROR(options.Validate());
  return JointReader(config, options);
}

JointReader::JointReader(const HardwareConfig& config, const JointReaderOptions& options)
    : config_(config), options_(options) {
  for (int w = 0; w < 6; ++w) {
    wheel_rates_.emplace_back(options.rate_window_s,
                              config.motors[static_cast<std::size_t>(w)].CountsPerRad());
  }
}

void JointReader::OnMotorTelemetry(const hw::MotorTelemetry& t) {
  if (last_telemetry_ && t.stamp_ns <= last_telemetry_->stamp_ns) return;  // old or duplicate
  for (std::size_t i = 0; i < t.motors.size(); ++i) {
    if (!last_telemetry_) {
      counts_[i] = t.motors[i].position;
    } else {
      counts_[i] += hw::CounterDelta(t.motors[i].position, last_telemetry_->motors[i].position);
    }
  }
  for (std::size_t w = 0; w < wheel_rates_.size(); ++w) wheel_rates_[w].Add(t.stamp_ns, counts_[w]);
  last_telemetry_ = t;
}

void JointReader::OnSuspensionPots(const hw::SuspensionPots& p) {
  if (last_pots_ && p.stamp_ns <= last_pots_->stamp_ns) return;
  last_pots_ = p;
}

void JointReader::OnArmContact(const hw::ArmContact& c) {
  if (last_contact_ && c.stamp_ns <= last_contact_->stamp_ns) return;
  last_contact_ = c;
}

JointState JointReader::State(Time now) const {
  JointState s;
  s.health = msg::SensorHealth::kOk;
  const double stale_ns = options_.stale_after_s * 1e9;
  if (!last_telemetry_) {
    Worsen(msg::SensorHealth::kStale, "no motor telemetry yet", &s);
  } else {
    s.stamp = Time{last_telemetry_->stamp_ns};
    if (static_cast<double>(now.ns - last_telemetry_->stamp_ns) > stale_ns) {
      Worsen(msg::SensorHealth::kStale,
             "motor telemetry " + FormatNumber((now.ns - last_telemetry_->stamp_ns) * 1e-9, 3) +
                 " s old",
             &s);
    }
    for (std::size_t w = 0; w < 6; ++w) {
      s.wheel_angle[w] = static_cast<double>(counts_[w]) / config_.motors[w].CountsPerRad();
      s.wheel_rate[w] = wheel_rates_[w].Rate();
    }
    for (int j = 0; j < 4; ++j) {
      const auto k = static_cast<std::size_t>(hw::kSteerLF + j);
      s.steer_angle[static_cast<std::size_t>(j)] =
          static_cast<double>(counts_[k]) / config_.motors[k].CountsPerRad();
    }
    s.mast_pan =
        static_cast<double>(counts_[hw::kMastPan]) / config_.motors[hw::kMastPan].CountsPerRad();
    s.mast_tilt =
        static_cast<double>(counts_[hw::kMastTilt]) / config_.motors[hw::kMastTilt].CountsPerRad();
    for (int j = 0; j < 4; ++j) {
      const auto k = static_cast<std::size_t>(hw::kArmAzimuth + j);
      s.arm_angle[static_cast<std::size_t>(j)] =
          static_cast<double>(counts_[k]) / config_.motors[k].CountsPerRad();
    }
    for (int m = hw::kSteerLF; m < hw::kNumMotors; ++m) {
      const MotorSpec& spec = config_.motors[static_cast<std::size_t>(m)];
      const double a =
          static_cast<double>(counts_[static_cast<std::size_t>(m)]) / spec.CountsPerRad();
      if (spec.HasLimits() && (a < spec.min_angle - options_.joint_limit_margin ||
                               a > spec.max_angle + options_.joint_limit_margin)) {
        Worsen(msg::SensorHealth::kDegraded,
               std::string(hw::MotorName(m)) + " angle " + FormatNumber(a, 3) +
                   " rad beyond its limits",
               &s);
      }
    }
  }

  s.arm_contact = last_contact_ && last_contact_->closed &&
                  static_cast<double>(now.ns - last_contact_->stamp_ns) <= stale_ns;
  if (!last_pots_) {
    Worsen(msg::SensorHealth::kStale, "no suspension pots yet", &s);
  } else {
    s.stamp = std::max(s.stamp, Time{last_pots_->stamp_ns});
    if (static_cast<double>(now.ns - last_pots_->stamp_ns) > stale_ns) {
      Worsen(
          msg::SensorHealth::kStale,
          "suspension pots " + FormatNumber((now.ns - last_pots_->stamp_ns) * 1e-9, 3) + " s old",
          &s);
    }
    std::array<double, hw::kNumPots> angle{};
    for (int i = 0; i < hw::kNumPots; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const std::uint16_t adc = last_pots_->adc[k];
      angle[k] = config_.pots.AngleFromCounts(i, adc);
      if (adc == 0 || adc >= hw::kAdcMax) {
        Worsen(msg::SensorHealth::kFailed,
               std::string(hw::PotName(i)) + " pot at the ADC rail (" + std::to_string(adc) + ")",
               &s);
      } else if (std::abs(angle[k]) > config_.pots.Limit(i) + options_.pot_limit_margin) {
        Worsen(msg::SensorHealth::kDegraded,
               std::string(hw::PotName(i)) + " angle " + FormatNumber(angle[k], 3) +
                   " rad beyond its mechanical stop",
               &s);
      }
    }
    s.rocker_angle = {angle[hw::kLeftRocker], angle[hw::kRightRocker]};
    s.bogie_angle = {angle[hw::kLeftBogie], angle[hw::kRightBogie]};
    const double diff = angle[hw::kLeftRocker] + angle[hw::kRightRocker];
    if (std::abs(diff) > config_.pots.differential_tolerance) {
      Worsen(msg::SensorHealth::kDegraded,
             "rocker angles inconsistent with the differential: left + right = " +
                 FormatNumber(diff, 3) + " rad",
             &s);
    }
  }
  return s;
}

}  // namespace rover::ddl::joints
