#include "rover/dl/camera_client/camera_request_client.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rover::dl::camera_client {
namespace {

Time T(double s) { return Time::FromSeconds(s); }

CameraClientOptions Options(int prefix = 2, double retry_delay_s = 0.0) {
  CameraClientOptions o;
  o.request_id_prefix = prefix;
  o.request_timeout_s = 2.0;
  o.exposure_us = 500;
  o.retry_delay_s = retry_delay_s;
  return o;
}

// A well-formed answer to `o`, captured at `capture`.
msg::StereoFrame Answer(const Outstanding& o, Time capture) {
  msg::StereoFrame f;
  f.stamp = capture;
  f.request_id = o.request_id;
  f.camera = o.camera;
  f.width = o.width != 0 ? o.width : 512;
  f.height = f.width * 3 / 4;
  return f;
}

TEST(CameraRequestClient, OwnIdsWithThePrefixAndAWrappingCounter) {
  CameraRequestClient c(Options(2));
  EXPECT_TRUE(c.Ready(T(1)));
  const msg::StereoRequest r = c.Issue(T(1), msg::CameraId::kFrontHazcam, 256, 17);
  EXPECT_EQ(r.request_id, (2u << 24) | 1u);
  EXPECT_EQ(r.stamp, T(1));
  EXPECT_EQ(r.camera, msg::CameraId::kFrontHazcam);
  EXPECT_EQ(r.width, 256);
  EXPECT_EQ(r.exposure_us, 500u);
  EXPECT_FALSE(c.Ready(T(1)));
  // Another requester's frame (same counter, other prefix) is not ours; ours closes the request.
  EXPECT_FALSE(c.Answer((1u << 24) | 1u).has_value());
  const auto o = c.Answer(r.request_id);
  ASSERT_TRUE(o.has_value());
  EXPECT_EQ(o->tag, 17u);
  EXPECT_EQ(o->sent, T(1));
  EXPECT_FALSE(c.Answer(r.request_id).has_value());  // a duplicate
  EXPECT_TRUE(c.Ready(T(1)));
  // The counter wraps past 2^24 - 1 to 1, never 0.
  CameraRequestClient w(Options(1));
  std::uint32_t last = 0;
  for (std::uint32_t i = 0; i < 0xFFFFFFu; ++i) {
    last = w.Issue(T(1), msg::CameraId::kNavcam, 0).request_id;
    (void)w.Answer(last);
  }
  EXPECT_EQ(last, (1u << 24) | 0xFFFFFFu);
  EXPECT_EQ(w.Issue(T(1), msg::CameraId::kNavcam, 0).request_id, (1u << 24) | 1u);
}

TEST(CameraRequestClient, ChecksTheAnswerAgainstItsRequest) {
  CameraRequestClient c(Options());
  const msg::StereoRequest r = c.Issue(T(10), msg::CameraId::kFrontHazcam, 256);
  const Outstanding o = *c.Answer(r.request_id);
  EXPECT_TRUE(c.Check(o, Answer(o, T(10.05))).ok());

  struct Case {
    const char* name;
    void (*edit)(msg::StereoFrame&);
    const char* expect;
  };
  const std::vector<Case> cases = {
      {"camera", [](msg::StereoFrame& f) { f.camera = msg::CameraId::kNavcam; },
       "frame is from camera navcam, requested front_hazcam"},
      {"failed", [](msg::StereoFrame& f) { f.health = msg::SensorHealth::kFailed; },
       "frame health is FAILED"},
      {"stale", [](msg::StereoFrame& f) { f.health = msg::SensorHealth::kStale; },
       "frame health is STALE"},
      {"width", [](msg::StereoFrame& f) { f.width = 128; }, "frame is 128 px wide, requested 256"},
      {"early", [](msg::StereoFrame& f) { f.stamp = T(9.8); },
       "capture stamp 9.8 s is before the request was sent (10 s)"},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    msg::StereoFrame f = Answer(o, T(10.05));
    k.edit(f);
    const Status s = c.Check(o, f);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.message().find(k.expect), std::string::npos) << s.message();
  }
  // A degraded frame is usable; 0.1 s of skew is tolerated.
  msg::StereoFrame degraded = Answer(o, T(9.95));
  degraded.health = msg::SensorHealth::kDegraded;
  EXPECT_TRUE(c.Check(o, degraded).ok());
  // Frames must come in time order after the last one used.
  c.Accepted(T(10.05));
  const Status again = c.Check(o, Answer(o, T(10.05)));
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.message().find("not after the previous frame's (10.05 s)"), std::string::npos)
      << again.message();
  // A request without a width takes any.
  const Outstanding any = *c.Answer(c.Issue(T(11), msg::CameraId::kFrontHazcam, 0).request_id);
  EXPECT_TRUE(c.Check(any, Answer(any, T(11.1))).ok());
}

TEST(CameraRequestClient, UnansweredRequestsExpireAfterTheTimeout) {
  CameraRequestClient c(Options());
  const msg::StereoRequest r = c.Issue(T(5), msg::CameraId::kNavcam, 0, 3);
  EXPECT_FALSE(c.Expire(T(7.0)).has_value());  // exactly the timeout: still waiting
  const auto expired = c.Expire(T(7.01));
  ASSERT_TRUE(expired.has_value());
  EXPECT_EQ(expired->tag, 3u);
  EXPECT_FALSE(c.Answer(r.request_id).has_value());  // the late answer is not ours any more
  EXPECT_TRUE(c.Ready(T(7.01)));
}

TEST(CameraRequestClient, FailuresHoldNewRequestsForTheRetryDelay) {
  CameraRequestClient c(Options(2, 1.0));
  (void)c.Issue(T(1), msg::CameraId::kFrontHazcam, 512);
  c.SendFailed(T(1));
  EXPECT_FALSE(c.outstanding());
  EXPECT_FALSE(c.Ready(T(1.5)));
  EXPECT_TRUE(c.Ready(T(2.0)));
  const auto o = c.Answer(c.Issue(T(2), msg::CameraId::kFrontHazcam, 512).request_id);
  ASSERT_TRUE(o.has_value());
  c.Failed(T(2.2));  // a bad answer
  EXPECT_FALSE(c.Ready(T(3.1)));
  EXPECT_TRUE(c.Ready(T(3.2)));
  // Without a retry delay nothing is held.
  CameraRequestClient n(Options(1, 0.0));
  (void)n.Issue(T(1), msg::CameraId::kFrontHazcam, 0);
  n.SendFailed(T(1));
  EXPECT_TRUE(n.Ready(T(1)));
}

TEST(CameraRequestClient, DetectsARunClockResetAndForgetsEverything) {
  CameraRequestClient c(Options(2, 5.0));
  EXPECT_FALSE(c.ClockWentBack(T(100)));
  EXPECT_FALSE(c.ClockWentBack(T(99.5)));  // jitter, not a reset
  const msg::StereoRequest r = c.Issue(T(100), msg::CameraId::kRearHazcam, 256, 9);
  c.Accepted(T(99));
  c.Failed(T(100));
  EXPECT_TRUE(c.ClockWentBack(T(2)));
  const auto pending = c.Reset();
  ASSERT_TRUE(pending.has_value());
  EXPECT_EQ(pending->request_id, r.request_id);
  EXPECT_EQ(pending->tag, 9u);
  EXPECT_TRUE(c.Ready(T(2)));  // no hold, nothing outstanding
  const auto o = *c.Answer(c.Issue(T(2), msg::CameraId::kRearHazcam, 256).request_id);
  EXPECT_TRUE(c.Check(o, Answer(o, T(2.05))).ok());  // the old capture stamp is forgotten
  EXPECT_FALSE(c.ClockWentBack(T(2.1)));
}

TEST(CameraClientOptions, ValidateAndParameters) {
  EXPECT_TRUE(CameraClientOptions().Validate().ok());
  CameraClientOptions o;
  o.request_id_prefix = 0;
  EXPECT_NE(o.Validate().message().find("request_id_prefix"), std::string::npos);
  o = CameraClientOptions();
  o.request_timeout_s = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  ParamSet ps("dl-vo");
  CameraClientOptions defaults;
  defaults.request_id_prefix = 2;
  DeclareParams<CameraClientOptions>(ps, "", defaults);
  ASSERT_TRUE(ps.LoadYamlString("request_timeout_s: 4\nexposure_us: 800\n", "vo.yaml").ok());
  auto read = ReadParams<CameraClientOptions>(ps, "");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->request_id_prefix, 2);
  EXPECT_EQ(read->request_timeout_s, 4.0);
  EXPECT_EQ(read->exposure_us, 800u);
  ParamSet bad("dl-vo");
  DeclareParams<CameraClientOptions>(bad, "");
  ASSERT_TRUE(bad.LoadYamlString("request_id_prefix: 300\n", "vo.yaml").ok());
  EXPECT_FALSE(ReadParams<CameraClientOptions>(bad, "").ok());
}

}  // namespace
}  // namespace rover::dl::camera_client
