#include "rover/ddl/driver_support/driver_params.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>

namespace rover::ddl::driver_support {
namespace {

const std::string kDeployFile =
    std::string(ROVER_SOURCE_DIR) + "/deploy/config/rover_hardware.yaml";

ParamSet Declared() {
  ParamSet p("ddl-test");
  DeclareDriverHardwareParams(p);
  return p;
}

TEST(DriverParams, DefaultsEqualTheDeployFile) {
  ParamSet p = Declared();
  ASSERT_TRUE(p.Validate().ok());
  auto from_params = DriverHardwareConfig(p);
  ASSERT_TRUE(from_params.ok()) << from_params.status().message();
  auto from_file = LoadHardwareConfig(kDeployFile);
  ASSERT_TRUE(from_file.ok()) << from_file.status().message();
  for (int m = 0; m < hw::kNumMotors; ++m) {
    EXPECT_DOUBLE_EQ(from_params->motors[m].CountsPerRad(), from_file->motors[m].CountsPerRad());
  }
  EXPECT_EQ(from_params->pots.offset_counts, from_file->pots.offset_counts);
  EXPECT_TRUE(from_params->imu.rover_from_case.isApprox(from_file->imu.rover_from_case));
}

TEST(DriverParams, HardwareSectionOfAServiceFileIsRead) {
  ParamSet p = Declared();
  ASSERT_TRUE(
      p.LoadYamlString("hardware:\n  motors:\n    drive:\n      gear_ratio: 1000\n", "svc.yaml")
          .ok());
  auto hw = DriverHardwareConfig(p);
  ASSERT_TRUE(hw.ok()) << hw.status().message();
  EXPECT_DOUBLE_EQ(hw->motors[0].gear_ratio, 1000.0);
}

TEST(DriverParams, HardwareFileIsLoadedAndErrorsNameTheFileLineAndKey) {
  ParamSet p = Declared();
  ASSERT_TRUE(p.SetFromString("hardware_file=" + kDeployFile).ok());
  auto hw = DriverHardwareConfig(p);
  ASSERT_TRUE(hw.ok()) << hw.status().message();
  EXPECT_DOUBLE_EQ(hw->motors[hw::kSteerLF].gear_ratio, 2500.0);

  const std::string dir = std::filesystem::temp_directory_path() / "ddl_driver_params_test";
  std::filesystem::create_directories(dir);
  const std::string bad = dir + "/bad_hw.yaml";
  std::ofstream(bad) << "motors:\n  drive:\n    gear_ratio: -3\n";
  ParamSet q = Declared();
  ASSERT_TRUE(q.SetFromString("hardware_file=" + bad).ok());
  auto e = DriverHardwareConfig(q);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("bad_hw.yaml:3"), std::string::npos) << e.status().message();
  EXPECT_NE(e.status().message().find("motors.drive.gear_ratio"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(DriverParams, FileAndKeysTogetherAreRejectedNamingTheKey) {
  ParamSet p = Declared();
  ASSERT_TRUE(p.SetFromString("hardware_file=" + kDeployFile).ok());
  ASSERT_TRUE(p.SetFromString("hardware.pots.rate_hz=40").ok());
  auto hw = DriverHardwareConfig(p);
  ASSERT_FALSE(hw.ok());
  EXPECT_EQ(hw.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hw.status().message().find("hardware.pots.rate_hz"), std::string::npos)
      << hw.status().message();
  EXPECT_NE(hw.status().message().find("--set"), std::string::npos);
}

TEST(DriverParams, MissingFileIsNotFoundNamingThePathsTried) {
  ParamSet p = Declared();
  ASSERT_TRUE(p.SetFromString("hardware_file=no/such/hw.yaml").ok());
  auto hw = DriverHardwareConfig(p);
  ASSERT_FALSE(hw.ok());
  EXPECT_EQ(hw.status().code(), StatusCode::kNotFound);
  EXPECT_NE(hw.status().message().find("hardware_file: no/such/hw.yaml"), std::string::npos)
      << hw.status().message();
}

TEST(DriverParams, RelativePathsFallBackToTheSourceDir) {
  const char* old = std::getenv("ROVER_SOURCE_DIR");
  const std::string saved = old ? old : "";
  setenv("ROVER_SOURCE_DIR", ROVER_SOURCE_DIR, 1);
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  auto r = ResolveConfigFile("deploy/config/rover_hardware.yaml");
  std::filesystem::current_path(cwd);
  if (old)
    setenv("ROVER_SOURCE_DIR", saved.c_str(), 1);
  else
    unsetenv("ROVER_SOURCE_DIR");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(*r, std::string(ROVER_SOURCE_DIR) + "/deploy/config/rover_hardware.yaml");
  EXPECT_EQ(ResolveConfigFile("/no/such/file.yaml").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(ResolveConfigFile("").status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace rover::ddl::driver_support
