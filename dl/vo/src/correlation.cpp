#include "rover/dl/vo/correlation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "rover/base/check.hpp"

namespace rover::dl::vo {

CorrelationImage::CorrelationImage(const cv::Mat& image) {
  ROVER_DEMAND(!image.empty() && image.channels() == 1);
  image.convertTo(image_, CV_32F);
  cv::integral(image_, sum_, sq_sum_, CV_64F, CV_64F);
}

void CorrelationImage::WindowStats(int x, int y, int r, double* sum, double* sum_sq) const {
  const int x0 = x - r, y0 = y - r, x1 = x + r + 1, y1 = y + r + 1;
  *sum = sum_.at<double>(y1, x1) - sum_.at<double>(y0, x1) - sum_.at<double>(y1, x0) +
         sum_.at<double>(y0, x0);
  *sum_sq = sq_sum_.at<double>(y1, x1) - sq_sum_.at<double>(y0, x1) - sq_sum_.at<double>(y1, x0) +
            sq_sum_.at<double>(y0, x0);
}

double Template::StdDev() const {
  if (values.empty()) return 0.0;
  return std::sqrt(energy / static_cast<double>(values.size()));
}

namespace {

void FinishTemplate(Template* t) {
  double mean = 0.0;
  for (float v : t->values) mean += v;
  mean /= static_cast<double>(t->values.size());
  double e = 0.0;
  for (float& v : t->values) {
    v = static_cast<float>(v - mean);
    e += static_cast<double>(v) * v;
  }
  t->energy = e;
}

}  // namespace

bool ExtractTemplate(const CorrelationImage& image, int x, int y, int radius, Template* out) {
  ROVER_DEMAND(out != nullptr && radius >= 1);
  if (!image.WindowInside(x, y, radius)) return false;
  const int n = 2 * radius + 1;
  out->radius = radius;
  out->values.resize(static_cast<std::size_t>(n * n));
  for (int j = 0; j < n; ++j) {
    const float* row = image.image().ptr<float>(y - radius + j) + (x - radius);
    for (int i = 0; i < n; ++i) out->values[static_cast<std::size_t>(j * n + i)] = row[i];
  }
  FinishTemplate(out);
  return true;
}

bool ExtractWarpedTemplate(const CorrelationImage& image, const Eigen::Vector2d& centre,
                           const Eigen::Matrix2d& a_inv, int radius, Template* out) {
  ROVER_DEMAND(out != nullptr && radius >= 1);
  const int n = 2 * radius + 1;
  out->radius = radius;
  out->values.resize(static_cast<std::size_t>(n * n));
  const cv::Mat& img = image.image();
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d p = centre + a_inv * Eigen::Vector2d(i - radius, j - radius);
      const double fx = std::floor(p.x()), fy = std::floor(p.y());
      const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
      if (ix < 0 || iy < 0 || ix + 1 >= img.cols || iy + 1 >= img.rows) {
        // Exactly on the last row or column is still fine.
        if (ix >= 0 && iy >= 0 && ix < img.cols && iy < img.rows && p.x() == fx && p.y() == fy) {
          out->values[static_cast<std::size_t>(j * n + i)] = img.at<float>(iy, ix);
          continue;
        }
        return false;
      }
      const double ax = p.x() - fx, ay = p.y() - fy;
      const float* r0 = img.ptr<float>(iy) + ix;
      const float* r1 = img.ptr<float>(iy + 1) + ix;
      const double v =
          (1 - ay) * ((1 - ax) * r0[0] + ax * r0[1]) + ay * ((1 - ax) * r1[0] + ax * r1[1]);
      out->values[static_cast<std::size_t>(j * n + i)] = static_cast<float>(v);
    }
  }
  FinishTemplate(out);
  return true;
}

double CorrelationScore(const Template& t, const CorrelationImage& image, int x, int y) {
  const int r = t.radius;
  if (!image.WindowInside(x, y, r)) return -2.0;
  const int n = 2 * r + 1;
  double cross = 0.0;
  const float* tv = t.values.data();
  for (int j = 0; j < n; ++j) {
    const float* row = image.image().ptr<float>(y - r + j) + (x - r);
    float acc = 0.0f;
    for (int i = 0; i < n; ++i) acc += tv[i] * row[i];
    cross += acc;
    tv += n;
  }
  double s = 0.0, s2 = 0.0;
  image.WindowStats(x, y, r, &s, &s2);
  const double eb = std::max(0.0, s2 - s * s / static_cast<double>(n * n));
  const double denom = t.energy + eb;
  if (denom <= 1e-9) return 0.0;
  return 2.0 * cross / denom;
}

SubpixelPeak FitBiquadratic(const std::array<double, 9>& scores) {
  // Least-squares pseudo-inverse of the 9x6 design matrix, computed once.
  static const Eigen::Matrix<double, 6, 9> kPinv = [] {
    Eigen::Matrix<double, 9, 6> a;
    for (int j = -1; j <= 1; ++j) {
      for (int i = -1; i <= 1; ++i) {
        a.row((j + 1) * 3 + (i + 1)) << 1.0, i, j, i * i, i * j, j * j;
      }
    }
    return Eigen::Matrix<double, 6, 9>((a.transpose() * a).inverse() * a.transpose());
  }();
  const Eigen::Matrix<double, 9, 1> s =
      Eigen::Map<const Eigen::Matrix<double, 9, 1>>(scores.data());
  const Eigen::Matrix<double, 6, 1> c = kPinv * s;
  Eigen::Matrix2d h;
  h << 2.0 * c(3), c(4), c(4), 2.0 * c(5);
  SubpixelPeak peak;
  const double det = h.determinant();
  if (!(h(0, 0) < 0.0 && det > 0.0)) return peak;  // not a maximum
  const Eigen::Vector2d off = -h.inverse() * Eigen::Vector2d(c(1), c(2));
  if (!(std::abs(off.x()) <= 1.0 && std::abs(off.y()) <= 1.0)) return peak;
  const double tr = -h.trace();
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4.0 - det));
  peak.ok = true;
  peak.dx = off.x();
  peak.dy = off.y();
  peak.curvature = tr / 2.0 - disc;
  return peak;
}

WindowMatch SearchWindow(const Template& t, const CorrelationImage& image, int x0, int y0, int rx,
                         int ry) {
  WindowMatch m;
  const int r = t.radius;
  const int xa = std::max(x0 - rx, r), xb = std::min(x0 + rx, image.width() - 1 - r);
  const int ya = std::max(y0 - ry, r), yb = std::min(y0 + ry, image.height() - 1 - r);
  if (xa > xb || ya > yb) {
    m.failure = "search window outside the image";
    return m;
  }
  int bx = xa, by = ya;
  double best = -3.0;
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) {
      const double s = CorrelationScore(t, image, x, y);
      if (s > best) {
        best = s;
        bx = x;
        by = y;
      }
    }
  }
  std::array<double, 9> nb{};
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const double s = (i == 0 && j == 0) ? best : CorrelationScore(t, image, bx + i, by + j);
      if (s < -1.5) {
        m.failure = "peak at the image edge";
        return m;
      }
      if (s > best) {
        m.failure = "peak on the search window edge";
        return m;
      }
      nb[static_cast<std::size_t>((j + 1) * 3 + (i + 1))] = s;
    }
  }
  const SubpixelPeak p = FitBiquadratic(nb);
  m.score = best;
  if (!p.ok) {
    m.failure = "no sub-pixel maximum";
    return m;
  }
  m.ok = true;
  m.position = Eigen::Vector2d(bx + p.dx, by + p.dy);
  m.curvature = p.curvature;
  return m;
}

}  // namespace rover::dl::vo
