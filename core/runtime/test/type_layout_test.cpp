#include "rover/runtime/type_layout.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <vector>

#include "layout_test_types.h"
#include "rover/idl/types.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::dds {
namespace {

std::shared_ptr<const TypeLayout> LayoutOf(const dds_topic_descriptor_t& d) {
  auto l = TypeLayout::For(&d);
  EXPECT_TRUE(l.ok()) << l.status().message();
  return l.ok() ? *l : nullptr;
}

// The addresses a path selects in `sample`, as offsets from `base`.
template <class T>
std::vector<std::ptrdiff_t> Offsets(const TypeLayout& layout, const std::string& path, T& sample,
                                    const void* base = nullptr) {
  auto sel = FieldSelector::Resolve(layout, path);
  EXPECT_TRUE(sel.ok()) << path << ": " << sel.status().message();
  std::vector<std::ptrdiff_t> out;
  if (!sel.ok()) return out;
  const char* b = static_cast<const char*>(base ? base : &sample);
  sel->ForEachLeaf(&sample, [&](void* p, const FieldNode&) { out.push_back(static_cast<char*>(p) - b); });
  return out;
}

TEST(TypeLayout, OffsetsOfNestedStructsAndArraysMatchTheCompiler) {
  auto layout = LayoutOf(rover_dl_PoseEstimate_desc);
  ASSERT_TRUE(layout);
  EXPECT_EQ(layout->type_name(), "rover::dl::PoseEstimate");
  EXPECT_TRUE(layout->flat());
  rover_dl_PoseEstimate s{};
  using P = rover_dl_PoseEstimate;
  EXPECT_EQ(Offsets(*layout, "pose.position.x", s),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(P, pose.position.x))});
  EXPECT_EQ(Offsets(*layout, "pose.orientation.z", s),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(P, pose.orientation.z))});
  EXPECT_EQ(Offsets(*layout, "header.stamp_ns", s),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(P, header.stamp_ns))});
  EXPECT_EQ(Offsets(*layout, "covariance[3]", s),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(P, covariance) + 3 * sizeof(double))});
  EXPECT_EQ(Offsets(*layout, "covariance[*]", s).size(), 36u);
  EXPECT_EQ(Offsets(*layout, "covariance", s).size(), 36u);  // a collection without index: all
  // A struct selects every leaf below it.
  const auto pose = Offsets(*layout, "pose", s);
  ASSERT_EQ(pose.size(), 7u);
  EXPECT_EQ(pose.front(), static_cast<std::ptrdiff_t>(offsetof(P, pose.position.x)));
  EXPECT_EQ(pose.back(), static_cast<std::ptrdiff_t>(offsetof(P, pose.orientation.z)));
}

TEST(TypeLayout, LeafKindsSizesAndEnums) {
  auto layout = LayoutOf(rover_dl_DriveStatus_desc);
  ASSERT_TRUE(layout);
  auto kind_of = [&](const std::string& path) {
    auto sel = FieldSelector::Resolve(*layout, path);
    EXPECT_TRUE(sel.ok()) << sel.status().message();
    return sel.ok() ? *sel->leaf_nodes().front() : FieldNode{};
  };
  const FieldNode stamp = kind_of("header.stamp_ns");
  EXPECT_EQ(stamp.kind, FieldKind::kInt);
  EXPECT_EQ(stamp.size, 8u);
  const FieldNode seq = kind_of("header.seq");
  EXPECT_EQ(seq.kind, FieldKind::kUInt);
  EXPECT_EQ(seq.size, 4u);
  const FieldNode frame = kind_of("header.frame_id");
  EXPECT_EQ(frame.kind, FieldKind::kBoundedString);
  EXPECT_EQ(frame.capacity, 32u);
  const FieldNode state = kind_of("state");
  EXPECT_EQ(state.kind, FieldKind::kEnum);
  EXPECT_EQ(state.size, sizeof(rover_dl_DriveState));
  EXPECT_EQ(state.enum_max, static_cast<std::uint32_t>(rover_dl_DRIVE_REJECTED));
  EXPECT_EQ(state.type_name, "rover::dl::DriveState");
  EXPECT_EQ(kind_of("message").capacity, 128u);
}

TEST(TypeLayout, SequencesOfNumbersAndOfStructs) {
  auto range = LayoutOf(rover_dl_RangeImage_desc);
  ASSERT_TRUE(range);
  EXPECT_FALSE(range->flat());
  rover_dl_RangeImage img{};
  std::vector<float> xyz(6, 1.0f);
  BorrowSequence(img.xyz, xyz);
  EXPECT_EQ(Offsets(*range, "xyz[*]", img, xyz.data()),
            (std::vector<std::ptrdiff_t>{0, 4, 8, 12, 16, 20}));
  EXPECT_EQ(Offsets(*range, "xyz[2]", img, xyz.data()), std::vector<std::ptrdiff_t>{8});
  EXPECT_TRUE(Offsets(*range, "xyz[10]", img, xyz.data()).empty());  // beyond the length: none

  auto plan = LayoutOf(rover_apl_Plan_desc);
  ASSERT_TRUE(plan);
  rover_apl_Plan p{};
  std::vector<rover_Vector3> wp(3);
  BorrowSequence(p.waypoints, wp);
  EXPECT_EQ(Offsets(*plan, "waypoints[*].y", p, wp.data()),
            (std::vector<std::ptrdiff_t>{8, 32, 56}));
  EXPECT_EQ(Offsets(*plan, "waypoints[1]", p, wp.data()), (std::vector<std::ptrdiff_t>{24, 32, 40}));
}

TEST(TypeLayout, EveryMemberKindOfTheTestTypes) {
  auto layout = LayoutOf(layout_test_Everything_desc);
  ASSERT_TRUE(layout);
  using E = layout_test_Everything;
  E s{};
  auto one = [&](const std::string& path) {
    const auto o = Offsets(*layout, path, s);
    EXPECT_EQ(o.size(), 1u) << path;
    return o.empty() ? -1 : o[0];
  };
  EXPECT_EQ(one("name"), static_cast<std::ptrdiff_t>(offsetof(E, name)));
  EXPECT_EQ(one("tag"), static_cast<std::ptrdiff_t>(offsetof(E, tag)));
  EXPECT_EQ(one("u64"), static_cast<std::ptrdiff_t>(offsetof(E, u64)));
  EXPECT_EQ(one("color"), static_cast<std::ptrdiff_t>(offsetof(E, color)));
  EXPECT_EQ(one("inner.t[2]"), static_cast<std::ptrdiff_t>(offsetof(E, inner.t) + 2 * sizeof(double)));
  EXPECT_EQ(one("inners[1].s"), static_cast<std::ptrdiff_t>(offsetof(E, inners) + sizeof(layout_test_Inner)));
  EXPECT_EQ(one("triple[1]"), static_cast<std::ptrdiff_t>(offsetof(E, triple) + sizeof(double)));
  // Multi-dimensional arrays are indexed flat, row-major.
  EXPECT_EQ(one("grid[4]"), static_cast<std::ptrdiff_t>(offsetof(E, grid) + 4 * sizeof(double)));
  auto grid = FieldSelector::Resolve(*layout, "grid");
  ASSERT_TRUE(grid.ok());
  EXPECT_EQ(grid->leaf_nodes().size(), 1u);  // one leaf node kind, visited 6 times

  // Nested sequences: sequence<sequence<float>>.
  std::vector<float> a = {1, 2}, b = {3};
  std::vector<dds_sequence_float> inner(2);
  BorrowSequence(inner[0], a);
  BorrowSequence(inner[1], b);
  s.nested._buffer = reinterpret_cast<layout_test_Floats*>(inner.data());
  s.nested._length = s.nested._maximum = 2;
  int floats = 0;
  auto sel = FieldSelector::Resolve(*layout, "nested[*][*]");
  ASSERT_TRUE(sel.ok()) << sel.status().message();
  sel->ForEachLeaf(&s, [&](void* p, const FieldNode& leaf) {
    EXPECT_EQ(leaf.kind, FieldKind::kFloat);
    floats += static_cast<int>(*static_cast<float*>(p));
  });
  EXPECT_EQ(floats, 6);
  s.nested = {};

  auto bounded = FieldSelector::Resolve(*layout, "bounded[4]");
  ASSERT_FALSE(bounded.ok());
  EXPECT_NE(bounded.status().message().find("beyond its bound 4"), std::string::npos);
}

TEST(TypeLayout, InheritedMembersComeFirst) {
  auto layout = LayoutOf(layout_test_Derived_desc);
  ASSERT_TRUE(layout);
  layout_test_Derived d{};
  EXPECT_EQ(Offsets(*layout, "base_id", d),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(layout_test_Derived, parent.base_id))});
  EXPECT_EQ(Offsets(*layout, "value", d),
            std::vector<std::ptrdiff_t>{static_cast<std::ptrdiff_t>(offsetof(layout_test_Derived, value))});
}

TEST(TypeLayout, UnionsAreRecordedButNotAddressableOrCopyable) {
  auto layout = LayoutOf(layout_test_WithUnion_desc);
  ASSERT_TRUE(layout);
  EXPECT_FALSE(layout->copyable());
  auto sel = FieldSelector::Resolve(*layout, "choice");
  ASSERT_FALSE(sel.ok());
  EXPECT_NE(sel.status().message().find("is a union; field paths cannot enter it"), std::string::npos) << sel.status().message();
  EXPECT_TRUE(FieldSelector::Resolve(*layout, "a").ok());
}

TEST(TypeLayout, ErrorsNameTheTypeAndTheNearestFields) {
  auto layout = LayoutOf(rover_dl_PoseEstimate_desc);
  ASSERT_TRUE(layout);
  auto typo = FieldSelector::Resolve(*layout, "pose.positon.x");
  ASSERT_FALSE(typo.ok());
  EXPECT_EQ(typo.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(typo.status().message().rfind(
                "rover::dl::PoseEstimate has no field 'pose.positon.x' (nearest: pose.position.x", 0),
            0u)
      << typo.status().message();
  auto index = FieldSelector::Resolve(*layout, "covariance[36]");
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), StatusCode::kOutOfRange);
  EXPECT_NE(index.status().message().find("it has 36 elements"), std::string::npos);
  auto not_array = FieldSelector::Resolve(*layout, "odometer[0]");
  ASSERT_FALSE(not_array.ok());
  EXPECT_NE(not_array.status().message().find("'odometer' is a floating-point, not an array"),
            std::string::npos)
      << not_array.status().message();
  auto not_struct = FieldSelector::Resolve(*layout, "covariance.x");
  ASSERT_FALSE(not_struct.ok());
  EXPECT_NE(not_struct.status().message().find("'covariance' is an array"), std::string::npos)
      << not_struct.status().message();
  for (const char* bad : {"", "pose..x", "pose.", "[0]", "covariance[", "covariance[x]", "9pose"}) {
    auto r = FieldSelector::Resolve(*layout, bad);
    EXPECT_FALSE(r.ok()) << bad;
  }
  auto plan = LayoutOf(rover_apl_Plan_desc);
  auto wp = FieldSelector::Resolve(*plan, "waypoints[*].w");
  ASSERT_FALSE(wp.ok());
  EXPECT_NE(wp.status().message().find("nearest: waypoints[*].x"), std::string::npos)
      << wp.status().message();
}

TEST(TypeLayout, CloneIsADeepCopy) {
  auto layout = LayoutOf(layout_test_Everything_desc);
  ASSERT_TRUE(layout);
  ASSERT_TRUE(layout->copyable());
  layout_test_Everything s{};
  char name[] = "rover";
  s.name = name;
  std::vector<int32_t> longs = {1, 2, 3};
  BorrowSequence(s.longs, longs);
  std::vector<layout_test_Inner> inner(2);
  inner[1].t[0] = 4.5;
  BorrowSequence(s.inner_seq, inner);
  char n0[] = "a", n1[] = "bc";
  std::vector<char*> names = {n0, n1};
  BorrowSequence(s.names, names);
  s.i64 = -7;
  auto* c = static_cast<layout_test_Everything*>(layout->Clone(&s));
  ASSERT_NE(c, nullptr);
  // The copy has its own buffers.
  EXPECT_NE(c->name, s.name);
  EXPECT_STREQ(c->name, "rover");
  EXPECT_NE(c->longs._buffer, s.longs._buffer);
  EXPECT_TRUE(c->longs._release);
  longs[1] = 99;
  inner[1].t[0] = 0;
  n1[0] = 'x';
  EXPECT_EQ(c->longs._buffer[1], 2);
  EXPECT_EQ(c->inner_seq._buffer[1].t[0], 4.5);
  EXPECT_STREQ(c->names._buffer[1], "bc");
  EXPECT_EQ(c->i64, -7);
  layout->Free(c);

  // CopyInto owns its buffers the way DDS does: dds_sample_free releases them.
  auto* d = static_cast<layout_test_Everything*>(dds_alloc(sizeof(layout_test_Everything)));
  internal::CopySample(d, &s, &layout_test_Everything_desc);
  EXPECT_STREQ(d->names._buffer[0], "a");
  dds_sample_free(d, &layout_test_Everything_desc, DDS_FREE_ALL);
}

TEST(TypeLayout, EveryCatalogTypeHasALayoutAndPaths) {
  for (const auto& topic : TopicCatalog()) {
    const dds_topic_descriptor_t* d = DescriptorForType(topic.type_name);
    ASSERT_NE(d, nullptr) << topic.type_name;
    auto layout = TypeLayout::For(d);
    ASSERT_TRUE(layout.ok()) << topic.type_name << ": " << layout.status().message();
    EXPECT_TRUE((*layout)->copyable()) << topic.type_name;
    EXPECT_EQ((*layout)->root().size, d->m_size);
    // Every member path resolves, and every inline leaf lies inside the sample.
    for (const auto& path : (*layout)->MemberPaths()) {
      auto sel = FieldSelector::Resolve(**layout, path);
      EXPECT_TRUE(sel.ok()) << topic.type_name << " " << path << ": " << sel.status().message();
    }
    std::vector<char> zero(d->m_size, 0);
    auto all = FieldSelector::Resolve(**layout, (*layout)->root().members.front().name);
    ASSERT_TRUE(all.ok());
    for (const auto& m : (*layout)->root().members) {
      auto sel = FieldSelector::Resolve(**layout, m.name);
      if (!sel.ok()) continue;
      sel->ForEachLeaf(zero.data(), [&](void* p, const FieldNode& leaf) {
        const auto off = static_cast<std::size_t>(static_cast<char*>(p) - zero.data());
        EXPECT_LE(off + leaf.size, d->m_size) << topic.type_name << " " << m.name;
      });
    }
  }
}

}  // namespace
}  // namespace rover::dds
