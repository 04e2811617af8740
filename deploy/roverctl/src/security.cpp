#include "rover/deploy/security.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "rover/base/process.hpp"
#include "rover/runtime/security_files.hpp"
#include "rover/runtime/topic_access.hpp"

namespace rover::deploy {
namespace {

namespace fs = std::filesystem;

Status WriteText(const std::string& path, const std::string& text, mode_t mode) {
  {
    std::ofstream out(path, std::ios::trunc);
    if (!(out << text)) return Unavailable(path + ": cannot write");
  }
  if (chmod(path.c_str(), mode) != 0) return Unavailable(path + ": cannot set its mode");
  return Status::Ok();
}

// Runs `openssl args...` (scratch files in `work`); returns stdout, or an error naming `what`
// with OpenSSL's own last line.
Result<std::string> Openssl(const std::string& work, const std::string& what,
                            std::vector<std::string> args) {
  args.insert(args.begin(), "openssl");
  auto r = RunCommand(args, work, std::chrono::seconds(60));
  if (!r.ok()) {
    return r.status().code() == StatusCode::kTimeout
               ? Timeout(what + ": " + r.status().message())
               : NotFound(what + ": cannot run openssl (" + r.status().message() +
                          "); scripts/setup.sh installs it");
  }
  if (!r->exit.success()) {
    const std::string why = r->LastErrorLine();
    return FailedPrecondition(what + ": openssl " + r->exit.ToString() +
                              (why.empty() ? "" : ": " + why));
  }
  return r->out;
}

std::string Stamp(std::chrono::system_clock::time_point t) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&tt, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

std::string RandomSerial() {
  std::random_device rd;
  const unsigned long long v = (static_cast<unsigned long long>(rd()) << 31) ^ rd();
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%llx", v | 1ULL);
  return buf;
}

std::vector<std::string> AllRoles() {
  std::vector<std::string> out;
  for (const auto& r : dds::RoleAccessTable()) out.emplace_back(r.role);
  return out;
}

std::string Domains(const SecurityOptions& o) {
  return "<domains><id_range><min>" + std::to_string(o.domain_min) + "</min><max>" +
         std::to_string(o.domain_max) + "</max></id_range></domains>";
}

std::string TopicList(const std::vector<std::string>& topics) {
  std::string s = "<topics>";
  for (const auto& t : topics) s += "<topic>" + t + "</topic>";
  return s + "</topics><partitions><partition>*</partition></partitions>";
}

Status MakeIdentity(const std::string& work, const SecurityOptions& o, const std::string& ca,
                    const std::string& ca_key, const std::string& role) {
  const dds::SecurityFiles f = dds::SecurityFilesFor(work, role);
  const std::string what = "identity '" + role + "'";
  ROVER_RETURN_IF_ERROR(Openssl(work, what + ": key", {"ecparam", "-name", "prime256v1",
                                                       "-genkey", "-noout", "-out",
                                                       f.private_key})
                            .status());
  chmod(f.private_key.c_str(), 0600);
  const std::string csr = work + "/identities/" + role + ".csr";
  ROVER_RETURN_IF_ERROR(Openssl(work, what + ": request",
                                {"req", "-new", "-sha256", "-key", f.private_key, "-subj",
                                 "/CN=" + role + "/O=" + o.site, "-out", csr})
                            .status());
  ROVER_RETURN_IF_ERROR(Openssl(work, what + ": certificate",
                                {"x509", "-req", "-sha256", "-in", csr, "-CA", ca, "-CAkey",
                                 ca_key, "-set_serial", RandomSerial(), "-days",
                                 std::to_string(o.identity_days), "-out", f.certificate})
                            .status());
  std::error_code ec;
  fs::remove(csr, ec);
  return Status::Ok();
}

Status Sign(const std::string& work, const std::string& xml, const std::string& p7s,
            const std::string& ca, const std::string& ca_key) {
  return Openssl(work, "signing " + fs::path(xml).filename().string(),
                 {"smime", "-sign", "-in", xml, "-text", "-out", p7s, "-signer", ca, "-inkey",
                  ca_key})
      .status();
}

// Writes a fresh directory in `work`, then renames its files over `dir`'s.
Status Make(const SecurityOptions& o, bool new_authority) {
  ROVER_RETURN_IF_ERROR(o.Validate());
  std::error_code ec;
  fs::create_directories(o.dir, ec);
  if (ec) return Unavailable(o.dir + ": cannot create the security directory: " + ec.message());
  chmod(o.dir.c_str(), 0700);
  const std::string work = o.dir + "/.init-" + std::to_string(getpid());
  fs::remove_all(work, ec);
  fs::create_directories(work + "/identities", ec);
  chmod(work.c_str(), 0700);
  auto run = [&]() -> Status {
    const std::string ca = work + "/ca.pem";
    const std::string ca_key = work + "/ca.key.pem";
    const bool keep = !new_authority && fs::exists(o.dir + "/ca.pem") &&
                      fs::exists(o.dir + "/ca.key.pem");
    if (keep) {
      fs::copy_file(o.dir + "/ca.pem", ca, ec);
      if (!ec) fs::copy_file(o.dir + "/ca.key.pem", ca_key, ec);
      if (ec) return Unavailable(o.dir + ": cannot read the authority: " + ec.message());
      chmod(ca_key.c_str(), 0600);
    } else {
      ROVER_RETURN_IF_ERROR(Openssl(work, "authority key", {"ecparam", "-name", "prime256v1",
                                                            "-genkey", "-noout", "-out", ca_key})
                                .status());
      chmod(ca_key.c_str(), 0600);
      ROVER_RETURN_IF_ERROR(Openssl(work, "authority certificate",
                                    {"req", "-new", "-x509", "-sha256", "-key", ca_key, "-days",
                                     std::to_string(o.ca_days), "-subj",
                                     "/CN=" + o.site + " security authority/O=" + o.site, "-out",
                                     ca})
                                .status());
    }
    for (const std::string& role : AllRoles()) {
      ROVER_RETURN_IF_ERROR(MakeIdentity(work, o, ca, ca_key, role));
    }
    const auto now = std::chrono::system_clock::now();
    ROVER_RETURN_IF_ERROR(WriteText(work + "/governance.xml", GovernanceXml(o), 0644));
    ROVER_RETURN_IF_ERROR(WriteText(
        work + "/permissions.xml",
        PermissionsXml(o, Stamp(now - std::chrono::hours(1)),
                       Stamp(now + std::chrono::hours(24) * o.identity_days)),
        0644));
    ROVER_RETURN_IF_ERROR(Sign(work, work + "/governance.xml", work + "/governance.p7s", ca, ca_key));
    ROVER_RETURN_IF_ERROR(
        Sign(work, work + "/permissions.xml", work + "/permissions.p7s", ca, ca_key));
    return Status::Ok();
  };
  const Status st = run();
  if (!st.ok()) {
    fs::remove_all(work, ec);
    return st;
  }
  fs::create_directories(o.dir + "/identities", ec);
  chmod((o.dir + "/identities").c_str(), 0700);
  for (const auto& e : fs::recursive_directory_iterator(work)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), work);
    fs::rename(e.path(), fs::path(o.dir) / rel, ec);
    if (ec) {
      return Unavailable((fs::path(o.dir) / rel).string() + ": cannot install: " + ec.message());
    }
  }
  fs::remove_all(work, ec);
  return Status::Ok();
}

}  // namespace

Status SecurityOptions::Validate() const {
  if (dir.empty()) return InvalidArgument("security.dir: empty");
  if (site.empty()) return InvalidArgument("security.site: empty");
  for (char c : site) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ||
          c == ' ')) {
      return InvalidArgument("security.site: '" + site + "' has '" + std::string(1, c) +
                             "' (letters, digits, '-', '_', '.' and spaces only)");
    }
  }
  if (identity_days <= 0) {
    return InvalidArgument("security.identity_days: " + std::to_string(identity_days) +
                           " must be positive");
  }
  if (ca_days <= 0) {
    return InvalidArgument("security.ca_days: " + std::to_string(ca_days) + " must be positive");
  }
  if (domain_min < 0 || domain_max > 230 || domain_min > domain_max) {
    return InvalidArgument("security.domains: [" + std::to_string(domain_min) + ", " +
                           std::to_string(domain_max) + "] is not a range within [0, 230]");
  }
  return Status::Ok();
}

std::string SecurityDirOf(const std::string& state_root) { return state_root + "/security"; }

std::string GovernanceXml(const SecurityOptions& o) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      )" + Domains(o) + R"(
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
)";
}

std::string PermissionsXml(const SecurityOptions& o, const std::string& not_before,
                           const std::string& not_after) {
  std::string s = R"(<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
)";
  for (const auto& r : dds::RoleAccessTable()) {
    const std::string role(r.role);
    s += "    <grant name=\"" + role + "\">\n";
    s += "      <subject_name>CN=" + role + ",O=" + o.site + "</subject_name>\n";
    s += "      <validity><not_before>" + not_before + "</not_before><not_after>" + not_after +
         "</not_after></validity>\n";
    s += "      <allow_rule>\n        " + Domains(o) + "\n";
    const auto w = dds::TopicsWritten(role);
    const auto rd = dds::TopicsRead(role);
    if (!w.empty()) s += "        <publish>" + TopicList(w) + "</publish>\n";
    if (!rd.empty()) s += "        <subscribe>" + TopicList(rd) + "</subscribe>\n";
    s += "      </allow_rule>\n      <default>DENY</default>\n    </grant>\n";
  }
  s += "  </permissions>\n</dds>\n";
  return s;
}

Status InitSecurity(const SecurityOptions& options, bool new_authority) {
  return Make(options, new_authority);
}

Status RotateSecurity(const SecurityOptions& options) {
  if (!fs::exists(options.dir + "/ca.pem")) {
    return FailedPrecondition(options.dir + "/ca.pem: no authority to rotate under (run "
                              "`roverctl security init` first)");
  }
  return Make(options, false);
}

Status VerifySecurity(const std::string& dir, const std::vector<std::string>& given,
                      int margin_days) {
  const std::vector<std::string> roles = given.empty() ? AllRoles() : given;
  const std::string ca = dir + "/ca.pem";
  for (const std::string& role : roles) {
    if (!dds::FindRole(role)) {
      return FailedPrecondition("identity '" + role + "': no such role in the topic access "
                                "table (core/runtime topic_access.cpp)");
    }
    const dds::SecurityFiles f = dds::SecurityFilesFor(dir, role);
    ROVER_RETURN_IF_ERROR(dds::CheckSecurityFiles(f));
    auto v = Openssl(dir, f.certificate + ": not signed by " + ca, {"verify", "-CAfile", ca, f.certificate});
    if (!v.ok()) return FailedPrecondition(v.status().message());
    auto end = Openssl(dir, f.certificate + ": expired or expiring within " +
                                std::to_string(margin_days) + " days",
                       {"x509", "-in", f.certificate, "-noout", "-checkend",
                        std::to_string(static_cast<long long>(margin_days) * 86400)});
    if (!end.ok()) return FailedPrecondition(end.status().message());
    ROVER_ASSIGN_OR_RETURN(const std::string cert_pub,
                           Openssl(dir, f.certificate, {"x509", "-in", f.certificate, "-noout",
                                                        "-pubkey"}));
    ROVER_ASSIGN_OR_RETURN(const std::string key_pub,
                           Openssl(dir, f.private_key, {"pkey", "-in", f.private_key, "-pubout"}));
    if (cert_pub != key_pub) {
      return FailedPrecondition(f.private_key + ": does not match " + f.certificate);
    }
  }
  for (const char* doc : {"governance", "permissions"}) {
    const std::string p7s = dir + "/" + doc + ".p7s";
    auto v = Openssl(dir, p7s + ": signature does not verify against " + ca,
                     {"smime", "-verify", "-in", p7s, "-CAfile", ca, "-text"});
    if (!v.ok()) return FailedPrecondition(v.status().message());
    if (v->find("<dds") == std::string::npos || v->find("</dds>") == std::string::npos) {
      return FailedPrecondition(p7s + ": the signed " + doc + " document does not parse");
    }
  }
  return Status::Ok();
}

Result<std::string> DescribeSecurity(const std::string& dir) {
  const std::string ca = dir + "/ca.pem";
  if (!fs::exists(ca)) {
    return NotFound(ca + ": no security directory here (run `roverctl security init`)");
  }
  std::string out = "security directory " + dir + "\n";
  ROVER_ASSIGN_OR_RETURN(const std::string ca_info,
                         Openssl(dir, ca, {"x509", "-in", ca, "-noout", "-subject", "-enddate"}));
  out += "authority: " + ca_info;
  out += "identities (certificate expiry; topics written / read):\n";
  for (const auto& r : dds::RoleAccessTable()) {
    const std::string role(r.role);
    const dds::SecurityFiles f = dds::SecurityFilesFor(dir, role);
    auto end = Openssl(dir, f.certificate, {"x509", "-in", f.certificate, "-noout", "-enddate"});
    std::string e = end.ok() ? *end : "missing\n";
    if (e.rfind("notAfter=", 0) == 0) e = e.substr(9);
    if (!e.empty() && e.back() == '\n') e.pop_back();
    char line[256];
    std::snprintf(line, sizeof line, "  %-18s %-26s %zu / %zu\n", role.c_str(), e.c_str(),
                  dds::TopicsWritten(role).size(), dds::TopicsRead(role).size());
    out += line;
  }
  const Status v = VerifySecurity(dir);
  out += v.ok() ? "checks: every identity verifies against the authority and matches its key; "
                  "governance and permissions verify\n"
                : "checks: FAILED: " + v.message() + "\n";
  return out;
}

}  // namespace rover::deploy
