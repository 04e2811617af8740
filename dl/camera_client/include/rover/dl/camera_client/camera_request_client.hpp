#pragma once
/// @file
/// The requester's side of the camera driver (ddl/camera_request -> ddl/stereo_frame), shared by
/// dl-stereo and dl-vo. DDS-free and clock-free: every call takes the run-clock time.
///
/// One request is outstanding at a time. A request gets this requester's own id,
///   request_id = request_id_prefix << 24 | counter,   counter = 1 .. 2^24 - 1 (wrapping, never 0),
/// so that two requesters (dl-stereo prefix 1, dl-vo prefix 2) never take each other's frames:
/// the driver echoes the id, and an answer whose id is not the outstanding one (another
/// requester's, or one that came after its time-out) is not ours. An answer is checked against
/// its request before it is used: the same camera, a usable health (not FAILED or STALE), the
/// requested width (when one was asked), a capture stamp no earlier than kCaptureSkewS before
/// the request was sent and later than the previous accepted frame's. A request the driver
/// does not answer within request_timeout_s expires. After a failed send or a bad answer the
/// client holds new requests for retry_delay_s. A run-clock jump back by more than
/// kClockResetS (a simulator reset) is detected from the times the caller passes in.

#include <cstdint>
#include <optional>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/msg/camera.hpp"

namespace rover::dl::camera_client {

/// A capture stamp this much before the request was sent is a stale (or reordered) frame [s].
inline constexpr double kCaptureSkewS = 0.1;
/// The run clock going back by more than this is a reset (simulator reset) [s].
inline constexpr double kClockResetS = 1.0;

struct CameraClientOptions {
  int request_id_prefix = 1;        ///< top 8 bits of the request ids, 1..255
  double request_timeout_s = 10.0;  ///< [s] run clock the driver has to answer
  std::uint32_t exposure_us = 0;    ///< [us] asked of the driver; 0 = auto
  double retry_delay_s = 0.0;       ///< [s] hold after a failed send or a bad answer (not bound)

  /// Prefix in 1..255, a positive timeout, a non-negative retry delay.
  Status Validate() const;
  /// Keys request_id_prefix, request_timeout_s, exposure_us (retry_delay_s is the service's:
  /// not every requester retries).
  static void BindParams(ParamBinder<CameraClientOptions>& b);
};

/// The request that is waiting for its frame.
struct Outstanding {
  std::uint32_t request_id = 0;  ///< this requester's ddl/camera_request id
  msg::CameraId camera = msg::CameraId::kNavcam;
  int width = 0;          ///< [px] asked of the driver; 0 = full size
  Time sent;              ///< run-clock time it was issued
  std::uint32_t tag = 0;  ///< the caller's (e.g. the range request it serves)
};

class CameraRequestClient {
 public:
  /// Precondition: options.Validate() is Ok.
  explicit CameraRequestClient(const CameraClientOptions& options = {});

  /// No request is outstanding and no hold is in force at `now`.
  bool Ready(Time now) const { return !outstanding_.has_value() && now >= hold_until_; }
  bool outstanding() const { return outstanding_.has_value(); }

  /// The next ddl/camera_request (stamped `now`, this client's next id, the exposure of the
  /// options), recorded as outstanding. Precondition: no request is outstanding.
  msg::StereoRequest Issue(Time now, msg::CameraId camera, int width, std::uint32_t tag = 0);
  /// Sending the issued request failed: it is forgotten and new ones are held for
  /// retry_delay_s from `now`.
  void SendFailed(Time now);

  /// The outstanding request if `request_id` answers it (it is then closed); nullopt if the
  /// answer is not ours (no request outstanding, another requester's id, a late answer).
  std::optional<Outstanding> Answer(std::uint32_t request_id);
  /// Checks an answer against its request (see the file comment). InvalidArgument naming the
  /// check, the value and the request's.
  Status Check(const Outstanding& request, const msg::StereoFrame& frame) const;
  /// The answer was used: its capture stamp is the one later frames must follow.
  void Accepted(Time capture);
  /// The answer was bad: new requests are held for retry_delay_s from `now`.
  void Failed(Time now);

  /// The outstanding request if it was sent more than request_timeout_s before `now` (it is
  /// then closed); nullopt otherwise.
  std::optional<Outstanding> Expire(Time now);
  /// Records `now` and says whether it is more than kClockResetS before the previous call's
  /// (the run clock went back). The caller then calls Reset().
  bool ClockWentBack(Time now);
  /// Forgets the outstanding request (returned, e.g. to be asked again), the previous capture
  /// stamp and any hold.
  std::optional<Outstanding> Reset();

  const CameraClientOptions& options() const { return options_; }

 private:
  CameraClientOptions options_;
  std::optional<Outstanding> outstanding_;
  std::uint32_t counter_ = 0;
  std::optional<Time> last_capture_;
  Time hold_until_{0};
  Time last_now_{0};
};

}  // namespace rover::dl::camera_client
