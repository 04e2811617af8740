#pragma once
/// @file
/// A small kinematic world for driving the MobilityManager in-process (test code only):
///  - terrain: tests/support's RockField (flat ground with half-ellipsoid rocks), or any Scene
///    (the autonav-kinematic tool's is a sim/terrain field seen by ray-cast HAZCAMs);
///  - locomotion: drive requests are integrated into the rover's planar pose at `speed` [m/s]
///    (arcs, straights) or `turn_rate` [rad/s] (turns in place), reported DRIVING / TURNING every
///    tick while they run (as locomotion does at 8 Hz) and DONE when finished;
///    STOP ends a running drive at once (FAILED / STOP_COMMAND);
///  - stereo: a range request is captured at the time and pose it arrives and delivered
///    `image_latency_s` later: RockField's synthetic HAZCAM image (exact, occluded points
///    invalid).
/// Run() steps the world and the manager every `dt` until the manager's command ends.
/// Deterministic: no randomness but the caller's seeded rock placement.

#include <functional>

#include "rover/base/cpu_time.hpp"
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/testing/fakes/rock_field.hpp"

namespace rover::apl::mobility::testing {

/// A dl/drive_status as locomotion reports the end of a drive (the fields the manager reads).
DriveStatus DriveReport(std::uint32_t command_id, DriveState state, DriveTermination termination,
                        double distance_done, std::string message);

using Rock = rover::testing::FieldRock;

struct WorldOptions {
  double dt = 0.1;                    ///< [s] simulation step
  double speed = 0.25;                ///< [m/s] drive speed (faster than MER to keep tests short)
  double turn_rate = 0.5;             ///< [rad/s]
  double image_latency_s = 1.0;       ///< [s] request to delivery
  rover::testing::HazcamSpec camera;  ///< the synthetic HAZCAMs (tests/support rock_field.hpp)
  bool deliver_images = true;         ///< false: range requests are never answered
  int lose_requests = 0;              ///< the first N range requests are lost (a restarted stereo)
  bool deliver_poses = true;          ///< false: dl/pose stops
  bool report_progress = true;        ///< false: a running drive reports nothing until it ends
};

/// What the rover drives through, as the fake stereo sees it. The default scene is the world's
/// own RockField; a caller's scene replaces it for capture, pose height and clearance.
class Scene {
 public:
  virtual ~Scene() = default;
  /// The rover's site pose when its planar pose is `pose` (its z and attitude on the ground).
  virtual Eigen::Isometry3d SiteFromRover(const Pose2& pose) const = 0;
  /// The range scan of `camera` from `pose`, points in the rover frame (capture_time, camera
  /// name and site_from_rover are filled in by the world).
  virtual nav_core::RangeScan Capture(const Pose2& pose, CameraId camera) const = 0;
  /// [m] distance from (x, y) to the nearest hazard's edge (negative inside one).
  virtual double Clearance(double x, double y) const = 0;
};

class FakeWorld {
 public:
  /// `scene` (optional, not owned, outlives the world) replaces the world's rock field.
  FakeWorld(MobilityManager* manager, WorldOptions options = {}, const Scene* scene = nullptr);

  std::vector<Rock>& rocks() { return field_.rocks(); }
  /// Adds rocks of the given size along the segment a..b, `spacing` apart.
  void AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing, double radius,
               double height);
  /// Scatters `n` rocks (seeded) in the box [x0, x1] x [y0, y1], none within `clear` of the
  /// points in `keep_clear`.
  void Scatter(std::uint32_t seed, int n, double x0, double x1, double y0, double y1, double radius,
               double height, const std::vector<Eigen::Vector2d>& keep_clear, double clear);

  double HeightAt(double x, double y) const;
  Pose2& pose() { return pose_; }
  Time now() const { return now_; }
  /// The rover's exact pose now, as dl/pose would carry it.
  PoseSample PoseNow() const;
  /// The synthetic scan from the current pose (for tests of the world itself).
  nav_core::RangeScan Capture(CameraId camera) const;

  /// Sends a command and steps until its terminal status (or `max_s` of simulated time).
  /// Returns the terminal status of that command (state kRunning if it never ended).
  MobilityStatus Run(const MobilityCommand& command, double max_s);
  /// Feeds one manager output into the world (drives, range requests), collecting statuses.
  void Absorb(const MobilityOutput& out);
  /// Advances one dt: drive integration, image delivery, pose, manager Step.
  void Tick();

  /// Closest approach of the rover centre to any rock's edge over all ticks [m].
  double min_rock_clearance() const { return min_clearance_; }
  const std::vector<MobilityStatus>& statuses() const { return statuses_; }
  const std::vector<DriveCommand>& drives() const { return drives_; }
  const std::vector<RangeRequest>& range_requests() const { return ranges_; }
  int arc_vote_snapshots() const { return arc_votes_; }
  /// [s] thread CPU time spent inside the manager's calls (assessment and path selection
  /// included; the world's own ray casting not).
  double manager_cpu_s() const { return manager_cpu_s_; }
  /// Called on every range scan before delivery (tests corrupt it here).
  std::function<void(nav_core::RangeScan*, CameraId*)> tamper_image;
  /// Called on every arc-vote snapshot the manager publishes (tools print them).
  std::function<void(const ArcVotesSnapshot&)> on_arc_votes;
  /// Called on every pose before delivery.
  std::function<void(PoseSample*)> tamper_pose;

 private:
  template <class F>
  MobilityOutput Timed(F f) {
    const double t0 = ThreadCpuSeconds();
    MobilityOutput out = f();
    manager_cpu_s_ += ThreadCpuSeconds() - t0;
    return out;
  }
  double manager_cpu_s_ = 0.0;

 public:

 private:
  struct Image {
    nav_core::RangeScan scan;
    CameraId camera;
    std::uint32_t id;
    Time due;
  };
  void Deliver(const MobilityOutput& out);

  MobilityManager* manager_;
  WorldOptions options_;
  const Scene* scene_;
  rover::testing::RockField field_;
  Pose2 pose_;
  Time now_;
  std::optional<DriveCommand> drive_;
  double drive_done_ = 0.0;  // [m] or [rad] so far
  std::vector<Image> images_;
  std::vector<MobilityStatus> statuses_;
  std::vector<DriveCommand> drives_;
  std::vector<RangeRequest> ranges_;
  int arc_votes_ = 0;
  double min_clearance_ = 1e9;
};

/// A manager with GESTALT (default options) injected.
MobilityManager MakeGestaltManager(const MobilityOptions& options = {});

}  // namespace rover::apl::mobility::testing
