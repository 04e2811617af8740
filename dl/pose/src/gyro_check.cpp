#include "rover/dl/pose/gyro_check.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::pose {

Status GyroCheckOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckPositive("gyro_check.bin_s", bin_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("gyro_check.window_s", window_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("gyro_check.max_disagreement", max_disagreement, "rad/s"));
  ROVER_RETURN_IF_ERROR(
      CheckPositive("gyro_check.max_odometry_rate", max_odometry_rate, "rad/s"));
  ROVER_RETURN_IF_ERROR(CheckRange("gyro_check.min_coverage", min_coverage, 1e-3, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("gyro_check.rate_tolerance", rate_tolerance, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("gyro_check.confirm_s", confirm_s, 0.0, 60.0, "s"));
  const auto whole_bins = [this](const char* key, double value, double min_bins) -> Status {
    const double n = value / bin_s;
    if (n < min_bins - 1e-9 || std::abs(n - std::round(n)) > 1e-6) {
      return InvalidArgument(std::string("gyro_check.") + key + ": " + FormatNumber(value) +
                             " s is not a whole number of bins of gyro_check.bin_s " +
                             FormatNumber(bin_s) + " s");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(whole_bins("window_s", window_s, 1.0));
  return whole_bins("confirm_s", confirm_s, 0.0);
}

void GyroCheckOptions::BindParams(ParamBinder<GyroCheckOptions>& b) {
  using O = GyroCheckOptions;
  b.Bind("enabled", &O::enabled,
         "compare the gyro's yaw rate with wheel odometry's and declare the pose unknown when "
         "they disagree (a gyro fault)");
  b.Bind("window_s", &O::window_s, "s", "judged window (a whole number of bins)")
      .Range(0.01, 60.0);
  b.Bind("bin_s", &O::bin_s, "s", "bin length; windows slide by one bin").Range(0.01, 60.0);
  b.Bind("max_disagreement", &O::max_disagreement, "rad/s",
         "gyro minus odometry yaw rate over a window that fails the check")
      .Range(1e-4, 10.0);
  b.Bind("max_odometry_rate", &O::max_odometry_rate, "rad/s",
         "windows whose wheel-odometry yaw rate is higher are not judged (turns slip)")
      .Range(1e-4, 10.0);
  b.Bind("rate_tolerance", &O::rate_tolerance, "",
         "share of the wheel-odometry yaw rate added to max_disagreement (turning wheels slip)")
      .Range(0.0, 1.0);
  b.Bind("min_coverage", &O::min_coverage, "",
         "share of a window that both the gyro and the odometry must cover to judge it")
      .Range(1e-3, 1.0);
  b.Bind("confirm_s", &O::confirm_s, "s",
         "a failed window counts only when the window this much earlier failed with the same "
         "sign (a bias persists, a skid off a rock does not); 0 judges one window")
      .Range(0.0, 60.0);
}

Result<GyroCheck> GyroCheck::Create(const GyroCheckOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return GyroCheck(options);
}

GyroCheck::GyroCheck(const GyroCheckOptions& options)
    : options_(options),
      bins_per_window_(static_cast<int>(std::lround(options.window_s / options.bin_s))),
      confirm_bins_(static_cast<int>(std::lround(options.confirm_s / options.bin_s))) {}

void GyroCheck::Reset() {
  bins_.clear();
  failed_.clear();
  gyro_bin_ = odo_bin_ = judged_through_ = INT64_MIN;
}

GyroCheck::Bin* GyroCheck::BinAt(Time t) {
  const auto index = static_cast<std::int64_t>(std::floor(t.seconds() / options_.bin_s));
  if (!bins_.empty()) {
    if (index > bins_.back().index + 2 * bins_per_window_ ||
        index < bins_.back().index - 4 * bins_per_window_) {
      Reset();  // a gap, or the clock went back: start over
    } else if (index < bins_.front().index) {
      return nullptr;  // older than every window still to judge
    }
  }
  if (bins_.empty()) bins_.push_back(Bin{index});
  while (bins_.back().index < index) bins_.push_back(Bin{bins_.back().index + 1});
  return &bins_[static_cast<std::size_t>(index - bins_.front().index)];
}

void GyroCheck::AddGyro(Time t, double dt, double rate_z) {
  if (!options_.enabled || !(dt > 0.0) || !std::isfinite(rate_z)) return;
  Bin* b = BinAt(t);
  if (b == nullptr) return;
  b->gyro_angle += rate_z * dt;
  b->gyro_time += dt;
  gyro_bin_ = std::max(gyro_bin_, b->index);
  Judge();
}

void GyroCheck::AddOdometry(Time t_from, Time t_to, double dyaw) {
  const double dt = ToSeconds(t_to - t_from);
  if (!options_.enabled || !(dt > 0.0) || !std::isfinite(dyaw)) return;
  Bin* b = BinAt(t_to);
  if (b == nullptr) return;
  b->odo_angle += dyaw;
  b->odo_time += dt;
  odo_bin_ = std::max(odo_bin_, b->index);
  Judge();
}

void GyroCheck::Judge() {
  if (bins_.empty() || gyro_bin_ == INT64_MIN || odo_bin_ == INT64_MIN) return;
  const std::int64_t last_complete = std::min(gyro_bin_, odo_bin_) - 1;
  const std::int64_t first_end =
      std::max(judged_through_ + 1, bins_.front().index + bins_per_window_ - 1);
  for (std::int64_t end = first_end; end <= last_complete; ++end) {
    double ga = 0, gt = 0, oa = 0, ot = 0;
    for (std::int64_t i = end - bins_per_window_ + 1; i <= end; ++i) {
      const Bin& b = bins_[static_cast<std::size_t>(i - bins_.front().index)];
      ga += b.gyro_angle;
      gt += b.gyro_time;
      oa += b.odo_angle;
      ot += b.odo_time;
    }
    judged_through_ = end;
    const double need = options_.min_coverage * options_.window_s;
    if (gt < need || ot < need) continue;
    const double gyro_rate = ga / gt, odometry_rate = oa / ot;
    if (std::abs(odometry_rate) > options_.max_odometry_rate) continue;
    ++judged_;
    const double d = gyro_rate - odometry_rate;
    worst_ = std::max(worst_, std::abs(d));
    const double tolerance =
        options_.max_disagreement + options_.rate_tolerance * std::abs(odometry_rate);
    if (failure_ || std::abs(d) <= tolerance) continue;
    const int sign = d > 0.0 ? 1 : -1;
    while (!failed_.empty() && failed_.front().first < end - confirm_bins_) failed_.pop_front();
    failed_.emplace_back(end, sign);
    const bool confirmed =
        confirm_bins_ == 0 || (failed_.front().first == end - confirm_bins_ &&
                               failed_.front().second == sign);
    if (confirmed) {
      GyroCheckFailure f;
      f.window_end = Time::FromSeconds(static_cast<double>(end + 1) * options_.bin_s);
      f.gyro_rate = gyro_rate;
      f.odometry_rate = odometry_rate;
      f.reason = "ddl/imu gyro z disagrees with wheel odometry: " + FormatNumber(gyro_rate, 4) +
                 " vs " + FormatNumber(odometry_rate, 4) + " rad/s over the " +
                 FormatNumber(options_.window_s) + " s to t = " +
                 FormatNumber(f.window_end.seconds()) + " s (allowed " +
                 FormatNumber(tolerance, 3) + " rad/s: gyro_check.max_disagreement + " +
                 "rate_tolerance x odometry" +
                 (confirm_bins_ > 0 ? ", and in the window " + FormatNumber(options_.confirm_s) +
                                          " s before"
                                    : std::string()) +
                 ")";
      failure_ = std::move(f);
    }
  }
  // Keep the bins the next window needs.
  if (judged_through_ == INT64_MIN) return;
  while (!bins_.empty() && bins_.front().index < judged_through_ - bins_per_window_ + 2) {
    bins_.pop_front();
  }
}

}  // namespace rover::dl::pose
