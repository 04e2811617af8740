#pragma once
/// @file
/// Fake dl-pose (header only; target rover_test_fakes): publishes dl/pose samples that say what
/// the test wants the rover's pose estimate to be, for services that consume it (dl-stereo,
/// dl-vo, dl-locomotion; the APL later). No filter, no noise: the sample is exactly `state`.
///
///   testing::FakePose pose;
///   ASSERT_TRUE(pose.Create(harness.peer()).ok());
///   ASSERT_TRUE(harness.SpinUntil([&] { return pose.Matched(); }));
///   pose.state.SetPose(site_from_rover);
///   ASSERT_TRUE(pose.Publish(harness.now()).ok());

#include <Eigen/Geometry>

#include "rover/base/clock.hpp"
#include "rover/base/status.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::testing {

/// The estimate a FakePose publishes.
struct FakePoseState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m] rover origin in the site frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< site from rover
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();               ///< [m/s] in the rover frame
  double odometer = 0.0;                                            ///< [m] path length driven
  bool stationary = false;
  double variance = 0.0;  ///< the diagonal of the 6x6 covariance [m^2, rad^2] (0: none)

  /// Position and orientation from the site-from-rover transform.
  void SetPose(const Eigen::Isometry3d& site_from_rover) {
    position = site_from_rover.translation();
    orientation = Eigen::Quaterniond(site_from_rover.linear());
  }
};

/// The dl/pose sample of `state`, stamped `stamp`, frame "site" (as dl-pose sends it).
inline rover_dl_PoseEstimate PoseEstimateMessage(Time stamp, const FakePoseState& state) {
  rover_dl_PoseEstimate p{};
  p.header.stamp_ns = stamp.ns;
  dds::CopyString(p.header.frame_id, "site");
  p.pose.position = {state.position.x(), state.position.y(), state.position.z()};
  const Eigen::Quaterniond& q = state.orientation;
  p.pose.orientation = {q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 6; ++i) p.covariance[i * 7] = state.variance;
  p.velocity = {state.velocity.x(), state.velocity.y(), state.velocity.z()};
  p.stationary = state.stationary;
  p.odometer = state.odometer;
  return p;
}

/// Plays dl-pose on the test's participant.
class FakePose {
 public:
  Status Create(const dds::Participant& p) {
    auto w = dds::Writer<rover_dl_PoseEstimate>::Create(p, "dl/pose");
    if (!w.ok()) return w.status();
    writer_ = std::move(*w);
    return Status::Ok();
  }
  /// True once `readers` subscribers (the services under test) matched.
  bool Matched(int readers = 1) const { return writer_.MatchedReaders() >= readers; }

  /// Publishes `state` stamped `stamp`.
  Status Publish(Time stamp) { return writer_.Write(PoseEstimateMessage(stamp, state)); }

  FakePoseState state;

 private:
  dds::Writer<rover_dl_PoseEstimate> writer_;
};

}  // namespace rover::testing
