// Checkpoints of stateful services: round trip, atomic replacement, set id scoping, bad files.
#include "rover/base/checkpoint.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rover {
namespace {

namespace fs = std::filesystem;

class CheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("checkpoint-test-" + std::to_string(getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path() const { return (dir_ / "checkpoints" / "svc.ckpt").string(); }
  fs::path dir_;
};

TEST_F(CheckpointTest, RoundTripAndTheNextSaveReplacesTheLast) {
  CheckpointStore store(Path(), "proj.1.abc/svc");
  ASSERT_TRUE(store.enabled());
  auto none = store.Load();
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  ASSERT_TRUE(store.Save({{"x", "1.5"}, {"note", "two words"}}).ok());
  ASSERT_TRUE(store.Save({{"x", "2.5"}}).ok());
  auto got = store.Load();
  ASSERT_TRUE(got.ok()) << got.status().message();
  ASSERT_TRUE(got->has_value());
  EXPECT_EQ(**got, (std::map<std::string, std::string>{{"x", "2.5"}}));
  // No temporary file is left next to it.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "checkpoints")) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  store.Remove();
  EXPECT_FALSE(store.Load()->has_value());
}

TEST_F(CheckpointTest, AnotherSetsCheckpointIsNotResumed) {
  ASSERT_TRUE(CheckpointStore(Path(), "proj.1.abc/svc").Save({{"x", "1"}}).ok());
  auto other = CheckpointStore(Path(), "proj.2.def/svc").Load();
  ASSERT_TRUE(other.ok());
  EXPECT_FALSE(other->has_value());
}

TEST_F(CheckpointTest, BadKeysAndFilesAreErrorsNamingThePath) {
  CheckpointStore store(Path(), "s");
  EXPECT_FALSE(store.Save({{"two words", "1"}}).ok());
  EXPECT_FALSE(store.Save({{"set_id", "x"}}).ok());
  EXPECT_FALSE(store.Save({{"k", "a\nb"}}).ok());
  fs::create_directories(dir_ / "checkpoints");
  std::ofstream(Path()) << "something else\n";
  auto bad = store.Load();
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find(Path() + ":1:"), std::string::npos)
      << bad.status().message();
  std::ofstream(Path()) << "rover-checkpoint 1\nx 1\n";
  EXPECT_FALSE(store.Load().ok());  // no set_id
}

TEST_F(CheckpointTest, OnlyASupervisedServiceHasAStore) {
  unsetenv("ROVER_SET_ID");
  setenv("ROVER_STATE_DIR", dir_.c_str(), 1);
  EXPECT_FALSE(CheckpointStore::FromEnvironment("svc").enabled());
  EXPECT_FALSE(CheckpointStore().Save({{"x", "1"}}).ok());
  setenv("ROVER_SET_ID", "proj.1.abc/svc", 1);
  const CheckpointStore s = CheckpointStore::FromEnvironment("svc");
  ASSERT_TRUE(s.enabled());
  EXPECT_EQ(s.path(), Path());
  EXPECT_EQ(s.set_id(), "proj.1.abc/svc");
  unsetenv("ROVER_SET_ID");
  unsetenv("ROVER_STATE_DIR");
}

}  // namespace
}  // namespace rover
