#pragma once
/// @file
/// RETURN_TO_LANDER as a DDS-free state machine (FIDO's visual rendezvous, seed 004, plus the
/// climb onto the deck): fed time-stamped inputs, it answers with the mobility, mast and camera
/// requests to send and the status to publish. The apl-rendezvous service binds it to topics.
///
/// Phases (msg::RendezvousPhase):
///  - LONG_RANGE (the estimate farther than 30 m): as MID_RANGE below, with the long-range
///    detector beyond the mid-range one's reach; the rover drives only once the lander is
///    acquired, far fixes are gated on bearing and range (FarFixConsistent) and the estimate's
///    range sigma stays >= 8 % of the distance (far fixes share their bias); two fixes since the
///    last accepted one on its bearing but off its range reset its range sigma to 30 %.
///  - MID_RANGE: point the mast at the lander estimate, take a NAVCAM pair, sight the
///    lander (RendezvousVision::SightLander), fuse the fix into the site-frame estimate (a
///    2-D information filter), then drive an autonav leg of at most `reacquire_step` towards
///    the point `approach_radius` from the deck centre on the rover's side, and look again. A
///    fix farther than `prior_gate` from the estimate is not the lander: it is never driven to.
///    No fix: look around (`search_pan_step_deg`), NOT_FOUND after `search_images` pairs; but
///    beyond `sight_range` the a-priori estimate leads a leg, and after two accepted fixes with
///    the estimate within 1 m (1 sigma) it leads up to two legs in a row after three misses.
///  - CLOSE_RANGE: sight a ramp's coded stripes (SightRamp) for the ramp's full pose; orbit the
///    lander (autonav legs of `circle_step_deg` on a circle `circle_margin` beyond the ramp
///    feet) until the chosen ramp is reachable; drive to the servo's start point `servo_run`
///    before the placement point on the ramp axis; then measure-and-correct: each step takes a
///    pair, computes the placement point P* = base - standoff * a (a the ramp's horizontal
///    up-axis) in the rover frame of that pair and drives a directed turn-straight-turn to it;
///    done when within `lateral_tolerance`, `along_tolerance` and `heading_tolerance_deg`, or
///    within the accept_* bounds after one back-up or on the last step; else PLACEMENT. Fewer than
///    `min_stripes` stripes here: TOO_FEW_STRIPES (no final servo).
///  - AT_RAMP_BASE: stands `hold_at_base_s` (the judge measures the placement here), then
///  - CLIMB (command.climb): one directed straight of standoff + ramp surface length + deck
///    apothem, tilt limit `climb_max_tilt_deg`; DONE when the pose has risen by half the deck
///    height and is level again, else MOBILITY.
///
/// Frames: site S (dl/pose), rover R, ramp-surface G (core/hwconfig lander_description.hpp).
/// Every placement quantity is computed in the rover frame of the pair it comes from, so pose
/// drift does not enter the final servo; site-frame estimates (lander centre, ramp bases) serve
/// the mast pointing and the legs between sightings.
///
/// Goal errors (msg::RendezvousFault): BAD_COMMAND (the field and value named), BUSY, NOT_FOUND,
/// TOO_FEW_STRIPES, STALE_POSE, MOBILITY, MAST, CAMERA, STOPPED, TIMEOUT, PLACEMENT. Every one
/// stops what the executor started and leaves it ready for the next command.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/apl/rendezvous/rendezvous_options.hpp"
#include "rover/apl/rendezvous/sightings.hpp"
#include "rover/base/time.hpp"
#include "rover/hwconfig/lander_description.hpp"
#include "rover/msg/arm.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/mast.hpp"
#include "rover/msg/mobility.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/rendezvous.hpp"

namespace rover::apl::rendezvous {

/// Id ranges of what the executor sends (other requesters use other prefixes).
inline constexpr std::uint32_t kMobilityIdBase = 0x52000000u;  ///< apl/mobility_command
inline constexpr std::uint32_t kMastIdBase = 0x52000000u;      ///< dl/mast_command
inline constexpr std::uint32_t kArmIdBase = 0x52000000u;       ///< dl/arm_command
inline constexpr std::uint32_t kCameraRequestPrefix = 3;       ///< ddl/camera_request ids 3 << 24

/// The ids an executor gives what it sends, one count per topic: `half` 0 for the lander
/// rendezvous (RendezvousExecutor), kScienceIdHalf for the science approach (TargetApproach), so
/// that neither takes the other's answer. The low 23 bits count from 1 and skip 0 on wrapping.
inline constexpr std::uint32_t kScienceIdHalf = 0x800000u;
class CommandIds {
 public:
  explicit CommandIds(std::uint32_t half) : half_(half) {}
  std::uint32_t Mobility() { return Next(kMobilityIdBase, &mobility_); }
  std::uint32_t Mast() { return Next(kMastIdBase, &mast_); }
  std::uint32_t Arm() { return Next(kArmIdBase, &arm_); }
  std::uint32_t Camera() { return Next(kCameraRequestPrefix << 24, &camera_); }

 private:
  std::uint32_t Next(std::uint32_t base, std::uint32_t* count) {
    std::uint32_t low = ++*count & (kScienceIdHalf - 1);
    if (low == 0) low = ++*count & (kScienceIdHalf - 1);
    return base | half_ | low;
  }
  std::uint32_t half_;
  std::uint32_t mobility_ = 0, mast_ = 0, arm_ = 0, camera_ = 0;
};


struct ExecutorOutput {
  std::vector<msg::MobilityCommand> mobility;
  std::vector<msg::MastCommand> mast;
  std::vector<msg::StereoRequest> camera;
  std::vector<msg::ArmCommand> arm;
  std::vector<msg::RendezvousStatus> statuses;
  std::vector<DetectionImage> images;
};

class RendezvousExecutor {
 public:
  /// Preconditions: options.Validate() and lander.Validate() are ok, vision is not null.
  RendezvousExecutor(const RendezvousOptions& options, const hwconfig::LanderDescription& lander,
                     std::shared_ptr<RendezvousVision> vision);

  ExecutorOutput OnCommand(const msg::RendezvousCommand& command, Time now);
  ExecutorOutput OnPose(const msg::PoseSample& pose, Time now);
  ExecutorOutput OnMobilityStatus(const msg::MobilityStatus& status, Time now);
  ExecutorOutput OnMastStatus(const msg::MastStatus& status, Time now);
  /// A NAVCAM pair; pairs that do not answer the outstanding request are ignored.
  ExecutorOutput OnStereoPair(const NavcamPair& pair, Time now);
  /// Time-outs, settling and holding (call at a few Hz).
  ExecutorOutput Step(Time now);

  const msg::RendezvousStatus& status() const { return status_; }
  bool busy() const { return wait_ != Wait::kNone; }

 private:
  enum class Wait { kNone, kMast, kSettle, kFrame, kDrive, kHold };
  enum class DriveKind { kLeg, kOrbit, kToServoStart, kServo, kClimb };
  struct RampGoal {  // site frame
    int ramp = -1;
    Eigen::Vector3d base = Eigen::Vector3d::Zero();
    Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  // horizontal, up the ramp
    double slope_len = 0.0;
  };

  void Reply(ExecutorOutput* out);
  void Fail(msg::RendezvousFault fault, const std::string& message, ExecutorOutput* out);
  void SetPhase(msg::RendezvousPhase phase, ExecutorOutput* out);
  bool PoseFresh(Time now) const;
  Eigen::Vector2d RoverXy() const;
  double RoverHeading() const;
  void LookAt(const Eigen::Vector3d& site_point, Time now, ExecutorOutput* out);
  void RequestPair(Time now, ExecutorOutput* out);
  void Drive(msg::MobilityCommand c, DriveKind kind, Time now, ExecutorOutput* out);
  void DriveTo(const Eigen::Vector2d& goal, double tolerance, DriveKind kind, Time now,
               ExecutorOutput* out);
  void LookAtLander(Time now, ExecutorOutput* out);
  // Where the mast looks for the lander (site frame, horizontal): the estimate or the look-around.
  Eigen::Vector2d LookTarget() const;
  void OnLanderFix(const LanderFix& fix, Time now, ExecutorOutput* out);
  // A long-range fix (deck centre c_site, covariance in R) consistent with the estimate?
  // range_conflict: on the bearing but not within the range gate.
  bool FarFixConsistent(const Eigen::Vector3d& c_site, const Eigen::Matrix3d& covariance_rover,
                        std::string* detail, bool* range_conflict) const;
  // Caps the estimate's information along the view at a sigma of relative_sigma x distance.
  void WeakenRange(double relative_sigma);
  // Close range when near the estimate, else the next leg towards the approach point.
  void Advance(Time now, ExecutorOutput* out);
  void OnRampFix(const RampFix& fix, Time now, ExecutorOutput* out);
  void AfterDrive(Time now, ExecutorOutput* out);
  void Orbit(Time now, ExecutorOutput* out);
  void StartClimb(Time now, ExecutorOutput* out);
  RampGoal RampGoalFromFix(const RampFix& fix) const;
  RampGoal OtherRamp(const RampGoal& g) const;
  Eigen::Vector2d ServoStart() const;
  double OrbitRadius() const;

  RendezvousOptions options_;
  hwconfig::LanderDescription lander_;
  std::shared_ptr<RendezvousVision> vision_;

  msg::RendezvousCommand command_;
  msg::RendezvousStatus status_;
  std::optional<msg::PoseSample> pose_;
  Wait wait_ = Wait::kNone;
  Time wait_since_;
  Time deadline_;
  CommandIds ids_{0};
  std::uint32_t outstanding_ = 0;  // id of the mast command, camera request or drive awaited
  DriveKind drive_kind_ = DriveKind::kLeg;
  double standoff_ = 1.0;

  // Lander estimate: information form of the deck centre (x, y) in the site frame.
  Eigen::Matrix2d info_ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d info_vec_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d center_ = Eigen::Vector2d::Zero();
  double center_z_ = 0.0;
  double search_bearing_offset_ = 0.0;  // [rad] look-around at a station
  int search_count_ = 0;
  int fixes_ = 0;       // accepted mid-range fixes of this command
  int blind_legs_ = 0;  // legs in a row led by the estimate alone
  int range_conflicts_ = 0;  // far fixes on the estimate's bearing but off its range since the last accepted one
  int mobility_retries_ = 0;
  int orbit_legs_ = 0;
  int servo_steps_ = 0;
  int backups_ = 0;  // servo steps that backed up to take out a lateral error
  std::optional<RampGoal> goal_ramp_;
  bool servo_started_ = false;
  double climb_start_z_ = 0.0;
};

}  // namespace rover::apl::rendezvous
