#pragma once
/// @file
/// The service's RendezvousVision: the long-range lander detector (long_range_detector.hpp,
/// when the prior is farther than `far_range`), the mid-range lander detector
/// (lander_detector.hpp) and the stripe detector with the ramp pose solver (stripe_detector.hpp,
/// ramp_pose.hpp) behind the executor's interface, with a drawing of every sighting for the run
/// folder.
///
/// Long range: the search window is the prior bearing +- atan(max(prior_gate, 0.1 R) / R) and
/// its range +- (prior_gate + 0.3 R); the fix's covariance is the detector's (sharp in bearing).
/// Between `far.min_range` and `far_range` a mid-range miss falls back to the long-range
/// detector (the mid-range one misses some views at 25-35 m).
/// Mid range: the deck centre in R is the left camera's centre plus the sighting's horizontal
/// range along its bearing, at deck height above the ground (R's z = 0); its covariance comes
/// from the range and bearing sigmas (a vertical sigma of half the deck height).
/// Close range: both images are searched; the ramp with most stripes in the left image is
/// solved with both cameras; base and yaw sigmas come from the pose covariance.

#include <memory>

#include "rover/apl/rendezvous/lander_detector.hpp"
#include "rover/apl/rendezvous/long_range_detector.hpp"
#include "rover/apl/rendezvous/ramp_pose.hpp"
#include "rover/apl/rendezvous/sightings.hpp"
#include "rover/apl/rendezvous/stripe_detector.hpp"
#include "rover/hwconfig/lander_description.hpp"

namespace rover::apl::rendezvous {

struct VisionOptions {
  /// [m] the executor's gate (rendezvous.prior_gate): the detector searches only where a fix
  /// could pass it (bearing window atan(gate / range), range window gate + 10 % of the range).
  double prior_gate = 8.0;
  LanderDetectorOptions lander;
  LongRangeOptions far;
  /// [m] a prior farther than this is searched with the long-range detector.
  double far_range = 30.0;
  StripeDetectorOptions stripes;
  RampPoseOptions pose;
};

class VisionPipeline final : public RendezvousVision {
 public:
  VisionPipeline(const hwconfig::LanderDescription& lander, const VisionOptions& options);

  Result<LanderFix> SightLander(const NavcamPair& pair,
                                const Eigen::Vector3d& prior_rover) override;
  Result<RampFix> SightRamp(const NavcamPair& pair) override;
  DetectionImage LastDrawing() override;

 private:
  // The long-range detector with its window about `prior` (bearing and range set).
  Result<LanderFix> SightFar(const NavcamPair& pair, LanderPrior prior);

  hwconfig::LanderDescription lander_;
  VisionOptions options_;
  DetectionImage drawing_;
  int sightings_ = 0;
};

}  // namespace rover::apl::rendezvous
