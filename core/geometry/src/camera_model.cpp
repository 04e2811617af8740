// Camera models: validation, projection, unprojection and Jacobians. The maths is stated in
// camera_model.hpp; the notation here follows it (p = P - C, zeta, lambda, tau, mu, chi, theta).

#include "rover/geometry/camera_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "camera_internal.hpp"
#include "rover/base/check.hpp"

namespace rover::geometry {
namespace internal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Beyond this tangent/radius (89.994 deg off axis) a model is not used.
constexpr double kMaxT = 1e4;

// Positive real roots of a u^2 + b u + c, ascending.
std::vector<double> PositiveQuadraticRoots(double a, double b, double c) {
  std::vector<double> roots;
  if (a == 0.0) {
    if (b != 0.0) roots.push_back(-c / b);
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      roots.push_back(q / a);
      if (q != 0.0) roots.push_back(c / q);
    }
  }
  std::erase_if(roots, [](double r) { return !(r > 0.0); });
  std::sort(roots.begin(), roots.end());
  return roots;
}

}  // namespace

double OddPolynomial::Value(double t) const {
  const double t2 = t * t;
  return t * (c0 + t2 * (c1 + t2 * (c2 + t2 * c3)));
}

double OddPolynomial::Derivative(double t) const {
  const double t2 = t * t;
  return c0 + t2 * (3.0 * c1 + t2 * (5.0 * c2 + t2 * 7.0 * c3));
}

OddPolynomial MakeOddPolynomial(double c0, double c1, double c2, double c3) {
  OddPolynomial p{c0, c1, c2, c3, kInf};
  // g'(t) = q(u) = c0 + 3 c1 u + 5 c2 u^2 + 7 c3 u^3 with u = t^2 > 0. q is monotonic between
  // the roots of q'(u) = 3 c1 + 10 c2 u + 21 c3 u^2, so look for the first sign change of q on
  // each of those intervals and bisect it.
  const auto q = [&](double u) { return c0 + u * (3.0 * c1 + u * (5.0 * c2 + u * 7.0 * c3)); };
  std::vector<double> breaks = PositiveQuadraticRoots(21.0 * c3, 10.0 * c2, 3.0 * c1);
  const double u_max = kMaxT * kMaxT;
  std::erase_if(breaks, [&](double u) { return u >= u_max; });
  breaks.push_back(u_max);
  double lo = 0.0;
  for (const double hi_break : breaks) {
    if (q(hi_break) <= 0.0) {
      double a = lo;
      double b = hi_break;
      for (int i = 0; i < 200 && b - a > 1e-15 * b; ++i) {
        const double m = 0.5 * (a + b);
        (q(m) > 0.0 ? a : b) = m;
      }
      p.fold = std::sqrt(a);
      return p;
    }
    lo = hi_break;
  }
  return p;
}

std::optional<double> OddPolynomial::Invert(double target) const {
  if (!std::isfinite(target) || target < 0.0) return std::nullopt;
  if (target == 0.0) return 0.0;
  double lo = 0.0;
  double hi = 0.0;
  if (std::isfinite(fold)) {
    if (target >= Value(fold)) return std::nullopt;
    hi = fold;
  } else {
    hi = target / c0;
    int n = 0;
    while (Value(hi) < target) {
      hi *= 2.0;
      if (++n > 60 || hi > kMaxT) return std::nullopt;
    }
  }
  // Safeguarded Newton: Newton steps that leave the bracket become bisections.
  double t = std::clamp(target / c0, lo, hi);
  for (int i = 0; i < 200; ++i) {
    const double g = Value(t) - target;
    if (g == 0.0) return t;
    (g < 0.0 ? lo : hi) = t;
    const double d = Derivative(t);
    double next = d > 0.0 ? t - g / d : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= 1e-16 * next || hi - lo <= 1e-16 * hi) return next;
    t = next;
  }
  return t;
}

OddPolynomial RadialPolynomialOf(const CameraModel::Variant& model, double fold) {
  if (const auto* m = std::get_if<Cahvor>(&model)) {
    return {1.0 + m->r.x(), m->r.y(), m->r.z(), 0.0, fold};
  }
  if (const auto* m = std::get_if<Cahvore>(&model)) {
    return {1.0 + m->r.x(), m->r.y(), m->r.z(), 0.0, fold};
  }
  if (const auto* m = std::get_if<PinholeRadial>(&model)) {
    return {1.0, m->k1, m->k2, m->k3, fold};
  }
  return {1.0, 0.0, 0.0, 0.0, kInf};
}

OddPolynomial RadialPolynomialOf(const CameraModel::Variant& model) {
  const OddPolynomial p = RadialPolynomialOf(model, kInf);
  return MakeOddPolynomial(p.c0, p.c1, p.c2, p.c3);
}

Eigen::Vector3d CahvRayDirection(const Eigen::Vector3d& a, const Eigen::Vector3d& h,
                                 const Eigen::Vector3d& v, const Eigen::Vector2d& pixel) {
  // d is perpendicular to H - x A and V - y A (both project to zero), and
  // ((H - xA) x (V - yA)).A = (H x V).A, so dividing by it gives d.A = 1.
  const Eigen::Vector3d d = (h - pixel.x() * a).cross(v - pixel.y() * a);
  return d / a.dot(h.cross(v));
}

LinearPart LinearPartOf(const CameraModel& model) {
  LinearPart part;
  if (const auto* p = model.As<PinholeRadial>()) {
    part.center = p->pose.translation();
    part.axes = p->pose.linear();
    part.fx = p->fx;
    part.fy = p->fy;
    part.cx = p->cx;
    part.cy = p->cy;
    part.theta = std::numbers::pi / 2.0;
    return part;
  }
  Eigen::Vector3d c;
  Eigen::Vector3d a;
  Eigen::Vector3d h;
  Eigen::Vector3d v;
  std::visit(
      [&](const auto& m) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(m)>, PinholeRadial>) {
          c = m.c;
          a = m.a;
          h = m.h;
          v = m.v;
        }
      },
      model.variant());
  // (A, H, V) and (A, H, V) / |A| project identically; use the latter so that A is a unit vector.
  const double norm_a = a.norm();
  a /= norm_a;
  h /= norm_a;
  v /= norm_a;
  const Intrinsics in = ComputeIntrinsics(Cahv{c, a, h, v});
  Eigen::Vector3d hp = (h - in.hc * a).normalized();
  Eigen::Vector3d vp = (v - in.vc * a).normalized();
  // Symmetric orthogonalisation of H', V' in the plane perpendicular to A.
  const Eigen::Vector3d b1 = (hp + vp).normalized();
  const Eigen::Vector3d b2 = (hp - vp).normalized();
  const Eigen::Vector3d x = (b1 + b2) / std::sqrt(2.0);
  const Eigen::Vector3d y = (b1 - b2) / std::sqrt(2.0);
  part.center = c;
  part.axes.col(0) = x;
  part.axes.col(1) = y;
  part.axes.col(2) = a;
  // With x, y at angle (theta - pi/2)/2 from H', V', hs (p.H')/(p.A) ~ hs (X/Z) to first order;
  // the fits refine it.
  part.fx = in.hs;
  part.fy = in.vs;
  part.cx = in.hc;
  part.cy = in.vc;
  part.theta = in.theta;
  return part;
}

std::vector<Eigen::Vector2d> PixelGrid(int width, int height, int cols, int rows) {
  std::vector<Eigen::Vector2d> grid;
  grid.reserve(static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows));
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      grid.emplace_back(cols > 1 ? (width - 1.0) * i / (cols - 1) : 0.5 * (width - 1.0),
                        rows > 1 ? (height - 1.0) * j / (rows - 1) : 0.5 * (height - 1.0));
    }
  }
  return grid;
}

}  // namespace internal

namespace {

using internal::CahvRayDirection;
using Jacobian = Eigen::Matrix<double, 2, 3>;

constexpr double kHalfPi = std::numbers::pi / 2.0;

std::string Vec(const Eigen::Vector3d& v) {
  std::ostringstream os;
  os.precision(9);
  os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return os.str();
}

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// --- validation --------------------------------------------------------------------------

Status ValidateSize(std::string_view kind, int width, int height) {
  if (width < 1 || height < 1) {
    return InvalidArgument(std::string(kind) + ": image size " + std::to_string(width) + "x" +
                           std::to_string(height) + " must be at least 1x1");
  }
  return Status::Ok();
}

Status ValidateCahvPart(std::string_view kind, const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& h, const Eigen::Vector3d& v) {
  const std::string k(kind);
  if (!Finite(c)) return InvalidArgument(k + ": C " + Vec(c) + " is not finite");
  if (!Finite(a)) return InvalidArgument(k + ": A " + Vec(a) + " is not finite");
  if (!Finite(h)) return InvalidArgument(k + ": H " + Vec(h) + " is not finite");
  if (!Finite(v)) return InvalidArgument(k + ": V " + Vec(v) + " is not finite");
  if (std::abs(a.norm() - 1.0) > 1e-3) {
    return InvalidArgument(k + ": |A| = " + std::to_string(a.norm()) + " for A " + Vec(a) +
                           ", expected a unit vector (within 1e-3)");
  }
  if (!(std::abs(a.dot(h.cross(v))) > 1e-6 * h.norm() * v.norm())) {
    return InvalidArgument(k + ": A " + Vec(a) + ", H " + Vec(h) + " and V " + Vec(v) +
                           " are (nearly) coplanar");
  }
  return Status::Ok();
}

Status ValidateOpticalAxis(std::string_view kind, const Eigen::Vector3d& o,
                           const Eigen::Vector3d& r) {
  const std::string k(kind);
  if (!Finite(o)) return InvalidArgument(k + ": O " + Vec(o) + " is not finite");
  if (std::abs(o.norm() - 1.0) > 1e-3) {
    return InvalidArgument(k + ": |O| = " + std::to_string(o.norm()) + " for O " + Vec(o) +
                           ", expected a unit vector (within 1e-3)");
  }
  if (!Finite(r)) return InvalidArgument(k + ": R " + Vec(r) + " is not finite");
  if (!(1.0 + r.x() > 0.0)) {
    return InvalidArgument(k + ": R " + Vec(r) + " has 1 + r0 <= 0 (the image would be inverted)");
  }
  return Status::Ok();
}

// Scales A, H and V jointly by 1 / |A|: x = p.H / p.A is unchanged and A becomes a unit vector,
// so that hc = A.H etc. are exactly the principal point and focal lengths.
template <class T>
void NormalizeAxis(T* m) {
  const double n = m->a.norm();
  m->a /= n;
  m->h /= n;
  m->v /= n;
}

// --- CAHV ----------------------------------------------------------------------------------

std::optional<Eigen::Vector2d> ProjectCahvVector(const Eigen::Vector3d& a, const Eigen::Vector3d& h,
                                                 const Eigen::Vector3d& v, const Eigen::Vector3d& p,
                                                 Jacobian* jac) {
  const double alpha = p.dot(a);
  if (!(alpha > 0.0)) return std::nullopt;
  const Eigen::Vector2d px(p.dot(h) / alpha, p.dot(v) / alpha);
  if (jac != nullptr) {
    jac->row(0) = (h - px.x() * a).transpose() / alpha;
    jac->row(1) = (v - px.y() * a).transpose() / alpha;
  }
  return px;
}

// --- CAHVOR --------------------------------------------------------------------------------

// Projects p = P - C (or a direction); `fold` is the tangent where the distortion folds back.
std::optional<Eigen::Vector2d> ProjectCahvorVector(const Cahvor& m, double fold,
                                                   const Eigen::Vector3d& p, Jacobian* jac) {
  const double zeta = p.dot(m.o);
  if (!(zeta > 0.0)) return std::nullopt;
  const Eigen::Vector3d lambda = p - zeta * m.o;
  const double lambda2 = lambda.squaredNorm();
  if (!(std::sqrt(lambda2) < fold * zeta)) return std::nullopt;
  const double tau = lambda2 / (zeta * zeta);
  const double mu = m.r.x() + tau * (m.r.y() + tau * m.r.z());
  const Eigen::Vector3d pp = p + mu * lambda;
  Jacobian jac_pp;
  const auto px = ProjectCahvVector(m.a, m.h, m.v, pp, jac != nullptr ? &jac_pp : nullptr);
  if (!px || jac == nullptr) return px;
  // dp'/dp = I + mu (I - O O^T) + lambda (dmu/dtau) (dtau/dp)^T,
  // dtau/dp = 2 lambda / zeta^2 - 2 |lambda|^2 / zeta^3 O.
  const double dmu_dtau = m.r.y() + 2.0 * m.r.z() * tau;
  const Eigen::Vector3d dtau_dp =
      2.0 * lambda / (zeta * zeta) - 2.0 * lambda2 / (zeta * zeta * zeta) * m.o;
  const Eigen::Matrix3d dpp_dp = Eigen::Matrix3d::Identity() +
                                 mu * (Eigen::Matrix3d::Identity() - m.o * m.o.transpose()) +
                                 dmu_dtau * lambda * dtau_dp.transpose();
  *jac = jac_pp * dpp_dp;
  return px;
}

// Undistorts the CAHV ray d (d.A = 1) of a CAHVOR/CAHVORE model: returns the unit vector u
// and the tangent chi of the incoming (undistorted) ray relative to O, and lambda_hat.
struct Undistorted {
  double chi = 0.0;                                      // undistorted "tangent" off O
  Eigen::Vector3d lambda_hat = Eigen::Vector3d::Zero();  // unit, perpendicular to O (or zero)
};

std::optional<Undistorted> UndistortRay(const Eigen::Vector3d& d, const Eigen::Vector3d& o,
                                        const internal::OddPolynomial& radial) {
  const double zeta = d.dot(o);
  if (!(zeta > 0.0)) return std::nullopt;
  const Eigen::Vector3d lambda = d - zeta * o;
  const double lambda_norm = lambda.norm();
  Undistorted u;
  if (lambda_norm == 0.0) return u;
  const auto chi = radial.Invert(lambda_norm / zeta);
  if (!chi) return std::nullopt;
  u.chi = *chi;
  u.lambda_hat = lambda / lambda_norm;
  return u;
}

// --- CAHVORE -------------------------------------------------------------------------------

// theta / sin(theta) - 1, accurate for small theta.
double ThetaOverSinMinusOne(double theta) {
  if (std::abs(theta) < 1e-3) {
    const double t2 = theta * theta;
    return t2 / 6.0 + 7.0 * t2 * t2 / 360.0;
  }
  return theta / std::sin(theta) - 1.0;
}

double PupilPolynomial(const Cahvore& m, double theta) {
  const double t2 = theta * theta;
  return m.e.x() + t2 * (m.e.y() + t2 * m.e.z());
}

// Largest valid theta (exclusive) of a linearity: |L| theta < pi/2; theta < pi for L = 0.
double MaxTheta(double linearity) {
  return linearity == 0.0 ? std::numbers::pi : kHalfPi / std::abs(linearity);
}

// chi(theta) for linearity L.
double ChiOfTheta(double linearity, double theta) {
  if (linearity > 0.0) return std::tan(linearity * theta) / linearity;
  if (linearity < 0.0) return std::sin(linearity * theta) / linearity;
  return theta;
}

// Projects the ray that makes angle theta with O on the side of lambda_hat.
std::optional<Eigen::Vector2d> ProjectCahvoreAngle(const Cahvore& m, double fold, double theta,
                                                   const Eigen::Vector3d& lambda_hat) {
  const double linearity = m.Linearity();
  if (!(theta >= 0.0 && theta < std::min(MaxTheta(linearity), std::numbers::pi))) {
    return std::nullopt;
  }
  const double chi = ChiOfTheta(linearity, theta);
  if (!(chi < fold)) return std::nullopt;
  const double chi2 = chi * chi;
  const double chi_d = chi * (1.0 + m.r.x() + chi2 * (m.r.y() + chi2 * m.r.z()));
  const Eigen::Vector3d rp = m.o + chi_d * lambda_hat;
  return ProjectCahvVector(m.a, m.h, m.v, rp, nullptr);
}

std::optional<Eigen::Vector2d> ProjectCahvorePoint(const Cahvore& m, double fold,
                                                   const Eigen::Vector3d& p_ref) {
  const Eigen::Vector3d p = p_ref - m.c;
  const double zeta = p.dot(m.o);
  const Eigen::Vector3d lambda = p - zeta * m.o;
  const double lambda_norm = lambda.norm();
  if (lambda_norm == 0.0) {
    if (!(zeta > 0.0)) return std::nullopt;
    return ProjectCahvoreAngle(m, fold, 0.0, Eigen::Vector3d::Zero());
  }
  // Solve f(theta) = zeta sin(theta) - |lambda| cos(theta) - (theta - sin(theta)) E(theta) = 0
  // for the angle of the ray from the moving entrance pupil C + s(theta) O to P.
  double theta = std::atan2(lambda_norm, zeta);
  const bool has_e = m.e.x() != 0.0 || m.e.y() != 0.0 || m.e.z() != 0.0;
  if (has_e) {
    bool converged = false;
    for (int i = 0; i < 100; ++i) {
      const double s = std::sin(theta);
      const double c = std::cos(theta);
      const double e = PupilPolynomial(m, theta);
      const double de = theta * (2.0 * m.e.y() + 4.0 * m.e.z() * theta * theta);
      const double f = zeta * s - lambda_norm * c - (theta - s) * e;
      const double df = zeta * c + lambda_norm * s - (1.0 - c) * e - (theta - s) * de;
      if (!(df > 0.0)) return std::nullopt;
      const double step = f / df;
      theta -= step;
      if (!(theta > 0.0 && theta < std::numbers::pi)) return std::nullopt;
      if (std::abs(step) <= 1e-15 * std::max(theta, 1.0)) {
        converged = true;
        break;
      }
    }
    if (!converged) return std::nullopt;
  }
  return ProjectCahvoreAngle(m, fold, theta, lambda / lambda_norm);
}

std::optional<Eigen::Vector2d> ProjectCahvoreDirection(const Cahvore& m, double fold,
                                                       const Eigen::Vector3d& d) {
  // At infinity the pupil shift does not matter: theta is the angle between d and O.
  const double zeta = d.dot(m.o);
  const Eigen::Vector3d lambda = d - zeta * m.o;
  const double lambda_norm = lambda.norm();
  if (lambda_norm == 0.0) {
    if (!(zeta > 0.0)) return std::nullopt;
    return ProjectCahvoreAngle(m, fold, 0.0, Eigen::Vector3d::Zero());
  }
  return ProjectCahvoreAngle(m, fold, std::atan2(lambda_norm, zeta), lambda / lambda_norm);
}

std::optional<Ray> UnprojectCahvore(const Cahvore& m, const internal::OddPolynomial& radial,
                                    const Eigen::Vector2d& pixel) {
  const Eigen::Vector3d d = CahvRayDirection(m.a, m.h, m.v, pixel);
  const auto u = UndistortRay(d, m.o, radial);
  if (!u) return std::nullopt;
  const double linearity = m.Linearity();
  double theta = u->chi;
  if (linearity > 0.0) {
    theta = std::atan(linearity * u->chi) / linearity;
  } else if (linearity < 0.0) {
    const double s = linearity * u->chi;
    if (!(std::abs(s) <= 1.0)) return std::nullopt;
    theta = std::asin(s) / linearity;
  }
  if (!(theta >= 0.0 && theta < std::numbers::pi)) return std::nullopt;
  Ray ray;
  ray.origin = m.c + ThetaOverSinMinusOne(theta) * PupilPolynomial(m, theta) * m.o;
  ray.direction = (std::cos(theta) * m.o + std::sin(theta) * u->lambda_hat).normalized();
  return ray;
}

// --- pinhole -------------------------------------------------------------------------------

std::optional<Eigen::Vector2d> ProjectPinholeCamera(const PinholeRadial& m, double fold,
                                                    const Eigen::Vector3d& pc, Jacobian* jac_c) {
  const double z = pc.z();
  if (!(z > 0.0)) return std::nullopt;
  const double xn = pc.x() / z;
  const double yn = pc.y() / z;
  const double r2 = xn * xn + yn * yn;
  if (!(std::sqrt(r2) < fold)) return std::nullopt;
  const double s = 1.0 + r2 * (m.k1 + r2 * (m.k2 + r2 * m.k3));
  const Eigen::Vector2d px(m.fx * xn * s + m.cx, m.fy * yn * s + m.cy);
  if (jac_c != nullptr) {
    const double ds = m.k1 + r2 * (2.0 * m.k2 + r2 * 3.0 * m.k3);  // ds / d(r^2)
    Eigen::Matrix2d d_dist;                                        // d(xd, yd) / d(xn, yn)
    d_dist << s + 2.0 * xn * xn * ds, 2.0 * xn * yn * ds,          //
        2.0 * xn * yn * ds, s + 2.0 * yn * yn * ds;
    Eigen::Matrix<double, 2, 3> d_norm;  // d(xn, yn) / d(pc)
    d_norm << 1.0 / z, 0.0, -xn / z,     //
        0.0, 1.0 / z, -yn / z;
    *jac_c = Eigen::DiagonalMatrix<double, 2>(m.fx, m.fy) * d_dist * d_norm;
  }
  return px;
}

}  // namespace

// --- structs -------------------------------------------------------------------------------

double Cahvore::Linearity() const {
  switch (type) {
    case CahvoreType::kPerspective:
      return 1.0;
    case CahvoreType::kFisheye:
      return 0.0;
    case CahvoreType::kGeneral:
      return parameter;
  }
  return parameter;
}

Intrinsics ComputeIntrinsics(const Cahv& m) {
  Intrinsics in;
  in.hc = m.a.dot(m.h);
  in.vc = m.a.dot(m.v);
  in.hs = m.a.cross(m.h).norm();
  in.vs = m.a.cross(m.v).norm();
  const Eigen::Vector3d hp = (m.h - in.hc * m.a) / in.hs;
  const Eigen::Vector3d vp = (m.v - in.vc * m.a) / in.vs;
  in.theta = std::atan2(hp.cross(vp).dot(m.a), hp.dot(vp));
  return in;
}

Intrinsics ComputeIntrinsics(const Cahvor& m) {
  return ComputeIntrinsics(Cahv{m.c, m.a, m.h, m.v});
}

Intrinsics ComputeIntrinsics(const Cahvore& m) {
  return ComputeIntrinsics(Cahv{m.c, m.a, m.h, m.v});
}

std::string_view KindName(CameraModel::Kind kind) {
  switch (kind) {
    case CameraModel::Kind::kCahv:
      return "CAHV";
    case CameraModel::Kind::kCahvor:
      return "CAHVOR";
    case CameraModel::Kind::kCahvore:
      return "CAHVORE";
    case CameraModel::Kind::kPinholeRadial:
      return "PINHOLE_RADIAL";
  }
  return "UNKNOWN";
}

// --- CameraModel ---------------------------------------------------------------------------

CameraModel::CameraModel(Variant model, int width, int height)
    : model_(std::move(model)),
      width_(width),
      height_(height),
      fold_(internal::RadialPolynomialOf(model_).fold) {}

Result<CameraModel> CameraModel::Create(const Cahv& m, int width, int height) {
  ROVER_RETURN_IF_ERROR(ValidateSize("CAHV", width, height));
  ROVER_RETURN_IF_ERROR(ValidateCahvPart("CAHV", m.c, m.a, m.h, m.v));
  Cahv copy = m;
  NormalizeAxis(&copy);
  return CameraModel(copy, width, height);
}

Result<CameraModel> CameraModel::Create(const Cahvor& m, int width, int height) {
  ROVER_RETURN_IF_ERROR(ValidateSize("CAHVOR", width, height));
  ROVER_RETURN_IF_ERROR(ValidateCahvPart("CAHVOR", m.c, m.a, m.h, m.v));
  ROVER_RETURN_IF_ERROR(ValidateOpticalAxis("CAHVOR", m.o, m.r));
  Cahvor copy = m;
  NormalizeAxis(&copy);
  copy.o.normalize();
  return CameraModel(copy, width, height);
}

Result<CameraModel> CameraModel::Create(const Cahvore& m, int width, int height) {
  ROVER_RETURN_IF_ERROR(ValidateSize("CAHVORE", width, height));
  ROVER_RETURN_IF_ERROR(ValidateCahvPart("CAHVORE", m.c, m.a, m.h, m.v));
  ROVER_RETURN_IF_ERROR(ValidateOpticalAxis("CAHVORE", m.o, m.r));
  if (!Finite(m.e)) return InvalidArgument("CAHVORE: E " + Vec(m.e) + " is not finite");
  const int type = static_cast<int>(m.type);
  if (type < 1 || type > 3) {
    return InvalidArgument("CAHVORE: type " + std::to_string(type) +
                           " is not 1 (perspective), 2 (fisheye) or 3 (general)");
  }
  if (m.type == CahvoreType::kGeneral && !std::isfinite(m.parameter)) {
    return InvalidArgument("CAHVORE: linearity parameter is not finite");
  }
  Cahvore copy = m;
  NormalizeAxis(&copy);
  copy.o.normalize();
  return CameraModel(copy, width, height);
}

Result<CameraModel> CameraModel::Create(const PinholeRadial& m) {
  ROVER_RETURN_IF_ERROR(ValidateSize("PINHOLE_RADIAL", m.width, m.height));
  if (!(std::isfinite(m.fx) && std::isfinite(m.fy) && m.fx > 0.0 && m.fy > 0.0)) {
    return InvalidArgument("PINHOLE_RADIAL: focal lengths fx = " + std::to_string(m.fx) +
                           ", fy = " + std::to_string(m.fy) + " must be finite and > 0");
  }
  if (!(std::isfinite(m.cx) && std::isfinite(m.cy))) {
    return InvalidArgument("PINHOLE_RADIAL: principal point is not finite");
  }
  if (!(std::isfinite(m.k1) && std::isfinite(m.k2) && std::isfinite(m.k3))) {
    return InvalidArgument("PINHOLE_RADIAL: k1, k2, k3 are not finite");
  }
  const Eigen::Matrix3d r = m.pose.linear();
  if (!r.allFinite() || !m.pose.translation().allFinite() ||
      !((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6) ||
      !(r.determinant() > 0.0)) {
    return InvalidArgument(
        "PINHOLE_RADIAL: pose is not a finite rigid transform (rotation "
        "must be orthonormal with determinant +1)");
  }
  return CameraModel(m, m.width, m.height);
}

Eigen::Vector3d CameraModel::Center() const {
  return std::visit(
      [](const auto& m) -> Eigen::Vector3d {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, PinholeRadial>) {
          return m.pose.translation();
        } else {
          return m.c;
        }
      },
      model_);
}

std::optional<Eigen::Vector2d> CameraModel::Project(const Eigen::Vector3d& p_ref) const {
  return Project(p_ref, nullptr);
}

std::optional<Eigen::Vector2d> CameraModel::Project(const Eigen::Vector3d& p_ref,
                                                    Jacobian* jacobian) const {
  if (!p_ref.allFinite()) return std::nullopt;
  switch (kind()) {
    case Kind::kCahv: {
      const Cahv& m = std::get<Cahv>(model_);
      return ProjectCahvVector(m.a, m.h, m.v, p_ref - m.c, jacobian);
    }
    case Kind::kCahvor: {
      const Cahvor& m = std::get<Cahvor>(model_);
      return ProjectCahvorVector(m, fold_, p_ref - m.c, jacobian);
    }
    case Kind::kCahvore: {
      const Cahvore& m = std::get<Cahvore>(model_);
      const auto px = ProjectCahvorePoint(m, fold_, p_ref);
      if (!px || jacobian == nullptr) return px;
      // Central differences; one-sided next to the edge of the valid range.
      const double step = 1e-6 * std::max((p_ref - m.c).norm(), 1e-6);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d dp = step * Eigen::Vector3d::Unit(k);
        const auto plus = ProjectCahvorePoint(m, fold_, p_ref + dp);
        const auto minus = ProjectCahvorePoint(m, fold_, p_ref - dp);
        if (plus && minus) {
          jacobian->col(k) = (*plus - *minus) / (2.0 * step);
        } else if (plus) {
          jacobian->col(k) = (*plus - *px) / step;
        } else if (minus) {
          jacobian->col(k) = (*px - *minus) / step;
        } else {
          return std::nullopt;
        }
      }
      return px;
    }
    case Kind::kPinholeRadial: {
      const PinholeRadial& m = std::get<PinholeRadial>(model_);
      const Eigen::Matrix3d rt = m.pose.linear().transpose();
      const Eigen::Vector3d pc = rt * (p_ref - m.pose.translation());
      Jacobian jac_c;
      const auto px = ProjectPinholeCamera(m, fold_, pc, jacobian != nullptr ? &jac_c : nullptr);
      if (px && jacobian != nullptr) *jacobian = jac_c * rt;
      return px;
    }
  }
  ROVER_UNREACHABLE();
}

std::optional<Eigen::Vector2d> CameraModel::ProjectDirection(const Eigen::Vector3d& d) const {
  if (!d.allFinite() || !(d.squaredNorm() > 0.0)) return std::nullopt;
  switch (kind()) {
    case Kind::kCahv: {
      const Cahv& m = std::get<Cahv>(model_);
      return ProjectCahvVector(m.a, m.h, m.v, d, nullptr);
    }
    case Kind::kCahvor:
      return ProjectCahvorVector(std::get<Cahvor>(model_), fold_, d, nullptr);
    case Kind::kCahvore:
      return ProjectCahvoreDirection(std::get<Cahvore>(model_), fold_, d);
    case Kind::kPinholeRadial: {
      const PinholeRadial& m = std::get<PinholeRadial>(model_);
      return ProjectPinholeCamera(m, fold_, m.pose.linear().transpose() * d, nullptr);
    }
  }
  ROVER_UNREACHABLE();
}

std::optional<Ray> CameraModel::Unproject(const Eigen::Vector2d& pixel) const {
  if (!pixel.allFinite()) return std::nullopt;
  switch (kind()) {
    case Kind::kCahv: {
      const Cahv& m = std::get<Cahv>(model_);
      return Ray{m.c, CahvRayDirection(m.a, m.h, m.v, pixel).normalized()};
    }
    case Kind::kCahvor: {
      const Cahvor& m = std::get<Cahvor>(model_);
      const Eigen::Vector3d d = CahvRayDirection(m.a, m.h, m.v, pixel);
      const auto u = UndistortRay(d, m.o, internal::RadialPolynomialOf(model_, fold_));
      if (!u) return std::nullopt;
      return Ray{m.c, (m.o + u->chi * u->lambda_hat).normalized()};
    }
    case Kind::kCahvore:
      return UnprojectCahvore(std::get<Cahvore>(model_),
                              internal::RadialPolynomialOf(model_, fold_), pixel);
    case Kind::kPinholeRadial: {
      const PinholeRadial& m = std::get<PinholeRadial>(model_);
      const Eigen::Vector2d xd((pixel.x() - m.cx) / m.fx, (pixel.y() - m.cy) / m.fy);
      const double rd = xd.norm();
      Eigen::Vector2d xn = xd;
      if (rd > 0.0) {
        const auto r = internal::RadialPolynomialOf(model_, fold_).Invert(rd);
        if (!r) return std::nullopt;
        xn *= *r / rd;
      }
      return Ray{m.pose.translation(),
                 (m.pose.linear() * Eigen::Vector3d(xn.x(), xn.y(), 1.0)).normalized()};
    }
  }
  ROVER_UNREACHABLE();
}

bool CameraModel::InImage(const Eigen::Vector2d& pixel) const {
  return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() < width_ - 0.5 &&
         pixel.y() < height_ - 0.5;
}

}  // namespace rover::geometry
