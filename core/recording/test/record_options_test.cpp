#include "rover/recording/record_options.hpp"

#include <gtest/gtest.h>

namespace rover::recording {
namespace {

Result<RecordOptions> Parse(const std::string& yaml_text) {
  const yaml::FileErrors err("s.yaml");
  const YAML::Node root = YAML::Load(yaml_text);
  return ParseRecordOptions(root["record"], "record", err);
}

TEST(RecordOptions, BooleansAndMaps) {
  auto off = Parse("record: false\n");
  ASSERT_TRUE(off.ok());
  EXPECT_FALSE(off->enabled);
  auto on = Parse("record: true\n");
  ASSERT_TRUE(on.ok());
  EXPECT_TRUE(on->enabled);
  EXPECT_EQ(on->compression, mcap::Compression::kZstd);
  auto full = Parse(
      "record:\n  path: run.mcap\n  topics: ['ddl/*', dl/range_image]\n  exclude: ddl/stereo_frame\n"
      "  size_cap_mb: 250\n  compression: lz4\n");
  ASSERT_TRUE(full.ok()) << full.status().message();
  EXPECT_TRUE(full->enabled);
  EXPECT_EQ(full->path, "run.mcap");
  EXPECT_EQ(full->topics.include, (std::vector<std::string>{"ddl/*", "dl/range_image"}));
  EXPECT_EQ(full->topics.exclude, (std::vector<std::string>{"ddl/stereo_frame"}));
  EXPECT_EQ(full->size_cap_mb, 250);
  EXPECT_EQ(full->compression, mcap::Compression::kLz4);
  const mcap::WriterOptions w = full->WriterOptions();
  EXPECT_EQ(w.size_cap_bytes, 250'000'000u);
  EXPECT_EQ(w.compression, mcap::Compression::kLz4);
  EXPECT_TRUE(full->Validate().ok());
}

TEST(RecordOptions, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(Parse("record:\n  compresion: zstd\n").status().message().substr(0, 51),
            "s.yaml:2: record: unknown key 'compresion' (did you");
  EXPECT_NE(Parse("record:\n  compression: gzip\n").status().message().find(
                "s.yaml:2: record.compression: 'gzip' is not one of: zstd, lz4, none"),
            std::string::npos)
      << Parse("record:\n  compression: gzip\n").status().message();
  EXPECT_NE(Parse("record:\n  size_cap_mb: -3\n").status().message().find(
                "s.yaml:2: record.size_cap_mb: -3 is out of range"),
            std::string::npos)
      << Parse("record:\n  size_cap_mb: -3\n").status().message();
  EXPECT_NE(Parse("record:\n  size_cap_mb: 0.001\n").status().message().find("below 0.01 MB"),
            std::string::npos);
  EXPECT_NE(Parse("record:\n  topics: ['']\n").status().message().find(
                "s.yaml:2: record.topics: empty topic pattern"),
            std::string::npos)
      << Parse("record:\n  topics: ['']\n").status().message();
  EXPECT_NE(Parse("record: maybe\n").status().message().find(
                "s.yaml:1: record: expected true, false or a map"),
            std::string::npos);
  EXPECT_NE(Parse("record:\n  topics: {a: b}\n").status().message().find(
                "record.topics: expected a topic pattern or a list"),
            std::string::npos);
}

TEST(RecordOptions, ValidateAndCompressionNames) {
  RecordOptions o;
  o.size_cap_mb = 0.001;
  EXPECT_FALSE(o.Validate().ok());
  o.size_cap_mb = 0;
  EXPECT_TRUE(o.Validate().ok());
  for (auto c : {mcap::Compression::kZstd, mcap::Compression::kLz4, mcap::Compression::kNone}) {
    auto back = ParseCompression(CompressionText(c));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, c);
  }
  EXPECT_EQ(ParseCompression("bz2").status().message(),
            "compression 'bz2' is not one of: zstd, lz4, none");
}

TEST(RecordOptions, APatternThatMatchesNoKnownTopicIsAnError) {
  const yaml::FileErrors err("s.yaml");
  const std::vector<std::string> known = {"hw/camera_frame", "ddl/stereo_frame", "dl/pose"};
  const YAML::Node typo = YAML::Load("record:\n  exclude: [hw/camera_frames]\n");
  auto bad = ParseRecordOptions(typo["record"], "record", err, {}, known);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "s.yaml:2: record.exclude: 'hw/camera_frames' matches no topic (did you mean "
            "'hw/camera_frame'?) (docs/topics.md lists them)");
  const YAML::Node glob = YAML::Load("record:\n  topics: ['ddl/*', dl/pose]\n  exclude: []\n");
  auto ok = ParseRecordOptions(glob["record"], "record", err, {}, known);
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_TRUE(ok->topics.exclude.empty());
  // Without the catalog nothing is checked (roverctl record checks against the live bus).
  EXPECT_TRUE(ParseRecordOptions(typo["record"], "record", err).ok());
}

}  // namespace
}  // namespace rover::recording
