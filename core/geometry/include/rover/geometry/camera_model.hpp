#pragma once
/// @file
/// Camera models: JPL's CAHV, CAHVOR and CAHVORE and the pinhole with Brown radial distortion,
/// behind one value type, CameraModel, plus conversions between them, resampling (Scale), moving
/// a model into another frame (Transform) and stereo rectification (RectifyStereoPair).
///
/// Pixels. A pixel coordinate is (x, y) = (sample, line) = (column, row) in pixels. The CENTRE of
/// the top-left pixel is (0, 0) and pixel (i, j) covers [i - 0.5, i + 0.5) x [j - 0.5, j + 0.5);
/// the image spans [-0.5, width - 0.5) x [-0.5, height - 0.5) and its centre is
/// ((width - 1) / 2, (height - 1) / 2). This is the convention of JPL's camera models and of
/// OpenCV (cv::remap, cv::projectPoints), so coordinates pass between them unchanged.
///
/// Frames and units. Every model is expressed in a "reference frame" (e.g. the rover frame, or
/// MSL's ROVER_NAV_FRAME as stored in PDS labels); Project takes points and Unproject returns
/// rays in that frame, lengths in metres. Transform() re-expresses a model in another frame. The
/// camera frame of the pinhole model is x right, y down, z forward (the optical axis).
///
/// CAHV (Yakimovsky & Cunningham 1978). C is the camera centre, A the unit pointing axis, H and V
/// the horizontal and vertical vectors [px]. A point P projects to
///   x = (P - C).H / (P - C).A,    y = (P - C).V / (P - C).A.
/// Writing H = hs H' + hc A and V = vs V' + vc A with unit H', V' perpendicular to A gives the
/// intrinsics (ComputeIntrinsics): principal point hc = A.H, vc = A.V, focal lengths
/// hs = |A x H|, vs = |A x V| [px], and theta = the angle from H' to V' about A (+pi/2 for an
/// ideal camera whose H', V', A are the camera frame's x, y, z). CAHV is a pinhole camera: with
/// theta = pi/2 it equals PinholeRadial with fx = hs, fy = vs, cx = hc, cy = vc, k = 0 and the
/// camera frame's axes x = H', y = V', z = A at C.
///
/// CAHVOR (Gennery 1992) adds radial distortion about the optical axis O (unit) with
/// coefficients R = (r0, r1, r2). With p = P - C, zeta = p.O, lambda = p - zeta O,
/// tau = lambda.lambda / zeta^2 (tan^2 of the angle off O) and mu = r0 + r1 tau + r2 tau^2, the
/// point is moved to p' = p + mu lambda and projected with CAHV. In angle terms the tangent of
/// the angle off O is multiplied by (1 + mu).
///
/// CAHVORE (Gennery 2006, "Generalized camera calibration including fish-eye lenses") adds a
/// moving entrance pupil and a choice of projection ("linearity" L):
///   1. the ray from P enters at C' = C + s(theta) O, s = (theta / sin theta - 1) *
///      (e0 + e1 theta^2 + e2 theta^4), where theta is the angle between the ray and O; theta
///      solves  zeta sin theta - |lambda| cos theta = (theta - sin theta)(e0 + e1 theta^2 +
///      e2 theta^4)  (Newton's method);
///   2. theta maps to chi = tan(L theta) / L (L > 0), theta (L = 0, equidistant fisheye) or
///      sin(L theta) / L (L < 0); L = 1 is the perspective case, chi = tan theta;
///   3. radial distortion as CAHVOR: chi' = chi (1 + r0 + r1 chi^2 + r2 chi^4);
///   4. the direction O + chi' lambda / |lambda| is projected with CAHV.
/// With L = 1 and E = 0 CAHVORE equals CAHVOR. Unprojection inverts 4 -> 3 (Newton) -> 2
/// (closed form) -> 1 (the pupil position follows from theta), so it is exact up to the Newton
/// tolerance; the ray origin is C' (not C) when E != 0.
///
/// PinholeRadial: with the point in the camera frame (X, Y, Z) = pose^-1 * P, Z > 0,
///   xn = X / Z, yn = Y / Z, r^2 = xn^2 + yn^2, s = 1 + k1 r^2 + k2 r^4 + k3 r^6,
///   u = fx xn s + cx,   v = fy yn s + cy      (OpenCV's model with p1 = p2 = 0).
///
/// Validity. Project returns nullopt for points behind the camera (CAHV: (P - C).A <= 0,
/// CAHVOR: zeta <= 0, pinhole: Z <= 0; CAHVORE: theta outside [0, min(pi, pi / (2 |L|))), so a
/// fisheye (L = 0) projects everything but the exact backward axis, usually far outside the
/// image) and where the radial distortion polynomial is not increasing (the model folds back on
/// itself, so the pixel would be a ghost). Unproject returns nullopt where the distortion cannot
/// be inverted. Neither checks that the pixel lies inside the image (use InImage).
///
/// References: Yakimovsky & Cunningham, CGIP 7, 1978; Gennery, "Least-squares camera calibration
/// including lens distortion and automatic editing of calibration points", 1992/2001; Gennery,
/// IJCV 68(3), 2006; Di & Li, "CAHVOR camera model and its photogrammetric conversion", 2004.

#include <optional>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rover/base/status.hpp"

namespace rover::geometry {

/// A viewing ray in the model's reference frame: points origin + t direction, t > 0.
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      ///< [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit
};

/// JPL linear model. See the file comment for the projection.
struct Cahv {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();   ///< C: camera centre [m]
  Eigen::Vector3d a = Eigen::Vector3d::UnitZ();  ///< A: pointing axis (unit, see Create)
  Eigen::Vector3d h = Eigen::Vector3d::Zero();   ///< H: horizontal vector [px]
  Eigen::Vector3d v = Eigen::Vector3d::Zero();   ///< V: vertical vector [px]
};

/// JPL model with radial distortion about the optical axis O.
struct Cahvor {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();   ///< C [m]
  Eigen::Vector3d a = Eigen::Vector3d::UnitZ();  ///< A (unit)
  Eigen::Vector3d h = Eigen::Vector3d::Zero();   ///< H [px]
  Eigen::Vector3d v = Eigen::Vector3d::Zero();   ///< V [px]
  Eigen::Vector3d o = Eigen::Vector3d::UnitZ();  ///< O: optical axis (normalised by Create)
  Eigen::Vector3d r = Eigen::Vector3d::Zero();   ///< R = (r0, r1, r2), dimensionless
};

/// CAHVORE projection type. JPL's codes: perspective = 1, fisheye = 2, general = 3.
enum class CahvoreType { kPerspective = 1, kFisheye = 2, kGeneral = 3 };

/// JPL model for wide-angle and fisheye lenses (moving entrance pupil, E).
struct Cahvore {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();   ///< C [m]
  Eigen::Vector3d a = Eigen::Vector3d::UnitZ();  ///< A (unit)
  Eigen::Vector3d h = Eigen::Vector3d::Zero();   ///< H [px]
  Eigen::Vector3d v = Eigen::Vector3d::Zero();   ///< V [px]
  Eigen::Vector3d o = Eigen::Vector3d::UnitZ();  ///< O (normalised by Create)
  Eigen::Vector3d r = Eigen::Vector3d::Zero();   ///< R = (r0, r1, r2)
  Eigen::Vector3d e = Eigen::Vector3d::Zero();   ///< E = (e0, e1, e2) [m]
  CahvoreType type = CahvoreType::kPerspective;
  double parameter = 0.0;  ///< linearity L for kGeneral (ignored otherwise)

  /// L: 1 for kPerspective, 0 for kFisheye, `parameter` for kGeneral.
  double Linearity() const;
};

/// Pinhole camera with Brown radial distortion (see the file comment).
struct PinholeRadial {
  double fx = 0.0;  ///< [px]
  double fy = 0.0;  ///< [px]
  double cx = 0.0;  ///< [px] principal point, pixel-centre convention (top-left centre = 0)
  double cy = 0.0;  ///< [px]
  double k1 = 0.0;  ///< radial coefficients on normalised coordinates
  double k2 = 0.0;
  double k3 = 0.0;
  /// reference_from_camera: the camera frame (x right, y down, z forward) in the reference frame.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
};

/// Intrinsic parameters implied by the C, A, H, V part of a JPL model (see the file comment).
struct Intrinsics {
  double hc = 0.0;     ///< A.H [px]
  double vc = 0.0;     ///< A.V [px]
  double hs = 0.0;     ///< |A x H| [px]
  double vs = 0.0;     ///< |A x V| [px]
  double theta = 0.0;  ///< angle from H' to V' about A [rad]; +pi/2 for an ideal camera
};

Intrinsics ComputeIntrinsics(const Cahv& m);
Intrinsics ComputeIntrinsics(const Cahvor& m);
Intrinsics ComputeIntrinsics(const Cahvore& m);

/// A validated camera model of one of the four kinds with its image size.
class CameraModel {
 public:
  enum class Kind { kCahv, kCahvor, kCahvore, kPinholeRadial };
  using Variant = std::variant<Cahv, Cahvor, Cahvore, PinholeRadial>;

  /// Validate and wrap a model. Errors (InvalidArgument, naming the field): non-finite values,
  /// width or height < 1, |A| not within 1e-3 of 1, H, V, A (nearly) coplanar, |O| not within
  /// 1e-3 of 1, unknown CAHVORE type, 1 + r0 <= 0, pinhole focal lengths <= 0 or a pose whose
  /// rotation is not orthonormal (1e-6).
  /// Labels print A rounded or slightly off unit length (MSL NAVCAM: |A| = 1 - 8.5e-6). Create
  /// therefore divides A, H and V by |A| (which leaves every projection unchanged, x = p.H / p.A)
  /// and normalises O, so that the stored model's intrinsics are exact: the axis projects onto
  /// (hc, vc). Intrinsics computed from the raw label vectors are |A|^2 times these (NAVCAM: up
  /// to 5e-3 px smaller).
  static Result<CameraModel> Create(const Cahv& m, int width, int height);
  static Result<CameraModel> Create(const Cahvor& m, int width, int height);
  static Result<CameraModel> Create(const Cahvore& m, int width, int height);
  static Result<CameraModel> Create(const PinholeRadial& m);  ///< size from m.width, m.height

  Kind kind() const { return static_cast<Kind>(model_.index()); }
  int width() const { return width_; }
  int height() const { return height_; }
  const Variant& variant() const { return model_; }
  /// The model if it is of kind T (Cahv, Cahvor, Cahvore or PinholeRadial), else nullptr.
  template <class T>
  const T* As() const {
    return std::get_if<T>(&model_);
  }

  /// The nominal projection centre in the reference frame (C, or the pinhole pose translation).
  /// For CAHVORE with E != 0 the actual ray origins move along O (see Unproject).
  Eigen::Vector3d Center() const;

  /// Pixel of point `p_ref` (reference frame, metres); nullopt if behind the camera or outside
  /// the model's valid range (see the file comment). The pixel may lie outside the image.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_ref) const;

  /// As Project, and if `jacobian` is not null and the result is valid, sets it to the 2x3
  /// derivative d(pixel)/d(p_ref) [px/m]. Analytic for CAHV, CAHVOR and PinholeRadial; central
  /// differences (relative step 1e-6) for CAHVORE.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_ref,
                                         Eigen::Matrix<double, 2, 3>* jacobian) const;

  /// Pixel of the point at infinity in `direction` (reference frame, any length > 0), e.g. the
  /// sun or a distant landmark; nullopt as for Project. For all kinds but CAHVORE with E != 0
  /// this equals Project(Center() + t direction) for every t > 0.
  std::optional<Eigen::Vector2d> ProjectDirection(const Eigen::Vector3d& direction) const;

  /// Viewing ray of `pixel` in the reference frame (unit direction); nullopt if the distortion
  /// cannot be inverted there (far outside the calibrated field, or a non-finite pixel).
  /// Project(ray.origin + t ray.direction) == pixel for every t > 0 (to ~1e-9 px).
  std::optional<Ray> Unproject(const Eigen::Vector2d& pixel) const;

  /// True if `pixel` lies in the image, i.e. in [-0.5, width - 0.5) x [-0.5, height - 0.5).
  bool InImage(const Eigen::Vector2d& pixel) const;

 private:
  CameraModel(Variant model, int width, int height);
  friend CameraModel Scale(const CameraModel& model, double sx, double sy);
  friend CameraModel Transform(const CameraModel& model, const Eigen::Isometry3d& new_from_old);

  Variant model_;
  int width_ = 0;
  int height_ = 0;
  double fold_ = 0.0;  // radial-distortion limit (tangent / chi / radius) where it folds back
};

/// Name of a kind: "CAHV", "CAHVOR", "CAHVORE", "PINHOLE_RADIAL".
std::string_view KindName(CameraModel::Kind kind);

// ---- resampling and frames ----------------------------------------------------------------

/// The model of the image resampled by factors (sx, sy) (0.5 = halve the resolution; software
/// downsampling by n x n binning is 1/n). Pixel areas stay aligned: the image's outer edges map
/// onto each other, i.e. with the pixel-centre convention above
///   x_new = sx (x_old + 0.5) - 0.5,   y_new = sy (y_old + 0.5) - 0.5,
/// which is also cv::resize's mapping. Exact for every kind: JPL models get
/// H' = sx H + (sx - 1)/2 A, V' = sy V + (sy - 1)/2 A (O, R, E unchanged); the pinhole gets
/// fx' = sx fx, cx' = sx (cx + 0.5) - 0.5 (same for y). New size = max(1, round(size * s)).
/// Preconditions: sx, sy finite and > 0.
CameraModel Scale(const CameraModel& model, double sx, double sy);
inline CameraModel Scale(const CameraModel& model, double factor) {
  return Scale(model, factor, factor);
}

/// The same camera expressed in another frame: for a model in frame "old" returns the model in
/// frame "new", p_new = new_from_old * p_old (e.g. camera-head frame -> rover frame with
/// new_from_old = rover_from_head as the mast pans and tilts). C' = T C; A, H, V, O rotate;
/// R, E unchanged; pinhole pose' = new_from_old * pose. Exact.
CameraModel Transform(const CameraModel& model, const Eigen::Isometry3d& new_from_old);

// ---- conversions --------------------------------------------------------------------------

/// Options of the least-squares conversions (ToPinholeRadial, ToCahvor).
struct FitOptions {
  int grid_cols = 32;       ///< fit samples across the image (pixel centres, corners included)
  int grid_rows = 32;       ///< fit samples down the image
  int max_iterations = 50;  ///< Gauss-Newton iterations (ToPinholeRadial)
  /// Checks grid sizes >= 4 and max_iterations >= 1.
  Status Validate() const;
};

/// A converted model and how well it reproduces the source model over the image: the distance
/// [px] between each pixel of a validation grid (2x denser than the fit grid, corners included)
/// and the converted model's projection of the source model's ray through that pixel.
template <class T>
struct ModelFit {
  T model;
  double rms_error_px = 0.0;
  double max_error_px = 0.0;
};

/// PinholeRadial equivalent of a CAHV, CAHVOR or CAHVORE model (a PinholeRadial is returned
/// unchanged). The camera frame is z = A and x, y = H', V' (made orthogonal symmetrically if
/// theta != pi/2), at C.
///  * CAHV with theta = pi/2: exact, fx = hs, fy = vs, cx = hc, cy = vc, k = 0.
///  * CAHVOR: starts from the closed form that is exact when O = A (fx = hs (1 + r0),
///    fy = vs (1 + r0), k1 = r1 / (1 + r0), k2 = r2 / (1 + r0), k3 = 0), then fits fx, fy, cx,
///    cy, k1, k2, k3 by Gauss-Newton to the model's rays over the image (non-linear least
///    squares on pixel error).
///  * CAHVORE: the same fit; the moving pupil cannot be represented (rays are treated as
///    starting at C), so expect larger residuals for fisheye lenses.
/// Errors: InvalidArgument for a mirrored model (theta < 0), a pixel whose ray is 90 deg or more
/// off A (not representable by a pinhole), or bad options.
Result<ModelFit<PinholeRadial>> ToPinholeRadial(const CameraModel& model,
                                                const FitOptions& options = {});

/// CAHV model of a distortion-free pinhole (exact): C = pose translation, A = z axis,
/// H = fx x + cx A, V = fy y + cy A with x, y, z the camera axes in the reference frame.
/// Error (InvalidArgument) if k1, k2 or k3 is not zero.
Result<Cahv> ToCahv(const PinholeRadial& pinhole);

/// CAHVOR model of a pinhole with radial distortion: C, A, H, V as ToCahv, O = A, r0 = 0 and
/// (r1, r2) = (k1, k2), which is exact if k3 == 0; otherwise (r0, r1, r2) are fitted by linear
/// least squares on pixel error over the image.
Result<ModelFit<Cahvor>> ToCahvor(const PinholeRadial& pinhole, const FitOptions& options = {});

// ---- stereo rectification -----------------------------------------------------------------

/// Options of RectifyStereoPair.
struct RectifyOptions {
  int width = 0;             ///< rectified image width [px]; 0 = the left input's width
  int height = 0;            ///< rectified image height [px]; 0 = the left input's height
  double focal_px = 0.0;     ///< rectified focal length [px]; 0 = mean of both inputs' hs and vs
  bool compute_maps = true;  ///< fill the remap tables
  /// Checks sizes >= 0 and focal_px >= 0, finite.
  Status Validate() const;
};

/// Marks a rectified pixel whose source lies outside the model's valid range in the remap
/// tables; any value outside the source image makes cv::remap use its border mode.
inline constexpr float kUnmappedPixel = -1.0e6F;

/// A rectified ("warped", JPL) stereo pair: two linear CAHV models with identical A, H, V whose
/// rows are parallel to the baseline, so a 3D point lands on the same row in both images, with
/// disparity  d = x_left - x_right = focal_px * baseline_m / z,  z = (P - C_left).A the depth
/// along the common axis [m]. Principal point at the image centre ((w - 1)/2, (h - 1)/2).
struct RectifiedPair {
  CameraModel left;         ///< kind kCahv
  CameraModel right;        ///< kind kCahv, same A, H, V as `left`
  double baseline_m = 0.0;  ///< (C_right - C_left).H' > 0 when the right camera is to the right
  double focal_px = 0.0;    ///< hs = vs of both rectified models
  /// Remap tables, row-major, size width * height each (empty if !compute_maps): rectified pixel
  /// (x, y) takes its value from source pixel (map_x[y w + x], map_y[y w + x]) of the original
  /// left (right) image; pass them to cv::remap as CV_32FC1 maps.
  std::vector<float> left_map_x, left_map_y, right_map_x, right_map_y;
};

/// Rectifies a stereo pair of any kinds, as JPL's "warp models": rectified x axis along the
/// baseline C_right - C_left (oriented like the inputs' H'), z axis = the mean of the two input
/// pointing axes (A, or the pinhole z axis) made perpendicular to x, y = z x x; each camera
/// keeps its own centre C. The remap tables follow ray directions (points at infinity), which is
/// exact except for CAHVORE inputs with E != 0, whose pupil shift (millimetres) they ignore.
/// Errors (InvalidArgument): bad options, baseline < 1e-9 m, baseline within 1 deg of the
/// mean pointing axis (forward stereo cannot be row-aligned), or a mirrored input.
Result<RectifiedPair> RectifyStereoPair(const CameraModel& left, const CameraModel& right,
                                        const RectifyOptions& options = {});

}  // namespace rover::geometry
