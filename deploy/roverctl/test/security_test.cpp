#include "rover/deploy/security.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "rover/runtime/security_files.hpp"
#include "rover/runtime/topic_access.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::deploy {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

int ModeOf(const std::string& path) {
  struct stat st {};
  stat(path.c_str(), &st);
  return static_cast<int>(st.st_mode & 0777);
}

TEST(SecurityOptions, ValidateNamesTheField) {
  SecurityOptions o;
  EXPECT_THAT(o.Validate().message(), HasSubstr("security.dir"));
  o.dir = "/tmp/x";
  EXPECT_TRUE(o.Validate().ok());
  o.site = "a/b";
  EXPECT_THAT(o.Validate().message(), HasSubstr("security.site: 'a/b' has '/'"));
  o.site = "rover";
  o.identity_days = 0;
  EXPECT_THAT(o.Validate().message(), HasSubstr("security.identity_days: 0"));
  o.identity_days = 10;
  o.domain_min = 5;
  o.domain_max = 4;
  EXPECT_THAT(o.Validate().message(), HasSubstr("security.domains: [5, 4]"));
}

TEST(SecurityDocuments, PermissionsGrantEachRoleItsTopicsOnly) {
  SecurityOptions o;
  o.dir = "/tmp/x";
  o.site = "test site";
  const std::string p = PermissionsXml(o, "2026-01-01T00:00:00", "2027-01-01T00:00:00");
  // dl-pose's grant publishes its estimate and the harness's topics, not drive commands.
  const std::size_t at = p.find("<grant name=\"dl-pose\">");
  ASSERT_NE(at, std::string::npos);
  const std::string grant = p.substr(at, p.find("</grant>", at) - at);
  EXPECT_THAT(grant, HasSubstr("<subject_name>CN=dl-pose,O=test site</subject_name>"));
  const std::string publish = grant.substr(grant.find("<publish>"),
                                           grant.find("</publish>") - grant.find("<publish>"));
  EXPECT_THAT(publish, HasSubstr("<topic>dl/pose</topic>"));
  EXPECT_THAT(publish, HasSubstr("<topic>sys/health</topic>"));
  EXPECT_EQ(publish.find("dl/drive_command"), std::string::npos);
  EXPECT_THAT(grant, HasSubstr("<default>DENY</default>"));
  // One grant per role.
  std::size_t grants = 0;
  for (std::size_t i = p.find("<grant "); i != std::string::npos; i = p.find("<grant ", i + 1)) {
    ++grants;
  }
  EXPECT_EQ(grants, dds::RoleAccessTable().size());
  const std::string g = GovernanceXml(o);
  EXPECT_THAT(g, HasSubstr("<allow_unauthenticated_participants>false"));
  EXPECT_THAT(g, HasSubstr("<data_protection_kind>ENCRYPT"));
  EXPECT_THAT(g, HasSubstr("<min>0</min><max>230</max>"));
}

class SecurityDir : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = rover::testing::MakeTempDir("security") + "/keys"; }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(fs::path(dir_).parent_path(), ec);
  }
  SecurityOptions Options() const {
    SecurityOptions o;
    o.dir = dir_;
    o.identity_days = 30;
    return o;
  }
  std::string dir_;
};

TEST_F(SecurityDir, InitMakesVerifiableKeysWithPrivateModes) {
  ASSERT_TRUE(InitSecurity(Options(), false).ok());
  const dds::SecurityFiles f = dds::SecurityFilesFor(dir_, "dl-pose");
  EXPECT_TRUE(dds::CheckSecurityFiles(f).ok());
  EXPECT_EQ(ModeOf(dir_), 0700);
  EXPECT_EQ(ModeOf(dir_ + "/ca.key.pem"), 0600);
  EXPECT_EQ(ModeOf(f.private_key), 0600);
  EXPECT_TRUE(VerifySecurity(dir_).ok()) << VerifySecurity(dir_).message();
  // Valid for 30 days, not for 40.
  EXPECT_THAT(VerifySecurity(dir_, {"dl-pose"}, 40).message(),
              HasSubstr("dl-pose.pem: expired or expiring within 40 days"));
  EXPECT_THAT(VerifySecurity(dir_, {"no-such-role"}).message(), HasSubstr("no such role"));
  auto show = DescribeSecurity(dir_);
  ASSERT_TRUE(show.ok()) << show.status().message();
  EXPECT_THAT(*show, HasSubstr("dl-pose"));
  EXPECT_THAT(*show, HasSubstr("checks: every identity verifies"));
  // Rotating keeps the authority and remakes the identities.
  const std::string ca = rover::testing::ReadFile(dir_ + "/ca.pem");
  const std::string key = rover::testing::ReadFile(f.private_key);
  ASSERT_TRUE(RotateSecurity(Options()).ok());
  EXPECT_EQ(rover::testing::ReadFile(dir_ + "/ca.pem"), ca);
  EXPECT_NE(rover::testing::ReadFile(f.private_key), key);
  EXPECT_TRUE(VerifySecurity(dir_).ok());
  // A new authority invalidates nothing in place: everything is remade under it.
  ASSERT_TRUE(InitSecurity(Options(), true).ok());
  EXPECT_NE(rover::testing::ReadFile(dir_ + "/ca.pem"), ca);
  EXPECT_TRUE(VerifySecurity(dir_).ok());
}

TEST_F(SecurityDir, BrokenFilesAreNamed) {
  EXPECT_THAT(RotateSecurity(Options()).message(), HasSubstr("no authority to rotate under"));
  ASSERT_TRUE(InitSecurity(Options(), false).ok());
  const dds::SecurityFiles f = dds::SecurityFilesFor(dir_, "dl-locomotion");
  // A permissions document changed after signing.
  std::string p7s = rover::testing::ReadFile(f.permissions);
  const std::size_t at = p7s.find("<default>DENY</default>");
  ASSERT_NE(at, std::string::npos);
  std::string tampered = p7s;
  tampered.replace(at, 23, "<default>ALLOW</default>");
  std::ofstream(f.permissions) << tampered;
  EXPECT_THAT(VerifySecurity(dir_, {"dl-locomotion"}).message(),
              HasSubstr("permissions.p7s: signature does not verify"));
  std::ofstream(f.permissions) << p7s;
  ASSERT_TRUE(VerifySecurity(dir_, {"dl-locomotion"}).ok());
  // Another role's key beside this role's certificate.
  fs::copy_file(dds::SecurityFilesFor(dir_, "dl-pose").private_key, f.private_key,
                fs::copy_options::overwrite_existing);
  EXPECT_THAT(VerifySecurity(dir_, {"dl-locomotion"}).message(),
              HasSubstr("dl-locomotion.key.pem: does not match"));
  // A missing certificate.
  fs::remove(f.certificate);
  EXPECT_THAT(VerifySecurity(dir_, {"dl-locomotion"}).message(),
              HasSubstr("dl-locomotion.pem: missing identity certificate"));
  // A certificate from another authority.
  SecurityOptions other = Options();
  other.dir = dir_ + "-other";
  ASSERT_TRUE(InitSecurity(other, false).ok());
  fs::copy_file(dds::SecurityFilesFor(other.dir, "dl-locomotion").certificate, f.certificate);
  EXPECT_THAT(VerifySecurity(dir_, {"dl-locomotion"}).message(),
              HasSubstr("dl-locomotion.pem: not signed by"));
}

}  // namespace
}  // namespace rover::deploy
