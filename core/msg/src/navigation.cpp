#include "rover/msg/navigation.hpp"

#include <string>
#include <utility>

namespace rover::msg {

Status GoodnessMap::CheckSizes() const {
  if (width < 0 || height < 0) {
    return InvalidArgument("apl/goodness_map size " + std::to_string(width) + " x " +
                           std::to_string(height) + " is negative");
  }
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::pair<const char*, std::size_t> arrays[] = {
      {"goodness", goodness.size()}, {"certainty", certainty.size()}, {"flags", flags.size()}};
  for (const auto& [name, size] : arrays) {
    if (size != n) {
      return InvalidArgument("apl/goodness_map " + std::string(name) + ": " + std::to_string(size) +
                             " cells for " + std::to_string(n) + " = " + std::to_string(width) +
                             " x " + std::to_string(height));
    }
  }
  return Status::Ok();
}

}  // namespace rover::msg
