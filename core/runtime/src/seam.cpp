#include "rover/runtime/seam.hpp"

#include <mutex>

namespace rover::dds {
namespace {
std::mutex& SeamMutex() {
  static std::mutex m;
  return m;
}
SeamFactory& Factory() {
  static SeamFactory f;
  return f;
}
std::shared_ptr<SeamPump>& Pump() {
  static std::shared_ptr<SeamPump> p;
  return p;
}
}  // namespace

void InstallSeamFactory(SeamFactory factory) {
  std::lock_guard lock(SeamMutex());
  Factory() = std::move(factory);
}

std::shared_ptr<TopicSeam> SeamFor(const std::string& topic, Direction direction) {
  SeamFactory f;
  {
    std::lock_guard lock(SeamMutex());
    f = Factory();
  }
  return f ? f(topic, direction) : nullptr;
}

void InstallSeamPump(std::shared_ptr<SeamPump> pump) {
  std::lock_guard lock(SeamMutex());
  Pump() = std::move(pump);
}

std::shared_ptr<SeamPump> CurrentSeamPump() {
  std::lock_guard lock(SeamMutex());
  return Pump();
}

}  // namespace rover::dds
