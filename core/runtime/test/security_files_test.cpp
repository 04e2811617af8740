#include "rover/runtime/security_files.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "rover/runtime/dds.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

// A process told to join a secured set refuses to make a participant with missing or wrong
// files, naming the file; a directory without a role is a configuration error.
TEST(SecuredParticipant, MissingFilesAreNamedBeforeDdsIsAsked) {
  const std::string dir = testing::MakeTempDir("secured-participant");
  setenv(kSecurityDirVariable, dir.c_str(), 1);
  unsetenv(kSecurityIdentityVariable);
  auto p = Participant::Create(0);
  EXPECT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("ROVER_SECURITY_IDENTITY is not"), std::string::npos)
      << p.status().message();
  setenv(kSecurityIdentityVariable, "dl-pose", 1);
  p = Participant::Create(0);
  EXPECT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find(dir + "/ca.pem: missing CA certificate"), std::string::npos)
      << p.status().message();
  // Something that is not a certificate where the certificate should be.
  std::ofstream(dir + "/ca.pem") << "hello\n";
  p = Participant::Create(0);
  EXPECT_NE(p.status().message().find("ca.pem: not a CA certificate"), std::string::npos)
      << p.status().message();
  unsetenv(kSecurityDirVariable);
  unsetenv(kSecurityIdentityVariable);
  EXPECT_TRUE(Participant::Create(0).ok());
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace
}  // namespace rover::dds
