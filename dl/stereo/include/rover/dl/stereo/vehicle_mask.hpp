#pragma once
/// @file
/// The moving vehicle mask in 3-D (MER's "swept cylindrical volume", seed 000): range points that
/// lie on the rover's own wheels or body, or behind them as seen from the camera, are removed
/// before terrain assessment sees them.
///
/// Volumes (rover frame R: x forward, y left, z up; metres), from the rover description at zero
/// suspension angles (core/hwconfig):
///   corner wheel  the square prism about the wheel centre c that holds the wheel at every
///                 steering angle: |x - c_x|, |y - c_y| <= hypot(r, w/2) + wheel_margin_m;
///   middle wheel  the wheel's own box: |x - c_x| <= r + wheel_margin_m,
///                 |y - c_y| <= w/2 + wheel_margin_m;
///   every wheel   c_z - r - wheel_margin_m - support_depth_m <= z <= c_z + r + wheel_margin_m +
///                 wheel_lift_m: up to the wheel's top when the suspension lifts it by
///                 wheel_lift_m, and down through the ground it stands on;
///   body          the body box grown by body_margin_m on every side.
/// (r = wheel_radius, w = wheel_width.)
///
/// Below the ground. A cut of every point some depth below the contact plane would also remove
/// real depressions and drop-offs, which AutoNav must see (seed 003: it detected and avoided the
/// negative hazards of Meridiani), so there is none. Under a wheel, though, the ground is known
/// to be there and opaque: the wheel stands on it. So each wheel volume reaches support_depth_m
/// below the wheel, and a point under a wheel or seen through the ground under it is masked.
///
/// A point p seen from the optical centre e (both in R) is masked when it lies inside a volume,
/// or when the segment e -> p crosses a volume that does not contain e: the rover is opaque, so a
/// point behind its own wheel cannot have been seen, and a range there is a mismatch of the wheel
/// (the gross outliers far below the ground at the HAZCAMs' bottom corners). A volume containing
/// e (a margin reaching over the camera) only masks the points inside it.
///
/// The fixed pixel mask (MER's first mask, for parts that never move in the image: cabling, a
/// stowed arm, a solar panel) is an image file per camera, non-zero = rover, scaled (nearest
/// neighbour) to the rectified image and applied by the pipeline (status kVehicle).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::dl::stereo {

/// dl-stereo's keys vehicle_mask.*.
struct VehicleMaskOptions {
  bool enabled = true;
  double wheel_margin_m = 0.03;   ///< [m] added to the wheel's radius and half width
  double wheel_lift_m = 0.05;     ///< [m] the wheel volume reaches this far above the wheel top
  double support_depth_m = 3.0;   ///< [m] and this far below the wheel's contact with the ground
  double body_margin_m = 0.01;    ///< [m] added to the body box on every side
  /// Fixed pixel masks (image files, non-zero = rover; empty = none).
  std::string front_hazcam_pixels;
  std::string rear_hazcam_pixels;
  std::string navcam_pixels;

  /// Margins finite and within [0, 1] m, support_depth_m within [0, 10] m; messages start with
  /// the field.
  Status Validate() const;
  static void BindParams(ParamBinder<VehicleMaskOptions>& b);
};

/// What a masked point hit.
enum class VehiclePart { kNone = 0, kWheel, kBody };

class VehicleMask {
 public:
  /// One volume of the rover (see the file comment).
  struct Volume {
    Eigen::AlignedBox3d box;
    VehiclePart part = VehiclePart::kNone;
  };

  /// Precondition: rover.Validate() and options.Validate() are Ok.
  VehicleMask(const hwconfig::RoverDescription& rover, const VehicleMaskOptions& options);

  /// The six wheel volumes (wheel index order) and the body's.
  const std::vector<Volume>& volumes() const { return volumes_; }
  const VehicleMaskOptions& options() const { return options_; }

  /// The part that hides `point` from `eye` (both in R), kNone if none does (or disabled).
  VehiclePart Hides(const Eigen::Vector3d& eye, const Eigen::Vector3d& point) const;

  /// Masks an image of points: `xyz` CV_32FC3 in R (NaN where invalid), `status` CV_8UC1
  /// PixelStatus of the same size. Valid pixels hidden by a wheel become kWheel, by the body
  /// kVehicle, and their xyz NaN. Returns the number of pixels masked. Errors: sizes or types.
  Result<int> Apply(const Eigen::Vector3d& eye, cv::Mat* xyz, cv::Mat* status) const;

 private:
  VehicleMaskOptions options_;
  std::vector<Volume> volumes_;
};

/// Reads a fixed pixel mask (any 8- or 16-bit image; non-zero = rover) as CV_8UC1 0/255.
/// Errors name the file: missing, unreadable, empty.
Result<cv::Mat> LoadPixelMask(const std::string& path);

/// True if the segment a -> b meets the closed box (slab test).
bool SegmentMeetsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::AlignedBox3d& box);

}  // namespace rover::dl::stereo
