#include "rover/dl/stereo/setup_cache.hpp"

#include <utility>

#include "rover/base/check.hpp"

namespace rover::dl::stereo {

StereoSetupCache::StereoSetupCache(std::size_t capacity, geometry::RectifyOptions options)
    : capacity_(capacity), options_(options) {
  ROVER_DEMAND(capacity_ >= 1);
}

Result<std::shared_ptr<const StereoSetup>> StereoSetupCache::Get(
    const msg::CameraModelFields& left, const msg::CameraModelFields& right) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if (it->left == left && it->right == right) {
      ++hits_;
      entries_.splice(entries_.begin(), entries_, it);  // now the most recently used
      return entries_.front().setup;
    }
  }
  ++misses_;
  auto l = msg::CameraModelFromFields(left);
  if (!l.ok()) return l.status().WithPrefix("left model");
  auto r = msg::CameraModelFromFields(right);
  if (!r.ok()) return r.status().WithPrefix("right model");
  auto setup = MakeStereoSetup(*l, *r, options_);
  if (!setup.ok()) return setup.status().WithPrefix("stereo rectification");
  auto shared = std::make_shared<const StereoSetup>(std::move(*setup));
  entries_.push_front(Entry{left, right, shared});
  while (entries_.size() > capacity_) entries_.pop_back();
  return shared;
}

}  // namespace rover::dl::stereo
