#include "rover/ddl/driver_support/driver_params.hpp"

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace rover::ddl::driver_support {

void DeclareDriverHardwareParams(ParamSet& params) {
  DeclareHardwareParams(params, kHardwarePrefix);
  params.Declare("hardware_file", std::string(),
                 "hardware calibration file in the layout of deploy/config/rover_hardware.yaml; "
                 "empty = use the hardware.* keys (setting both is an error)");
}

Result<std::string> ResolveConfigFile(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) return InvalidArgument("empty file name");
  std::error_code ec;
  if (fs::path(path).is_absolute()) {
    if (fs::is_regular_file(path, ec)) return path;
    return NotFound(path + ": no such file");
  }
  std::string tried = (fs::current_path(ec) / path).string();
  if (fs::is_regular_file(path, ec)) return path;
  if (const char* src = std::getenv("ROVER_SOURCE_DIR"); src != nullptr && *src != '\0') {
    const std::string candidate = (fs::path(src) / path).string();
    if (fs::is_regular_file(candidate, ec)) return candidate;
    tried += ", " + candidate;
  }
  // Installed tree: <prefix>/bin/<service> reads <prefix>/share/rover/config/... for
  // "deploy/config/..." (deploy/CMakeLists.txt installs deploy/config there).
  if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec) {
    const std::string_view kDeployPrefix = "deploy/";
    const std::string rel =
        path.rfind(kDeployPrefix, 0) == 0 ? path.substr(kDeployPrefix.size()) : path;
    const std::string candidate =
        (exe.parent_path().parent_path() / "share" / "rover" / rel).lexically_normal().string();
    if (fs::is_regular_file(candidate, ec)) return candidate;
    tried += ", " + candidate;
  }
  return NotFound(path + ": no such file (tried " + tried + ")");
}

Result<HardwareConfig> DriverHardwareConfig(const ParamSet& params) {
  const std::string& file = params.GetString("hardware_file");
  if (file.empty()) return HardwareConfigFromParams(params, kHardwarePrefix);
  const std::string prefix = std::string(kHardwarePrefix) + ".";
  for (const std::string& name : params.names()) {
    if (name.rfind(prefix, 0) != 0) continue;
    const ParamOrigin& origin = params.Origin(name);
    if (origin.source != "default") {
      return InvalidArgument("key '" + name + "' (set at " + origin.ToString() +
                             ") and hardware_file '" + file +
                             "' are exclusive: give the calibration in one place");
    }
  }
  auto path = ResolveConfigFile(file);
  if (!path.ok()) return path.status().WithPrefix("hardware_file");
  return LoadHardwareConfig(*path);
}

}  // namespace rover::ddl::driver_support
