#pragma once
/// @file
/// Reading and writing data in the KITTI odometry layout, and KITTI's odometry error metric
/// (Geiger, Lenz & Urtasun, CVPR 2012), for the VO benchmark, the rover-vo tool and tests.
///
/// Folder layout: image_l/ and image_r/ (or KITTI's own image_0/ and image_1/) holding
/// rectified grey images with the same file names (sorted by name); calib.txt with the 3x4
/// projection matrices of the left and right cameras, one per line, 12 numbers each, row-major,
/// optionally prefixed by "P0:" / "P1:" (KITTI's file has P0..P3; the first two are used);
/// optionally times.txt (one time in seconds per frame) and poses.txt (ground truth).
///
/// Poses: one line per frame with the top 3x4 of T_0_i, the transform from frame i's left camera
/// to frame 0's left camera (x right, y down, z forward), row-major.
///
/// Metric: for every start frame i (every `step` frames) and every length L, the first frame j
/// with path length(i..j) >= L along the ground truth gives the error
///   E = (T_gt_i^-1 T_gt_j)^-1 (T_est_i^-1 T_est_j),
/// translational error |t(E)| / L and rotational error angle(E) / L; both are averaged over all
/// (i, L) pairs. KITTI uses L = 100..800 m; shorter sequences need shorter lengths.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/dl/vo/stereo_camera.hpp"
#include "rover/dl/vo/visual_odometry.hpp"

namespace rover::dl::vo::kitti {

struct Sequence {
  std::string folder;
  std::vector<std::string> left_files;   ///< full paths, sorted
  std::vector<std::string> right_files;  ///< full paths, same names as left
  std::vector<double> times;             ///< [s] per frame (times.txt, else 0.1 s steps)
  StereoCamera camera;                   ///< from calib.txt and the first image's size
  std::string poses_file;                ///< poses.txt if present, else empty

  std::size_t size() const { return left_files.size(); }
};

/// Parses calib.txt text into the left and right projection matrices. `source` names the file
/// in error messages.
Status ParseCalibration(const std::string& text, const std::string& source,
                        Eigen::Matrix<double, 3, 4>* p_left, Eigen::Matrix<double, 3, 4>* p_right);

/// Opens a sequence folder: checks the folders, the file lists, calib.txt and the image size.
Result<Sequence> OpenSequence(const std::string& folder);

/// Loads frame `index` as 8-bit grey images stamped with its time.
Result<StereoFrame> LoadFrame(const Sequence& sequence, std::size_t index);

/// Reads a KITTI pose file (12 numbers per line).
Result<std::vector<Eigen::Isometry3d>> ReadPoses(const std::string& path);
/// Writes poses in KITTI's format (12 numbers per line, %e).
Status WritePoses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses);
/// One pose as a KITTI line (no newline).
std::string FormatPose(const Eigen::Isometry3d& pose);

/// Prior for playing back datasets without wheel odometry: the first step gets a stationary prior
/// with wide sigmas, later steps the previous step's motion (constant velocity) with narrower
/// ones. Sigmas are 1-sigma per axis [m] and [rad].
struct ConstantVelocityModel {
  double first_sigma_translation = 2.0;
  double first_sigma_rotation = 0.05;
  double sigma_translation = 0.3;
  double sigma_rotation = 0.02;

  /// `last` is the previous step's estimate (status kNoReference for the first step).
  MotionPrior Next(const MotionEstimate& last) const;
};

struct ErrorMetrics {
  double translation_percent = 0.0;  ///< mean |t(E)| / L * 100 over segments
  double rotation_deg_per_m = 0.0;   ///< mean angle(E) / L over segments [deg/m]
  int segments = 0;                  ///< (start, length) pairs evaluated
  double path_length = 0.0;          ///< [m] ground-truth path length of the whole sequence
  double endpoint_percent = 0.0;     ///< |t_end_est - t_end_gt| / path length * 100
  double endpoint_m = 0.0;           ///< [m]
};

/// Segment lengths for Evaluate(): KITTI's 100, 200, ..., 800 m that fit a path of this length
/// (at least two of them), else five lengths of path / 6 rounded to whole metres (10, 20, ...,
/// 50 m for a 60 m path).
std::vector<double> SegmentLengths(double path_length);

/// Ground-truth path length [m] of a pose list.
double PathLength(const std::vector<Eigen::Isometry3d>& poses);

/// KITTI odometry error of `estimate` against `truth` (same length, T_0_i each).
ErrorMetrics Evaluate(const std::vector<Eigen::Isometry3d>& truth,
                      const std::vector<Eigen::Isometry3d>& estimate,
                      const std::vector<double>& lengths, int step = 1);

}  // namespace rover::dl::vo::kitti
