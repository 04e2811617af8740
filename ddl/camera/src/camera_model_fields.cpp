#include "rover/ddl/camera/camera_model_fields.hpp"

namespace rover::ddl {
namespace {

std::array<double, 3> A3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

void SetCahvor(const geometry::Cahvor& m, CameraModelFields* f) {
  f->c = A3(m.c);
  f->a = A3(m.a);
  f->h = A3(m.h);
  f->v = A3(m.v);
  f->o = A3(m.o);
  f->r = A3(m.r);
}

}  // namespace

Result<CameraModelFields> ToCameraModelFields(const geometry::CameraModel& model) {
  CameraModelFields f;
  f.width = static_cast<std::uint16_t>(model.width());
  f.height = static_cast<std::uint16_t>(model.height());
  auto pin = geometry::ToPinholeRadial(model);
  if (!pin.ok()) return pin.status();
  const geometry::PinholeRadial& p = pin->model;
  f.fx = p.fx;
  f.fy = p.fy;
  f.cx = p.cx;
  f.cy = p.cy;
  f.k1 = p.k1;
  f.k2 = p.k2;
  f.k3 = p.k3;
  f.pose = p.pose;
  f.pinhole_rms_error_px = pin->rms_error_px;
  f.pinhole_max_error_px = pin->max_error_px;

  if (const auto* m = model.As<geometry::Cahv>()) {
    geometry::Cahvor cv;
    cv.c = m->c;
    cv.a = m->a;
    cv.h = m->h;
    cv.v = m->v;
    cv.o = m->a;
    cv.r.setZero();
    SetCahvor(cv, &f);
  } else if (const auto* m2 = model.As<geometry::Cahvor>()) {
    SetCahvor(*m2, &f);
  } else {
    auto cv = geometry::ToCahvor(p);
    if (!cv.ok()) return cv.status();
    SetCahvor(cv->model, &f);
  }
  return f;
}

}  // namespace rover::ddl
