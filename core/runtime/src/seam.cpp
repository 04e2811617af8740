#include "rover/runtime/seam.hpp"

#include <mutex>

namespace rover::dds {
namespace {
std::mutex& FactoryMutex() {
  static std::mutex m;
  return m;
}
SeamFactory& Factory() {
  static SeamFactory f;
  return f;
}
}  // namespace

void InstallSeamFactory(SeamFactory factory) {
  std::lock_guard lock(FactoryMutex());
  Factory() = std::move(factory);
}

std::shared_ptr<TopicSeam> SeamFor(const std::string& topic, Direction direction) {
  SeamFactory f;
  {
    std::lock_guard lock(FactoryMutex());
    f = Factory();
  }
  return f ? f(topic, direction) : nullptr;
}

}  // namespace rover::dds
