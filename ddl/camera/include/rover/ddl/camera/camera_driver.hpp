#pragma once
/// @file
/// CameraDriver: the camera driver's logic without DDS. It pairs ddl/camera_request with the
/// camera head's hw/camera_frame, downsamples the pair (DownsampleStereo) and attaches the
/// camera models valid for the result in the rover frame at capture time.
///
///  1. HandleRequest checks a request (camera in 0..2, width 0..the camera's calibrated width,
///     exposure <= max_exposure_us, fewer than max_pending requests waiting) and returns the
///     hw/camera_request to send, with the readout: the largest b x b binning b <= max_binning
///     that divides the sensor width W and still gives W / b >= the requested width (0 = full
///     frame: no binning), so a 256-px request of a 1024-px HAZCAM reads 256 x 256 out (MER read
///     its HAZCAMs binned and downsampled the rest in software: seed 000). ReadoutFor() says
///     which. Hardware request ids are the driver's own (1, 2, ...), so two
///     requesters using the same request_id do not get each other's frames; the frame echoes
///     the requester's request_id.
///  2. HandleMast stores ddl/joint_state mast angles (history of mast_history_s).
///  3. HandleFrame matches a hw/camera_frame to its pending request, checks it (camera, sizes,
///     byte counts), and produces the stereo frame:
///       - models at the frame's size: the calibration models scaled by frame/calibration size
///         when the camera delivers a binned frame of the same aspect ratio (geometry::Scale is
///         exact for binning); any other size is a corrupt frame;
///       - mast-head pairs transformed by MastHeadPose at the capture time (frame stamp): mast
///         angles interpolated linearly between the two joint-state samples around it, or the
///         nearest sample at the ends of the history;
///       - downsampled to the requested width (0 or a width >= the frame's = full size) with
///         height round(H w / W), models scaled consistently.
///     Health of the frame: OK; DEGRADED if the nearest mast sample is more than mast_max_age_s
///     from the capture time (the models may not match the head's pose); FAILED for a
///     mast-head pair when no mast sample was ever received (models unknown: do not use).
///  MI. The microscopic imager on the arm: HandleMiRequest checks the exposure and the pending
///     count (shared with the stereo requests) and returns the hw/mi_request (own hardware ids,
///     as above); HandleMiFrame matches a hw/mi_frame to it and checks its size and byte count;
///     the ddl/mi_frame carries no model (the imager's pose follows the arm angles,
///     core/hwconfig ArmDescription::ImagerPose). ExpireMiRequests drops unanswered ones.
///  4. ExpireRequests drops requests the camera head has not answered within
///     request_timeout_s (run clock).
/// Errors never throw; every message names the field, the value and the allowed range.

#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/ddl/camera/camera_calibration.hpp"
#include "rover/ddl/camera/downsample.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/msg/camera.hpp"

namespace rover::ddl::camera {

struct CameraDriverOptions {
  double request_timeout_s = 5.0;  ///< [s] run clock; unanswered requests are dropped
  int max_pending = 8;             ///< requests waiting for a frame at once
  double mast_max_age_s = 0.1;     ///< [s] mast sample further from the capture: DEGRADED
  double mast_history_s = 2.0;     ///< [s] mast samples kept
  std::uint32_t max_exposure_us = 10'000'000;  ///< [us] longest exposure accepted
  /// Largest b x b binning the camera head is asked for (1 = always the full frame).
  int max_binning = 8;
  /// Positive finite times, max_pending >= 1, history >= max age, max_binning in [1, 16].
  Status Validate() const;
};

/// Mast angles from one ddl/joint_state sample.
struct MastSample {
  std::int64_t stamp_ns = 0;
  double pan = 0.0;   ///< [rad]
  double tilt = 0.0;  ///< [rad]
};

/// ddl/stereo_frame content.
struct StereoFrameData {
  std::int64_t stamp_ns = 0;     ///< capture time (the hw frame's stamp)
  std::uint32_t request_id = 0;  ///< the requester's id
  int camera = 0;
  std::uint32_t exposure_us = 0;       ///< as used by the camera
  DownsampledStereo pair;              ///< images and models (rover frame) at the output size
  msg::CameraModelFields left_fields;  ///< `pair`'s models as message fields
  msg::CameraModelFields right_fields;
  double mast_pan = 0.0;  ///< [rad] mast angles used (mast-head pairs)
  double mast_tilt = 0.0;
  msg::SensorHealth health = msg::SensorHealth::kOk;
  std::string health_reason;  ///< empty when kOk
  std::string note;           ///< e.g. a requested width larger than the frame (sent full size)

  /// The ddl/stereo_frame message of this data; its images view `pair`'s pixels (valid while
  /// this data is and is not changed).
  msg::StereoFrame Message() const;
};

/// A request that is waiting for its frame.
struct PendingRequest {
  std::uint32_t hw_request_id = 0;
  msg::StereoRequest request;
  Time issued;
};

class CameraDriver {
 public:
  /// Errors: options.Validate(), a calibration without kNumCameras pairs.
  static Result<CameraDriver> Create(CameraCalibration calibration,
                                     const CameraDriverOptions& options = {});

  /// Checks a ddl/camera_request; on success it is pending and the hw request is returned.
  /// Errors: InvalidArgument (unknown camera, width out of range, exposure too long), Busy
  /// (max_pending requests already wait).
  Result<hw::CameraRequest> HandleRequest(const msg::StereoRequest& request, Time now);

  /// The hw readout width for an output `width` (0 = full) of a sensor `sensor_width` px wide:
  /// sensor_width / b for the largest b <= max_binning dividing sensor_width with
  /// sensor_width / b >= width, or 0 (full frame) when b = 1. Precondition: 0 <= width <=
  /// sensor_width, sensor_width >= 1.
  int ReadoutFor(int width, int sensor_width) const;

  /// Stores a mast sample. InvalidArgument for non-finite angles; samples not newer than the
  /// newest stored are ignored (Ok).
  Status HandleMast(const MastSample& sample);

  /// The stereo frame for a hw/camera_frame. Errors: NotFound (no pending request has this
  /// hardware request id: late, duplicate or not ours); InvalidArgument (camera differs from
  /// the request's, empty or inconsistent sizes, byte counts, a size that is not a binning of
  /// the calibrated one) — the request is dropped; Internal if a model conversion fails.
  Result<StereoFrameData> HandleFrame(const hw::CameraFrame& frame);

  /// Checks a ddl/mi_request; on success it is pending and the hw request is returned.
  /// Errors: InvalidArgument (exposure too long), Busy (max_pending requests already wait).
  Result<hw::MiRequest> HandleMiRequest(const msg::MiRequest& request, Time now);
  /// The ddl/mi_frame for a hw/mi_frame (its image views `frame`'s). Errors: NotFound (not a
  /// pending request of ours), InvalidArgument (empty size or a byte count that does not match;
  /// the request is dropped).
  Result<msg::MiFrame> HandleMiFrame(const hw::MiFrame& frame);
  /// Removes and returns the microscopic-imager requests older than request_timeout_s.
  std::vector<msg::MiRequest> ExpireMiRequests(Time now);

  /// Removes and returns the requests issued more than request_timeout_s before `now`.
  std::vector<PendingRequest> ExpireRequests(Time now);

  /// Forgets pending requests and mast samples (the run clock went back).
  void Reset();

  std::size_t pending() const { return pending_.size() + pending_mi_.size(); }
  const CameraCalibration& calibration() const { return calibration_; }
  const CameraDriverOptions& options() const { return options_; }

 private:
  CameraDriver(CameraCalibration calibration, const CameraDriverOptions& options);
  // Any request (stereo or microscopic imager): the exposure limit and max_pending; `id` names
  // the request in the message.
  Status Admit(const std::string& id, std::uint32_t exposure_us) const;
  std::uint32_t NextHwId();  // the driver's own hardware ids, 1, 2, ... (0 skipped on wrap)
  /// Mast angles at `stamp_ns`; false if no sample. `gap_s` = distance to the nearest sample.
  bool MastAt(std::int64_t stamp_ns, double* pan, double* tilt, double* gap_s) const;

  CameraCalibration calibration_;
  CameraDriverOptions options_;
  std::vector<PendingRequest> pending_;
  struct PendingMi {
    std::uint32_t hw_request_id = 0;
    msg::MiRequest request;
    Time issued;
  };
  std::vector<PendingMi> pending_mi_;
  std::uint32_t next_hw_id_ = 1;
  std::deque<MastSample> mast_;
};

}  // namespace rover::ddl::camera
