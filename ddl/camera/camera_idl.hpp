#pragma once
/// @file
/// Conversions between the IDL C structs of ddl-camera's topics and the ddl_camera library's
/// plain structs. Enums are read as raw integers (an unknown camera on the wire reaches the
/// driver's request check); sequences are viewed, not copied, on the way in and borrowed on the
/// way out (the StereoFrameData must outlive the write). Headers are the caller's.

#include "rover/ddl/camera/camera_driver.hpp"
#include "rover/idl/types.hpp"

namespace rover::ddl {

/// ddl/camera_request.
StereoRequest StereoRequestFromIdl(const rover_ddl_StereoRequest& in);
/// hw/camera_request, except the header.
void HwCameraRequestToIdl(const HwCameraRequest& in, rover_hw_CameraRequest* out);
/// hw/camera_frame as a view on the sample's buffers (valid while the sample is).
CameraFrameView CameraFrameViewFromIdl(const rover_hw_CameraFrame& in);
/// The mast angles of a ddl/joint_state sample (stamp from the header).
MastSample MastSampleFromIdl(const rover_ddl_JointState& in);
/// The raw value of a SensorHealth field (may be out of range on a corrupt sample).
int RawHealth(const rover_SensorHealth& h);
/// One ddl CameraModel: CAHVOR vectors, pinhole intrinsics, pose (quaternion w first), size.
void CameraModelToIdl(const CameraModelFields& in, rover_ddl_CameraModel* out);
/// ddl/stereo_frame except the header; `left`/`right` borrow `in`'s pixel buffers.
void StereoFrameToIdl(StereoFrameData& in, rover_ddl_StereoFrame* out);

}  // namespace rover::ddl
