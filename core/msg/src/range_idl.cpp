#include "rover/msg/range_idl.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "idl_enum.hpp"
#include "rover/base/format.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::msg {

using internal::ClampSize;
namespace {

template <class E, class Seq>
std::vector<E> Copy(const Seq& seq) {
  const auto view = idl::View(seq);
  return std::vector<E>(view.begin(), view.end());
}

}  // namespace

RangeRequest RangeRequestFromIdl(const rover_dl_RangeRequest& in) {
  RangeRequest r;
  r.stamp = Time{in.header.stamp_ns};
  r.request_id = in.request_id;
  r.camera = internal::RawEnumFromIdl<CameraId>(in.camera);
  r.width = in.width;
  return r;
}

void RangeRequestToIdl(const RangeRequest& in, rover_dl_RangeRequest* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  idl::SetRawEnum(&out->camera, static_cast<std::int32_t>(in.camera));
  out->width = ClampSize(in.width);
}

Status RangeImageToIdl(const RangeImage& in, rover_dl_RangeImage* out) {
  ROVER_RETURN_IF_ERROR(in.CheckSizes());
  out->header.stamp_ns = in.stamp.ns;
  out->request_id = in.request_id;
  out->camera = CameraIdToIdl(in.camera);
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  IsometryToIdl(in.rover_pose, &out->rover_pose);
  idl::BorrowSequence(out->xyz, std::span<const float>(in.xyz));
  idl::BorrowSequence(out->valid, std::span<const std::uint8_t>(in.valid));
  idl::BorrowSequence(out->disparity, std::span<const float>(in.disparity));
  return Status::Ok();
}

Result<RangeImage> RangeImageFromIdl(const rover_dl_RangeImage& in) {
  RangeImage r;
  r.stamp = Time{in.header.stamp_ns};
  r.request_id = in.request_id;
  ROVER_ASSIGN_OR_RETURN(r.camera, CameraIdFromIdl(in.camera, "dl/range_image camera"));
  r.width = in.width;
  r.height = in.height;
  const rover_Quaternion& qi = in.rover_pose.orientation;
  const Eigen::Quaterniond q(qi.w, qi.x, qi.y, qi.z);
  if (!(std::abs(q.norm() - 1.0) <= 1e-3)) {
    return InvalidArgument("dl/range_image rover_pose orientation is not a unit quaternion (norm " +
                           FormatNumber(q.norm()) + ")");
  }
  r.rover_pose = IsometryFromIdl(in.rover_pose);
  r.xyz = Copy<float>(in.xyz);
  r.valid = Copy<std::uint8_t>(in.valid);
  r.disparity = Copy<float>(in.disparity);
  ROVER_RETURN_IF_ERROR(r.CheckSizes());
  return r;
}

}  // namespace rover::msg
