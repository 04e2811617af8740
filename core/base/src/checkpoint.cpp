// Checkpoints of stateful services (see checkpoint.hpp).
#include "rover/base/checkpoint.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace rover {
namespace {

namespace fs = std::filesystem;
constexpr const char* kMagic = "rover-checkpoint 1";

}  // namespace

CheckpointStore CheckpointStore::FromEnvironment(const std::string& service) {
  const char* dir = std::getenv("ROVER_STATE_DIR");
  const char* set = std::getenv("ROVER_SET_ID");
  if (dir == nullptr || set == nullptr || *dir == '\0' || *set == '\0' || service.empty()) {
    return CheckpointStore();
  }
  return CheckpointStore(std::string(dir) + "/checkpoints/" + service + ".ckpt", set);
}

CheckpointStore::CheckpointStore(std::string path, std::string set_id)
    : path_(std::move(path)), set_id_(std::move(set_id)) {}

Status CheckpointStore::Save(const std::map<std::string, std::string>& fields) const {
  if (!enabled()) return FailedPrecondition("checkpoint: no store (not in a supervised set)");
  for (const auto& [k, v] : fields) {
    if (k.empty() || k.find_first_of(" \t\n") != std::string::npos || k == "set_id") {
      return InvalidArgument("checkpoint " + path_ + ": bad key '" + k + "'");
    }
    if (v.find('\n') != std::string::npos) {
      return InvalidArgument("checkpoint " + path_ + ": value of '" + k + "' holds a newline");
    }
  }
  std::error_code ec;
  fs::create_directories(fs::path(path_).parent_path(), ec);
  const std::string tmp = path_ + ".tmp." + std::to_string(getpid());
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << kMagic << "\nset_id " << set_id_ << "\n";
    for (const auto& [k, v] : fields) out << k << ' ' << v << "\n";
    out.flush();
    if (!out) return Unavailable("checkpoint: cannot write " + tmp);
  }
  fs::rename(tmp, path_, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return Unavailable("checkpoint: cannot rename " + tmp + " to " + path_);
  }
  return Status::Ok();
}

Result<std::optional<std::map<std::string, std::string>>> CheckpointStore::Load() const {
  using Fields = std::map<std::string, std::string>;
  if (!enabled()) return std::optional<Fields>();
  std::ifstream in(path_);
  if (!in) return std::optional<Fields>();
  std::string line;
  if (!std::getline(in, line) || line != kMagic) {
    return InvalidArgument(path_ + ":1: not a checkpoint (expected '" + kMagic + "')");
  }
  Fields fields;
  std::optional<std::string> set;
  for (int n = 2; std::getline(in, line); ++n) {
    const auto sp = line.find(' ');
    if (sp == 0 || sp == std::string::npos) {
      return InvalidArgument(path_ + ":" + std::to_string(n) + ": expected 'key value', got '" +
                             line + "'");
    }
    const std::string key = line.substr(0, sp);
    if (key == "set_id") {
      set = line.substr(sp + 1);
    } else {
      fields[key] = line.substr(sp + 1);
    }
  }
  if (!set.has_value()) return InvalidArgument(path_ + ": no set_id line");
  if (*set != set_id_) return std::optional<Fields>();  // another set's: not ours to resume
  return std::optional<Fields>(std::move(fields));
}

void CheckpointStore::Remove() const {
  if (!enabled()) return;
  std::error_code ec;
  fs::remove(path_, ec);
}

}  // namespace rover
