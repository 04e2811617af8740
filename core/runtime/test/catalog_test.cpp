#include "rover/runtime/topic_catalog.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

TEST(Catalog, NamesFollowLayerNounAndAreUnique) {
  std::set<std::string_view> names;
  const std::regex pattern("^(hw|ddl|dl|apl|sys|sim)/[a-z_]+$");
  for (const auto& t : TopicCatalog()) {
    EXPECT_TRUE(std::regex_match(std::string(t.name), pattern)) << t.name;
    EXPECT_TRUE(names.insert(t.name).second) << "duplicate " << t.name;
    // The type must come from the IDL family of the topic's layer.
    const std::string layer(t.name.substr(0, t.name.find('/')));
    EXPECT_EQ(std::string(t.type_name).rfind("rover_" + layer + "_", 0), 0u) << t.name;
  }
  EXPECT_TRUE(FindTopic("dl/pose").has_value());
  EXPECT_FALSE(FindTopic("dl/nothing").has_value());
}

// docs/topics.md is the catalog for people; every topic must appear there with its DDS type name
// (what other vendors match on, from the type's descriptor) and QoS profile in one table row:
// | `topic` | `rover::layer::Type` | profile | ...
TEST(Catalog, DocsListEveryTopicWithTypeAndProfile) {
  const std::string doc = testing::ReadFile(testing::SourceDir() + "/docs/topics.md");
  ASSERT_FALSE(doc.empty()) << "docs/topics.md is missing";
  for (const auto& t : TopicCatalog()) {
    const dds_topic_descriptor_t* d = DescriptorForType(t.type_name);
    ASSERT_NE(d, nullptr) << t.name << ": no descriptor for " << t.type_name;
    const std::string row = "| `" + std::string(t.name) + "` | `" + d->m_typename + "` | " +
                            QosProfileName(t.profile) + " |";
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/topics.md lacks the row: " << row;
  }
}

// The DDS name is the C name with "::" for "_" between module and type: rover_dl_PoseEstimate
// is rover::dl::PoseEstimate on the wire.
TEST(Catalog, DdsTypeNameIsTheScopedIdlName) {
  for (const auto& t : TopicCatalog()) {
    const dds_topic_descriptor_t* d = DescriptorForType(t.type_name);
    ASSERT_NE(d, nullptr) << t.name;
    std::string expected(t.type_name);
    expected.replace(expected.find('_'), 1, "::");
    expected.replace(expected.find('_'), 1, "::");
    EXPECT_EQ(std::string(d->m_typename), expected) << t.name;
  }
}

}  // namespace
}  // namespace rover::dds
