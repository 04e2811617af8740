#include "rover/apl/rendezvous/rendezvous_options.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rover::apl::rendezvous {
namespace {

using ::testing::HasSubstr;

TEST(RendezvousOptionsTest, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_TRUE(RendezvousOptions{}.Validate().ok());
  RendezvousOptions o;
  o.default_standoff = 5.0;
  EXPECT_THAT(o.Validate().message(), HasSubstr("rendezvous.default_standoff = 5 m is outside"));
  o = {};
  o.accept_lateral = 0.001;
  EXPECT_THAT(o.Validate().message(), HasSubstr("rendezvous.accept_lateral"));
  o = {};
  o.min_stripes = 1;
  EXPECT_THAT(o.Validate().message(), HasSubstr("rendezvous.min_stripes"));
  o = {};
  o.leg_mode = "fly";
  EXPECT_THAT(o.Validate().message(), HasSubstr("rendezvous.leg_mode: 'fly'"));
}

}  // namespace
}  // namespace rover::apl::rendezvous
