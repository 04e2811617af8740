#include "rover/msg/range.hpp"

#include <string>
#include <utility>

namespace rover::msg {

Status RangeImage::CheckSizes() const {
  if (width < 0 || height < 0) {
    return InvalidArgument("range image size " + std::to_string(width) + "x" +
                           std::to_string(height) + " is negative");
  }
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::pair<const char*, std::pair<std::size_t, std::size_t>> arrays[] = {
      {"xyz", {xyz.size(), 3 * n}},
      {"valid", {valid.size(), n}},
      {"disparity", {disparity.size(), n}}};
  for (const auto& [name, sizes] : arrays) {
    if (sizes.first != sizes.second) {
      return InvalidArgument("range image " + std::string(name) + " has " +
                             std::to_string(sizes.first) + " values; expected " +
                             std::to_string(sizes.second) + " for " + std::to_string(width) + "x" +
                             std::to_string(height));
    }
  }
  return Status::Ok();
}

}  // namespace rover::msg
