#include "rover/runtime/type_object.hpp"

#include <gtest/gtest.h>

#include "layout_test_types.h"
#include "rover/idl/types.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::dds {
namespace {

XTypeTable Decode(const dds_topic_descriptor_t& d) {
  auto t = XTypeTable::Decode(d.type_mapping.data, d.type_mapping.sz);
  EXPECT_TRUE(t.ok()) << t.status().message();
  return t.ok() ? std::move(*t) : XTypeTable();
}

std::vector<std::string> Names(const XType& t) {
  std::vector<std::string> out;
  for (const auto& m : t.members) out.push_back(m.name);
  return out;
}

TEST(TypeObject, StructMembersHaveTheirIdlNamesInOrder) {
  const XTypeTable table = Decode(rover_dl_DriveCommand_desc);
  const XType* t = table.FindByName("rover::dl::DriveCommand");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->kind, XType::Kind::kStruct);
  EXPECT_EQ(Names(*t), (std::vector<std::string>{"header", "command_id", "primitive", "curvature",
                                                  "distance", "angle", "speed", "timeout_s"}));
  // Nested struct and enum members name COMPLETE TypeObjects of the same mapping.
  ASSERT_EQ(t->members[0].type.kind, XTypeId::Kind::kHash);
  const XType* header = table.Find(t->members[0].type.hash);
  ASSERT_NE(header, nullptr);
  EXPECT_EQ(header->name, "rover::Header");
  EXPECT_EQ(Names(*header), (std::vector<std::string>{"stamp_ns", "frame_id", "seq"}));
  EXPECT_EQ(header->members[1].type.kind, XTypeId::Kind::kString);
  EXPECT_EQ(header->members[1].type.bound, 31u);
  const XType* primitive = table.Find(t->members[2].type.hash);
  ASSERT_NE(primitive, nullptr);
  EXPECT_EQ(primitive->kind, XType::Kind::kEnum);
  ASSERT_FALSE(primitive->members.empty());
  EXPECT_EQ(primitive->members[0].name, "PRIMITIVE_STOP");
  EXPECT_EQ(primitive->members[0].value, 0);
  EXPECT_EQ(primitive->members.back().value, static_cast<int>(primitive->members.size()) - 1);
}

TEST(TypeObject, CollectionsCarryBoundsAndElements) {
  const XTypeTable table = Decode(rover_dl_PoseEstimate_desc);
  const XType* pose = table.FindByName("rover::dl::PoseEstimate");
  ASSERT_NE(pose, nullptr);
  const auto it = std::find_if(pose->members.begin(), pose->members.end(),
                               [](const XMember& m) { return m.name == "covariance"; });
  ASSERT_NE(it, pose->members.end());
  EXPECT_EQ(it->type.kind, XTypeId::Kind::kArray);
  EXPECT_EQ(it->type.dims, std::vector<std::uint32_t>{36});
  ASSERT_TRUE(it->type.element);
  EXPECT_EQ(it->type.element->kind, XTypeId::Kind::kPrimitive);

  const XTypeTable range = Decode(rover_dl_RangeImage_desc);
  const XType* ri = range.FindByName("rover::dl::RangeImage");
  ASSERT_NE(ri, nullptr);
  const auto xyz = std::find_if(ri->members.begin(), ri->members.end(),
                                [](const XMember& m) { return m.name == "xyz"; });
  ASSERT_NE(xyz, ri->members.end());
  EXPECT_EQ(xyz->type.kind, XTypeId::Kind::kSequence);
  EXPECT_EQ(xyz->type.bound, 0u);
}

TEST(TypeObject, AliasesResolveToTheirTypes) {
  const XTypeTable table = Decode(layout_test_Everything_desc);
  const XType* t = table.FindByName("layout_test::Everything");
  ASSERT_NE(t, nullptr);
  const auto triple = std::find_if(t->members.begin(), t->members.end(),
                                   [](const XMember& m) { return m.name == "triple"; });
  ASSERT_NE(triple, t->members.end());
  EXPECT_EQ(triple->type.kind, XTypeId::Kind::kHash);  // the typedef
  const XTypeId& real = table.Unalias(triple->type);
  EXPECT_EQ(real.kind, XTypeId::Kind::kArray);
  EXPECT_EQ(real.dims, std::vector<std::uint32_t>{3});
  const auto grid = std::find_if(t->members.begin(), t->members.end(),
                                 [](const XMember& m) { return m.name == "grid"; });
  ASSERT_NE(grid, t->members.end());
  EXPECT_EQ(grid->type.dims, (std::vector<std::uint32_t>{2, 3}));
}

TEST(TypeObject, EveryCatalogTypeDecodes) {
  for (const auto& topic : TopicCatalog()) {
    const dds_topic_descriptor_t* d = DescriptorForType(topic.type_name);
    ASSERT_NE(d, nullptr) << topic.type_name;
    auto t = XTypeTable::Decode(d->type_mapping.data, d->type_mapping.sz);
    ASSERT_TRUE(t.ok()) << topic.type_name << ": " << t.status().message();
    EXPECT_NE(t->FindByName(d->m_typename), nullptr) << d->m_typename;
  }
}

TEST(TypeObject, MalformedMappingsAreErrorsNamingTheOffset) {
  const auto& d = rover_dl_DriveCommand_desc;
  auto truncated = XTypeTable::Decode(d.type_mapping.data, d.type_mapping.sz / 2);
  ASSERT_FALSE(truncated.ok());
  EXPECT_NE(truncated.status().message().find("at byte"), std::string::npos)
      << truncated.status().message();
  EXPECT_FALSE(XTypeTable::Decode(nullptr, 0).ok());
  std::vector<std::uint8_t> garbage(d.type_mapping.data, d.type_mapping.data + d.type_mapping.sz);
  garbage[4] = 0xff;  // an absurd element count in the minimal sequence
  garbage[0] = 0xff;
  garbage[1] = 0xff;
  EXPECT_FALSE(XTypeTable::Decode(garbage.data(), garbage.size()).ok());
}

}  // namespace
}  // namespace rover::dds
