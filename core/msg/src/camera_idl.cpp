#include "rover/msg/camera_idl.hpp"

#include <algorithm>

#include "idl_enum.hpp"
#include "rover/msg/health_idl.hpp"

namespace rover::msg {

using internal::ClampSize;
static_assert(rover_CAMERA_NAVCAM == static_cast<int>(CameraId::kNavcam));
static_assert(rover_CAMERA_FRONT_HAZCAM == static_cast<int>(CameraId::kFrontHazcam));
static_assert(rover_CAMERA_REAR_HAZCAM == static_cast<int>(CameraId::kRearHazcam));
static_assert(kNumCameras == 3);

rover_CameraId CameraIdToIdl(CameraId c) { return internal::EnumToIdl<rover_CameraId>(c); }

Result<CameraId> CameraIdFromIdl(const rover_CameraId& c, std::string_view field) {
  return internal::EnumFromIdl<CameraId>(c, kNumCameras, field, "CameraId");
}

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
  out->pose.position = {in.position[0], in.position[1], in.position[2]};
  out->pose.orientation = {in.orientation[0], in.orientation[1], in.orientation[2],
                           in.orientation[3]};
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
}

CameraModelFields CameraModelFieldsFromIdl(const rover_ddl_CameraModel& in) {
  CameraModelFields f;
  for (std::size_t i = 0; i < 3; ++i) {
    f.c[i] = in.c[i];
    f.a[i] = in.a[i];
    f.h[i] = in.h[i];
    f.v[i] = in.v[i];
    f.o[i] = in.o[i];
    f.r[i] = in.r[i];
  }
  f.fx = in.fx;
  f.fy = in.fy;
  f.cx = in.cx;
  f.cy = in.cy;
  f.k1 = in.k1;
  f.k2 = in.k2;
  f.k3 = in.k3;
  f.position = {in.pose.position.x, in.pose.position.y, in.pose.position.z};
  f.orientation = {in.pose.orientation.w, in.pose.orientation.x, in.pose.orientation.y,
                   in.pose.orientation.z};
  f.width = in.width;
  f.height = in.height;
  return f;
}

Status CameraModelToIdl(const geometry::CameraModel& model, rover_ddl_CameraModel* out) {
  ROVER_ASSIGN_OR_RETURN(const CameraModelFields fields, CameraModelFieldsFromModel(model));
  CameraModelToIdl(fields, out);
  return Status::Ok();
}

Result<geometry::CameraModel> CameraModelFromIdl(const rover_ddl_CameraModel& in) {
  return CameraModelFromFields(CameraModelFieldsFromIdl(in));
}

StereoRequest StereoRequestFromIdl(const rover_ddl_StereoRequest& in) {
  StereoRequest r;
  r.stamp = Time{in.header.stamp_ns};
  r.request_id = in.request_id;
  r.camera = internal::RawEnumFromIdl<CameraId>(in.camera);
  r.exposure_us = in.exposure_us;
  r.width = in.width;
  return r;
}

void StereoRequestToIdl(const StereoRequest& in, rover_ddl_StereoRequest* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  out->camera = CameraIdToIdl(in.camera);
  out->exposure_us = in.exposure_us;
  out->width = ClampSize(in.width);
}

Result<StereoFrame> StereoFrameFromIdl(const rover_ddl_StereoFrame& in) {
  StereoFrame f;
  f.stamp = Time{in.header.stamp_ns};
  f.request_id = in.request_id;
  ROVER_ASSIGN_OR_RETURN(f.camera, CameraIdFromIdl(in.camera));
  f.exposure_us = in.exposure_us;
  f.width = in.width;
  f.height = in.height;
  f.left_model = CameraModelFieldsFromIdl(in.left_model);
  f.right_model = CameraModelFieldsFromIdl(in.right_model);
  if ((in.left._length > 0 && in.left._buffer == nullptr) ||
      (in.right._length > 0 && in.right._buffer == nullptr)) {
    return InvalidArgument("stereo frame image buffer is null");
  }
  f.left = idl::View(in.left);
  f.right = idl::View(in.right);
  ROVER_ASSIGN_OR_RETURN(f.health, HealthFromIdl(in.health));
  ROVER_RETURN_IF_ERROR(CheckStereoFrame(f));
  return f;
}

void StereoFrameToIdl(const StereoFrame& in, rover_ddl_StereoFrame* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  out->camera = CameraIdToIdl(in.camera);
  out->exposure_us = in.exposure_us;
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  CameraModelToIdl(in.left_model, &out->left_model);
  CameraModelToIdl(in.right_model, &out->right_model);
  idl::BorrowSequence(out->left, in.left);
  idl::BorrowSequence(out->right, in.right);
  out->health = HealthToIdl(in.health);
}

MiRequest MiRequestFromIdl(const rover_ddl_MiRequest& in) {
  MiRequest r;
  r.stamp = Time{in.header.stamp_ns};
  r.request_id = in.request_id;
  r.exposure_us = in.exposure_us;
  return r;
}

void MiRequestToIdl(const MiRequest& in, rover_ddl_MiRequest* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  out->exposure_us = in.exposure_us;
}

Result<MiFrame> MiFrameFromIdl(const rover_ddl_MiFrame& in) {
  MiFrame f;
  f.stamp = Time{in.header.stamp_ns};
  f.request_id = in.request_id;
  f.exposure_us = in.exposure_us;
  f.width = in.width;
  f.height = in.height;
  if (in.image._length > 0 && in.image._buffer == nullptr) {
    return InvalidArgument("microscopic-imager frame image buffer is null");
  }
  f.image = idl::View(in.image);
  ROVER_ASSIGN_OR_RETURN(f.health, HealthFromIdl(in.health));
  ROVER_RETURN_IF_ERROR(CheckMiFrame(f));
  return f;
}

void MiFrameToIdl(const MiFrame& in, rover_ddl_MiFrame* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  out->exposure_us = in.exposure_us;
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  idl::BorrowSequence(out->image, in.image);
  out->health = HealthToIdl(in.health);
}

}  // namespace rover::msg
