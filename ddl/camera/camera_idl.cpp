#include "camera_idl.hpp"

#include <cstdint>
#include <cstring>

#include "rover/runtime/dds.hpp"

namespace rover::ddl {
namespace {

template <class E>
std::int32_t RawEnum(const E& e) {
  static_assert(sizeof(E) == sizeof(std::int32_t), "IDL enums are 32 bit");
  std::int32_t v = 0;
  std::memcpy(&v, &e, sizeof v);
  return v;
}

}  // namespace

static_assert(rover_CAMERA_NAVCAM == 0 && rover_CAMERA_FRONT_HAZCAM == 1 &&
              rover_CAMERA_REAR_HAZCAM == 2 && kNumCameras == 3);
static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

StereoRequest StereoRequestFromIdl(const rover_ddl_StereoRequest& in) {
  return {in.request_id, RawEnum(in.camera), in.exposure_us, in.width};
}

void HwCameraRequestToIdl(const HwCameraRequest& in, rover_hw_CameraRequest* out) {
  out->request_id = in.request_id;
  out->camera = static_cast<rover_CameraId>(in.camera);
  out->exposure_us = in.exposure_us;
}

CameraFrameView CameraFrameViewFromIdl(const rover_hw_CameraFrame& in) {
  return {in.header.stamp_ns, in.request_id, RawEnum(in.camera), in.exposure_us,
          in.width,           in.height,     dds::View(in.left), dds::View(in.right)};
}

MastSample MastSampleFromIdl(const rover_ddl_JointState& in) {
  return {in.header.stamp_ns, in.mast_pan, in.mast_tilt};
}

int RawHealth(const rover_SensorHealth& h) { return RawEnum(h); }

void CameraModelToIdl(const CameraModelFields& in, rover_ddl_CameraModel* out) {
  for (std::size_t i = 0; i < 3; ++i) {
    out->c[i] = in.c[i];
    out->a[i] = in.a[i];
    out->h[i] = in.h[i];
    out->v[i] = in.v[i];
    out->o[i] = in.o[i];
    out->r[i] = in.r[i];
  }
  out->fx = in.fx;
  out->fy = in.fy;
  out->cx = in.cx;
  out->cy = in.cy;
  out->k1 = in.k1;
  out->k2 = in.k2;
  out->k3 = in.k3;
  const Eigen::Vector3d t = in.pose.translation();
  Eigen::Quaterniond q(in.pose.linear());
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // the same rotation, w >= 0
  out->pose.position = {t.x(), t.y(), t.z()};
  out->pose.orientation = {q.w(), q.x(), q.y(), q.z()};
  out->width = in.width;
  out->height = in.height;
}

void StereoFrameToIdl(StereoFrameData& in, rover_ddl_StereoFrame* out) {
  out->request_id = in.request_id;
  out->camera = static_cast<rover_CameraId>(in.camera);
  out->exposure_us = in.exposure_us;
  out->width = static_cast<std::uint16_t>(in.pair.left.width);
  out->height = static_cast<std::uint16_t>(in.pair.left.height);
  CameraModelToIdl(in.left_fields, &out->left_model);
  CameraModelToIdl(in.right_fields, &out->right_model);
  dds::BorrowSequence(out->left, in.pair.left.pixels);
  dds::BorrowSequence(out->right, in.pair.right.pixels);
  out->health = static_cast<rover_SensorHealth>(static_cast<int>(in.health));
}

}  // namespace rover::ddl
