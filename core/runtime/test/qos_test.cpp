#include "rover/runtime/qos.hpp"

#include <gtest/gtest.h>

namespace rover::dds {
namespace {

TEST(Qos, ProfilesMeanWhatTheDesignSays) {
  EXPECT_TRUE(DescribeQos(QosProfile::kState).reliable);
  EXPECT_EQ(DescribeQos(QosProfile::kState).history_depth, 1);
  EXPECT_FALSE(DescribeQos(QosProfile::kState).transient_local);
  EXPECT_FALSE(DescribeQos(QosProfile::kStream).reliable);
  EXPECT_GT(DescribeQos(QosProfile::kStream).history_depth, 1);
  EXPECT_EQ(DescribeQos(QosProfile::kCommand).history_depth, 0);  // keep-all
  EXPECT_TRUE(DescribeQos(QosProfile::kCommand).reliable);
  // None lost to discovery, none executed by a late joiner (CommandDelivery in dds_test.cpp).
  EXPECT_TRUE(DescribeQos(QosProfile::kCommand).transient_local);
  EXPECT_TRUE(DescribeQos(QosProfile::kCommand).fresh_only);
  EXPECT_FALSE(DescribeQos(QosProfile::kLatched).fresh_only);
  EXPECT_TRUE(DescribeQos(QosProfile::kLatched).transient_local);
}

TEST(Qos, MakeQosSetsThePolicies) {
  for (QosProfile p : {QosProfile::kState, QosProfile::kStream, QosProfile::kCommand,
                       QosProfile::kLatched}) {
    QosPtr q = MakeQos(p);
    const QosSpec spec = DescribeQos(p);
    dds_reliability_kind_t rel{};
    dds_duration_t block = 0;
    ASSERT_TRUE(dds_qget_reliability(q.get(), &rel, &block));
    EXPECT_EQ(rel == DDS_RELIABILITY_RELIABLE, spec.reliable) << QosProfileName(p);
    dds_history_kind_t hist{};
    int32_t depth = 0;
    ASSERT_TRUE(dds_qget_history(q.get(), &hist, &depth));
    if (spec.history_depth == 0) {
      EXPECT_EQ(hist, DDS_HISTORY_KEEP_ALL);
    } else {
      EXPECT_EQ(hist, DDS_HISTORY_KEEP_LAST);
      EXPECT_EQ(depth, spec.history_depth);
    }
    dds_durability_kind_t dur{};
    ASSERT_TRUE(dds_qget_durability(q.get(), &dur));
    EXPECT_EQ(dur == DDS_DURABILITY_TRANSIENT_LOCAL, spec.transient_local);
    if (p == QosProfile::kCommand) {
      dds_duration_t cleanup = 0;
      dds_history_kind_t kind{};
      int32_t tl_depth = 0, a = 0, b = 0, c = 0;
      ASSERT_TRUE(dds_qget_durability_service(q.get(), &cleanup, &kind, &tl_depth, &a, &b, &c));
      EXPECT_EQ(kind, DDS_HISTORY_KEEP_LAST);
      EXPECT_EQ(tl_depth, kCommandHistoryDepth);
    }
  }
}

TEST(Qos, ParseNamesRoundTripAndUnknownIsAnError) {
  for (const char* n : {"state", "stream", "command", "latched"}) {
    auto p = ParseQosProfile(n);
    ASSERT_TRUE(p.ok());
    EXPECT_STREQ(QosProfileName(*p), n);
  }
  auto bad = ParseQosProfile("volatile-ish");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "unknown QoS profile 'volatile-ish' (known: state, stream, command, latched)");
}

}  // namespace
}  // namespace rover::dds
