#pragma once
/// @file
/// Rectification of raw stereo pairs, computed once per camera-model pair.
///
/// Computing the remap tables of a pair (geometry::RectifyStereoPair, one ray per pixel through
/// CAHVOR) costs far more than remapping an image, and a fixed camera (a HAZCAM, or the NAVCAM
/// while the mast does not move) sends the same two models with every frame. The cache keys on
/// the exact message fields of both models (msg::CameraModelFields, compared field by field) and
/// keeps the `capacity` most recently used setups (least recently used evicted).

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/geometry_adapter.hpp"
#include "rover/msg/camera.hpp"

namespace rover::dl::stereo {

class StereoSetupCache {
 public:
  /// Precondition: capacity >= 1.
  explicit StereoSetupCache(std::size_t capacity = 4, geometry::RectifyOptions options = {});

  /// The rectification maps and rectified camera of a model pair: from the cache, or converted
  /// (msg::CameraModelFromFields) and rectified (MakeStereoSetup) and then cached. Errors (not
  /// cached): "left model: ..." / "right model: ..." for bad models, and MakeStereoSetup's
  /// (different sizes, cameras at the same place: no baseline, forward stereo, mirrored).
  /// The returned setup stays valid after eviction (shared ownership).
  Result<std::shared_ptr<const StereoSetup>> Get(const msg::CameraModelFields& left,
                                                 const msg::CameraModelFields& right);

  void Clear() { entries_.clear(); }
  std::size_t size() const { return entries_.size(); }
  std::size_t capacity() const { return capacity_; }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  struct Entry {
    msg::CameraModelFields left, right;
    std::shared_ptr<const StereoSetup> setup;
  };
  std::size_t capacity_;
  geometry::RectifyOptions options_;
  std::list<Entry> entries_;  // most recently used first
  std::uint64_t hits_ = 0;
  std::uint64_t misses_ = 0;
};

}  // namespace rover::dl::stereo
