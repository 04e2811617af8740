// apl-sequencer in-process over DDS (tests/support's ServiceHarness on the simulated run clock).
// The test plays the mobility manager (answers apl/mobility_command on apl/mobility_status one
// tick later), the mast (dl/mast_command -> dl/mast_status AT_GOAL) and the pose estimator
// (dl/pose every tick).
#include "sequencer_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "service_links.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/sequence_idl.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::apl::sequencer {
namespace {


struct Sent {
  std::string topic;  // "mobility" or "mast"
  msg::MobilityCommand mobility;
  msg::MastCommand mast;
};

class SequencerServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    harness_ = std::make_unique<rover::testing::ServiceHarness>(service_, "apl-sequencer-test");
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    sequences_ = harness_->Writer<rover_apl_SequenceCommand>("apl/sequence_command");
    mobility_status_ = harness_->Writer<rover_apl_MobilityStatus>("apl/mobility_status");
    mast_status_ = harness_->Writer<rover_dl_MastStatus>("dl/mast_status");
    pose_ = harness_->Writer<rover_dl_PoseEstimate>("dl/pose");
    mobility_ = harness_->Reader<rover_apl_MobilityCommand>("apl/mobility_command");
    mast_ = harness_->Reader<rover_dl_MastCommand>("dl/mast_command");
    status_ = harness_->Reader<rover_apl_SequenceStatus>("apl/sequence_status");
  }

  void Submit(std::uint32_t id, const std::string& text) {
    msg::SequenceCommand c;
    c.stamp = Time::FromSeconds(t_);
    c.command_id = id;
    c.text = text;
    rover_apl_SequenceCommand m{};
    ASSERT_TRUE(msg::SequenceCommandToIdl(c, &m).ok());
    ASSERT_TRUE(sequences_.Write(m).ok());
  }

  // One 0.1 s step: answer what came in the last step, publish the pose, move time on, and
  // collect what the service sent.
  bool Tick() {
    for (const msg::MobilityCommand& c : hold_answers_ ? std::vector<msg::MobilityCommand>{}
                                                       : to_answer_mobility_) {
      msg::MobilityStatus s;
      s.stamp = Time::FromSeconds(t_);
      s.command_id = c.command_id;
      s.mode = c.mode;
      s.state = msg::MobilityState::kSucceeded;
      if (mobility_answer) mobility_answer(c, &s);
      if (s.state == msg::MobilityState::kSucceeded && !c.primitives.empty()) {
        x_ += c.primitives[0].distance;
      }
      rover_apl_MobilityStatus sm{};
      msg::MobilityStatusToIdl(s, &sm);
      if (!mobility_status_.Write(sm).ok()) return false;
    }
    if (!hold_answers_) to_answer_mobility_.clear();
    for (const msg::MastCommand& c : to_answer_mast_) {
      msg::MastStatus s;
      s.stamp = Time::FromSeconds(t_);
      s.command_id = c.command_id;
      s.state = msg::MastState::kAtGoal;
      rover_dl_MastStatus m{};
      msg::MastStatusToIdl(s, &m);
      if (!mast_status_.Write(m).ok()) return false;
    }
    to_answer_mast_.clear();
    msg::PoseEstimate p;
    p.stamp = Time::FromSeconds(t_);
    p.position = {x_, 0.0, 0.0};
    rover_dl_PoseEstimate pm{};
    msg::PoseEstimateToIdl(p, &pm);
    if (!pose_.Write(pm).ok()) return false;

    t_ += 0.1;
    if (!harness_->AdvanceTo(Time::FromSeconds(t_))) return false;
    harness_->Spin();
    for (auto& s : mobility_.Take()) {
      const msg::MobilityCommand c = msg::MobilityCommandFromIdl(s.data());
      // Event-driven: a new command only once every earlier one was answered (a STOP that
      // cancels one is the exception).
      if (c.mode != msg::MobilityMode::kStop || (c.command_id & 0x80000000u) == 0) {
        EXPECT_EQ(unanswered(), 0) << "mobility command " << c.command_id;
      }
      sent_.push_back({"mobility", c, {}});
      to_answer_mobility_.push_back(c);
    }
    for (auto& s : mast_.Take()) {
      const msg::MastCommand c = msg::MastCommandFromIdl(s.data());
      EXPECT_EQ(unanswered(), 0) << "mast command " << c.command_id;
      sent_.push_back({"mast", {}, c});
      to_answer_mast_.push_back(c);
    }
    for (auto& s : status_.Take()) {
      Result<msg::SequenceStatus> st = msg::SequenceStatusFromIdl(s.data());
      EXPECT_TRUE(st.ok());
      if (st.ok()) statuses_.push_back(*st);
    }
    return true;
  }
  bool hold_answers_ = false;  // keep mobility answers back
  int unanswered() const {
    return static_cast<int>(to_answer_mobility_.size() + to_answer_mast_.size());
  }

  /// Ticks until sequence `id` is DONE or FAILED (or `max_s` of run-clock time passed).
  std::optional<msg::SequenceStatus> WaitEnd(std::uint32_t id, double max_s = 30.0) {
    const double end = t_ + max_s;
    while (t_ < end) {
      if (!Tick()) return std::nullopt;
      for (const auto& s : statuses_) {
        if (s.command_id == id && (s.state == msg::SequenceState::kDone ||
                                   s.state == msg::SequenceState::kFailed)) {
          return s;
        }
      }
    }
    return std::nullopt;
  }

  SequencerService service_;
  std::unique_ptr<rover::testing::ServiceHarness> harness_;
  dds::Writer<rover_apl_SequenceCommand> sequences_;
  dds::Writer<rover_apl_MobilityStatus> mobility_status_;
  dds::Writer<rover_dl_MastStatus> mast_status_;
  dds::Writer<rover_dl_PoseEstimate> pose_;
  dds::Reader<rover_apl_MobilityCommand> mobility_;
  dds::Reader<rover_dl_MastCommand> mast_;
  dds::Reader<rover_apl_SequenceStatus> status_;
  std::function<void(const msg::MobilityCommand&, msg::MobilityStatus*)> mobility_answer;
  std::vector<msg::MobilityCommand> to_answer_mobility_;
  std::vector<msg::MastCommand> to_answer_mast_;
  std::vector<Sent> sent_;
  std::vector<msg::SequenceStatus> statuses_;
  double t_ = 0.0;
  double x_ = 0.0;  // [m] the fake rover's position along site x
};

TEST_F(SequencerServiceTest, RunsASequenceCommandByCommandOverTopics) {
  Submit(1,
         "TARGET rock = (2, 0, 0)\n"
         "MAST pan_deg=10 tilt_deg=-20\n"
         "WHILE distance_to(rock) > 1.1 m MAX 5\n"
         "  VISODOM STRAIGHT distance=0.4\n"
         "END\n"
         "IF last.termination == NOMINAL\n  TURN angle_deg=90\nEND\n");
  const auto end = WaitEnd(1);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, msg::SequenceState::kDone) << end->message;
  EXPECT_EQ(end->step, 3u);
  // 2 m to go, 0.4 m steps: three reach 0.8 m (<= 1.1).
  ASSERT_EQ(sent_.size(), 5u);
  EXPECT_EQ(sent_[0].topic, "mast");
  EXPECT_EQ(sent_[0].mast.pointing, msg::MastPointing::kAngles);
  EXPECT_NEAR(sent_[0].mast.pan, 10 * std::numbers::pi / 180, 1e-12);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_EQ(sent_[k].topic, "mobility");
    EXPECT_EQ(sent_[k].mobility.mode, msg::MobilityMode::kVisOdom);
    ASSERT_EQ(sent_[k].mobility.primitives.size(), 1u);
    EXPECT_DOUBLE_EQ(sent_[k].mobility.primitives[0].distance, 0.4);
  }
  EXPECT_EQ(sent_[4].mobility.primitives.at(0).kind, msg::DrivePrimitive::kTurnInPlace);
  // Every command id differs, so each status ends only its own command.
  for (std::size_t k = 1; k < sent_.size(); ++k) {
    const std::uint32_t a = sent_[k - 1].topic == "mast" ? sent_[k - 1].mast.command_id
                                                         : sent_[k - 1].mobility.command_id;
    const std::uint32_t b = sent_[k].topic == "mast" ? sent_[k].mast.command_id
                                                     : sent_[k].mobility.command_id;
    EXPECT_LT(a, b);
  }
  EXPECT_EQ(statuses_.front().state, msg::SequenceState::kRunning);
}

TEST_F(SequencerServiceTest, BadSequencesAreRefusedAndNothingMoves) {
  struct Case {
    std::string text;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"STOP\nTURN angle_deg=90)\n",
       "apl/sequence_command 1:2:18: expected an argument name=value of TURN"},
      {"DRIV ARC curvature=1 distance=1\n",
       "apl/sequence_command 2:1:1: unknown command 'DRIV ARC' (did you mean 'DRIVE ARC'?)"},
      {"TURN angel_deg=90\n",
       "apl/sequence_command 3:1:6: TURN has no argument 'angel_deg' (did you mean "
       "'angle_deg'?)"},
      {"WHILE tilt < 5\n  STOP\nEND\n",
       "apl/sequence_command 4:1:1: unbounded loop: WHILE needs MAX n"},
      {"STOP\nARM UNSTOW\n",
       "apl/sequence_command 5: line 2: ARM UNSTOW: apl-sequencer does not dispatch it (dl-arm "
       "has no unstowed pose"},  // the wire's 127 characters end within the reason
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE(cases[k].text);
    const auto id = static_cast<std::uint32_t>(k + 1);
    Submit(id, cases[k].text);
    const auto end = WaitEnd(id, 2.0);
    ASSERT_TRUE(end.has_value());
    EXPECT_EQ(end->state, msg::SequenceState::kFailed);
    EXPECT_EQ(end->step, 0u);
    EXPECT_EQ(end->message.substr(0, cases[k].message.size()), cases[k].message);
  }
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(Tick());
  EXPECT_TRUE(sent_.empty());
}

TEST_F(SequencerServiceTest, AFailedDriveRunsTheAbortBlockAndASecondSequenceWaits) {
  mobility_answer = [](const msg::MobilityCommand& c, msg::MobilityStatus* s) {
    if (c.mode == msg::MobilityMode::kAutoNav) {
      s->state = msg::MobilityState::kFailed;
      s->fault = msg::MobilityFault::kNoPath;
      s->fault_class = msg::FaultClass::kGoalError;
      s->message = "every arc forbidden";
    }
  };
  Submit(7, "ON_ABORT\n  STOP\nEND\nDRIVE STRAIGHT distance=1\nAUTONAV goal=(9, 0)\nTURN "
            "angle_deg=5\n");
  for (int k = 0; k < 50 && sent_.size() < 2; ++k) ASSERT_TRUE(Tick());
  ASSERT_EQ(sent_.size(), 2u);  // the DRIVE answered, the AUTONAV out
  // While 7 runs (its AUTONAV held), 8 is refused and its FAILED stays latched until 7's status
  // changes; then 7 goes on.
  hold_answers_ = true;
  Submit(8, "STOP\n");
  const auto refused = WaitEnd(8, 2.0);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->state, msg::SequenceState::kFailed);
  EXPECT_EQ(refused->message, "sequence 7 is running (step 3)");
  hold_answers_ = false;
  const auto end = WaitEnd(7);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, msg::SequenceState::kFailed);
  EXPECT_EQ(end->message,
            "step 3 (line 5: AUTONAV goal=(9, 0)) failed: NOPATH (goal error): every arc "
            "forbidden");
  ASSERT_EQ(sent_.size(), 3u);
  EXPECT_EQ(sent_[0].mobility.mode, msg::MobilityMode::kDirected);
  EXPECT_EQ(sent_[1].mobility.mode, msg::MobilityMode::kAutoNav);
  EXPECT_EQ(sent_[1].mobility.goal, Eigen::Vector3d(9, 0, 0));
  EXPECT_EQ(sent_[2].mobility.mode, msg::MobilityMode::kStop);  // the ON_ABORT block
}

TEST_F(SequencerServiceTest, DeactivationStopsTheRunningSequenceAndItsDrive) {
  Submit(3, "ON_ABORT\n  MAST pan_deg=0 tilt_deg=0\nEND\nAUTONAV goal=(20, 0)\n");
  hold_answers_ = true;  // the AUTONAV runs on
  for (int k = 0; k < 50 && sent_.empty(); ++k) ASSERT_TRUE(Tick());
  ASSERT_EQ(sent_.size(), 1u);
  const std::uint32_t autonav = sent_[0].mobility.command_id;
  ASSERT_TRUE(harness_->lifecycle().Deactivate().ok());
  // The service no longer serves its timer; what it wrote on deactivation is read directly.
  std::vector<msg::MobilityCommand> stops;
  std::optional<msg::SequenceStatus> end;
  ASSERT_TRUE(harness_->SpinUntil([&] {
    for (auto& m : mobility_.Take()) stops.push_back(msg::MobilityCommandFromIdl(m.data()));
    for (auto& m : status_.Take()) {
      Result<msg::SequenceStatus> st = msg::SequenceStatusFromIdl(m.data());
      if (st.ok() && st->command_id == 3 && st->state == msg::SequenceState::kFailed) end = *st;
    }
    return !stops.empty() && end.has_value();
  }));
  ASSERT_EQ(stops.size(), 1u);  // the STOP, not the ON_ABORT block's MAST
  EXPECT_EQ(stops[0].mode, msg::MobilityMode::kStop);
  EXPECT_EQ(stops[0].command_id, autonav | kCancelIdBit);
  EXPECT_TRUE(mast_.Take().empty());
  EXPECT_NE(end->message.find("apl-sequencer deactivated"), std::string::npos) << end->message;
  EXPECT_FALSE(service_.interpreter()->busy());
}

}  // namespace
}  // namespace rover::apl::sequencer
