#pragma once
/// @file
/// A raw (unrectified) stereo pair as the camera driver sends it on ddl/stereo_frame: two 8-bit
/// mono images of width x height, row-major, and the two camera models valid for them (in the
/// rover frame at capture time). RawStereoPairFromMessage reads the idlc-generated struct
/// without DDS (any struct with the IDL's member names and DDS sequence layout `_buffer`,
/// `_length`) and checks that sizes agree, so that nothing downstream sees a bad frame.

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/stereo/camera_model_fields.hpp"

namespace rover::dl::stereo {

struct RawStereoPair {
  Time stamp;      ///< capture time on the run clock
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  /// CV_8UC1 height x width. From RawStereoPairFromMessage these VIEW the message's memory:
  /// valid only while the message is (e.g. during a DDS callback); clone() to keep them.
  cv::Mat left, right;
  CameraModelFields left_model, right_model;
};

/// Checks width, height >= 1, both images CV_8UC1 of width x height, both models sized
/// width x height and a positive stamp. Errors name the image or model and the sizes.
Status CheckRawStereoPair(const RawStereoPair& pair);

/// Reads a ddl/stereo_frame message (header.stamp_ns, width, height, left, right, left_model,
/// right_model) into a pair whose images view the message's buffers. Errors: an image whose
/// byte count is not width x height, and those of CheckRawStereoPair.
template <class Frame>
Result<RawStereoPair> RawStereoPairFromMessage(const Frame& m) {
  RawStereoPair p;
  p.stamp = Time{m.header.stamp_ns};
  p.width = static_cast<int>(m.width);
  p.height = static_cast<int>(m.height);
  const std::size_t n = static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height);
  const std::pair<const char*, std::size_t> lengths[] = {{"left", m.left._length},
                                                         {"right", m.right._length}};
  for (const auto& [name, length] : lengths) {
    if (length != n) {
      return InvalidArgument(std::string(name) + " image has " + std::to_string(length) +
                             " bytes; expected " + std::to_string(p.width) + "x" +
                             std::to_string(p.height) + " = " + std::to_string(n));
    }
  }
  if (n > 0 && (m.left._buffer == nullptr || m.right._buffer == nullptr)) {
    return InvalidArgument("stereo frame image buffer is null");
  }
  if (n > 0) {
    // cv::Mat has no const view; the pair is only read from.
    p.left = cv::Mat(p.height, p.width, CV_8UC1,
                     const_cast<std::uint8_t*>(static_cast<const std::uint8_t*>(m.left._buffer)));
    p.right = cv::Mat(p.height, p.width, CV_8UC1,
                      const_cast<std::uint8_t*>(static_cast<const std::uint8_t*>(m.right._buffer)));
  }
  p.left_model = FieldsFromMessage(m.left_model);
  p.right_model = FieldsFromMessage(m.right_model);
  ROVER_RETURN_IF_ERROR(CheckRawStereoPair(p));
  return p;
}

}  // namespace rover::dl::stereo
