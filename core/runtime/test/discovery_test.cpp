#include "rover/runtime/discovery.hpp"

#include <gtest/gtest.h>

#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

TEST(Discovery, SeesAnotherParticipantsWritersButNotItsOwn) {
  DomainLease lease = testing::IsolatedDomain();
  auto probe = Participant::Create(lease.domain());
  auto other = Participant::Create(lease.domain());
  ASSERT_TRUE(probe.ok() && other.ok());
  auto own = Writer<rover_dl_PoseEstimate>::Create(*probe, "dl/pose");
  auto theirs = Writer<rover_ddl_Imu>::Create(*other, "ddl/imu");
  ASSERT_TRUE(own.ok() && theirs.ok());
  auto found = DiscoverRemoteWriters(*probe, std::chrono::milliseconds(1500));
  ASSERT_TRUE(found.ok()) << found.status().message();
  bool imu = false;
  for (const auto& w : *found) {
    EXPECT_NE(w.topic, "dl/pose") << "the probe's own writer";
    if (w.topic == "ddl/imu") {
      imu = true;
      EXPECT_EQ(w.type, "rover::ddl::Imu");
      EXPECT_FALSE(w.participant.empty());
    }
  }
  EXPECT_TRUE(imu);
}

TEST(Discovery, AnEmptyDomainHasNoWriters) {
  DomainLease lease = testing::IsolatedDomain();
  auto probe = Participant::Create(lease.domain());
  ASSERT_TRUE(probe.ok());
  auto found = DiscoverRemoteWriters(*probe, std::chrono::milliseconds(300));
  ASSERT_TRUE(found.ok());
  EXPECT_TRUE(found->empty());
}

}  // namespace
}  // namespace rover::dds
