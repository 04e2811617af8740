#include "rover/runtime/security_files.hpp"

#include <dds/dds.h>
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace rover::dds {
namespace {

namespace fs = std::filesystem;

Status CheckFile(const std::string& path, const char* what, const char* marker) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    return FailedPrecondition(path + ": missing " + what + " (run `roverctl security init`)");
  }
  std::ifstream in(path);
  if (!in) return FailedPrecondition(path + ": cannot read the " + std::string(what));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find(marker) == std::string::npos) {
    return FailedPrecondition(path + ": not a " + std::string(what) + " (no '" + marker + "')");
  }
  return Status::Ok();
}

}  // namespace

SecurityFiles SecurityFilesFor(const std::string& dir, const std::string& role) {
  SecurityFiles f;
  f.ca = dir + "/ca.pem";
  f.governance = dir + "/governance.p7s";
  f.permissions = dir + "/permissions.p7s";
  f.certificate = dir + "/identities/" + role + ".pem";
  f.private_key = dir + "/identities/" + role + ".key.pem";
  return f;
}

Status CheckSecurityFiles(const SecurityFiles& f) {
  ROVER_RETURN_IF_ERROR(CheckFile(f.ca, "CA certificate", "BEGIN CERTIFICATE"));
  ROVER_RETURN_IF_ERROR(CheckFile(f.governance, "signed governance document", "MIME-Version"));
  ROVER_RETURN_IF_ERROR(CheckFile(f.permissions, "signed permissions document", "MIME-Version"));
  ROVER_RETURN_IF_ERROR(CheckFile(f.certificate, "identity certificate", "BEGIN CERTIFICATE"));
  ROVER_RETURN_IF_ERROR(CheckFile(f.private_key, "private key", "PRIVATE KEY"));
  return Status::Ok();
}

Result<std::optional<SecurityIdentity>> SecurityIdentityFromEnvironment() {
  const char* dir = std::getenv(kSecurityDirVariable);
  if (dir == nullptr || *dir == '\0') return std::optional<SecurityIdentity>{};
  const char* role = std::getenv(kSecurityIdentityVariable);
  if (role == nullptr || *role == '\0') {
    return InvalidArgument(std::string(kSecurityDirVariable) + "=" + dir + " is set but " +
                           kSecurityIdentityVariable +
                           " is not: a secured participant needs its role's identity");
  }
  return std::optional<SecurityIdentity>(SecurityIdentity{dir, role});
}

Result<std::string> SecurityPluginDir() {
  const std::string lib = "libdds_security_auth.so";
  std::string looked;
  auto has = [&](const std::string& d) {
    looked += (looked.empty() ? "" : ", ") + d;
    return access((d + "/" + lib).c_str(), R_OK) == 0;
  };
  if (const char* o = std::getenv("ROVER_DDS_SECURITY_LIB_DIR"); o != nullptr && *o != '\0') {
    if (has(o)) return std::string(o);
    return NotFound(lib + " is not in ROVER_DDS_SECURITY_LIB_DIR=" + o);
  }
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&dds_create_participant), &info) != 0 &&
      info.dli_fname != nullptr) {
    const std::string here = fs::path(info.dli_fname).parent_path().string();
    for (const std::string& d : {here + "/libddsc0debian", here}) {
      if (has(d)) return d;
    }
  }
  return NotFound("Cyclone DDS's security plugins (" + lib + ") were not found in " + looked +
                  "; set ROVER_DDS_SECURITY_LIB_DIR");
}

}  // namespace rover::dds
