#include "rover/base/param_binder.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover {
namespace {

enum class Mode { kArc, kTurn };

struct PriorOptions {
  double sigma = 0.01;  // [m]
  static void BindParams(ParamBinder<PriorOptions>& b) {
    b.Bind("sigma", &PriorOptions::sigma, "m", "prior 1-sigma").Range(0.0, 1.0);
  }
};

struct TestOptions {
  double rate_hz = 8.0;
  double max_tilt = 30.0 * kDegree;  // [rad]
  double lead = 0.5;              // [m], key in mm
  int cycles = 3;
  std::uint32_t id_prefix = 2;
  bool enabled = true;
  std::string name = "front";
  std::vector<double> gains{1.0, 2.0};
  std::array<double, 3> offset{0.0, 0.1, 0.2};
  Mode mode = Mode::kArc;
  PriorOptions prior;
  double unbound = 42.0;

  Status Validate() const {
    ROVER_RETURN_IF_ERROR(CheckRange("max_tilt", max_tilt, 0.0, 40.0 * kDegree, "rad"));
    if (cycles > 5 && !enabled) return InvalidArgument("cycles must be <= 5 when disabled");
    return Status::Ok();
  }

  static void BindParams(ParamBinder<TestOptions>& b) {
    b.Bind("rate_hz", &TestOptions::rate_hz, "Hz", "check rate").Range(1.0, 100.0);
    b.BindDegrees("max_tilt_deg", &TestOptions::max_tilt, "tilt limit").Range(0.0, 45.0);
    b.BindScaled("lead_mm", &TestOptions::lead, 1e-3, "mm", "look-ahead").Min(0.0);
    b.Bind("cycles", &TestOptions::cycles, "", "cycles over the limit").Range(1, 10);
    b.Bind("id_prefix", &TestOptions::id_prefix, "", "request id prefix").Range(1, 255);
    b.Bind("enabled", &TestOptions::enabled, "checks on");
    b.Bind("name", &TestOptions::name, "camera").OneOf({"front", "rear"});
    b.Bind("gains", &TestOptions::gains, "", "PID gains");
    b.Bind("offset", &TestOptions::offset, "m", "mount offset");
    b.BindEnum("mode", &TestOptions::mode, {{"arc", Mode::kArc}, {"turn", Mode::kTurn}},
               "primitive");
    b.Nest("prior.", &TestOptions::prior);
  }
};

TEST(ParamBinder, DeclaresWithDefaultsUnitsAndRanges) {
  ParamSet p("svc");
  DeclareParams<TestOptions>(p, "t.");
  ASSERT_TRUE(p.Validate().ok());
  EXPECT_EQ(p.GetDouble("t.rate_hz"), 8.0);
  EXPECT_NEAR(p.GetDouble("t.max_tilt_deg"), 30.0, 1e-12);
  EXPECT_NEAR(p.GetDouble("t.lead_mm"), 500.0, 1e-9);
  EXPECT_EQ(p.GetInt("t.cycles"), 3);
  EXPECT_EQ(p.GetString("t.mode"), "arc");
  EXPECT_EQ(p.GetDoubleList("t.offset").size(), 3u);
  EXPECT_EQ(p.GetDouble("t.prior.sigma"), 0.01);
  EXPECT_EQ(p.spec("t.max_tilt_deg").doc(), "[deg] tilt limit");
  EXPECT_EQ(p.spec("t.enabled").doc(), "checks on");
  EXPECT_FALSE(p.Has("t.unbound"));
  // Ranges are declared in the parameter's unit.
  ASSERT_TRUE(p.SetFromString("t.max_tilt_deg=50").ok());
  EXPECT_EQ(p.Validate().message(), "--set t.max_tilt_deg=50: key 't.max_tilt_deg': 50 is out of range [0, 45]");
}

TEST(ParamBinder, CustomDefaultsReplaceTheStructs) {
  TestOptions d;
  d.rate_hz = 20.0;
  ParamSet p;
  DeclareParams(p, "", d);
  EXPECT_EQ(p.GetDouble("rate_hz"), 20.0);
}

TEST(ParamBinder, ReadsBackEveryMemberInItsUnit) {
  ParamSet p;
  DeclareParams<TestOptions>(p, "t.");
  ASSERT_TRUE(p.LoadYamlString("t:\n  rate_hz: 10\n  max_tilt_deg: 20\n  lead_mm: 250\n"
                               "  cycles: 4\n  id_prefix: 7\n  enabled: false\n  name: rear\n"
                               "  gains: [3, 4, 5]\n  offset: [1, 2, 3]\n  mode: turn\n"
                               "  prior: {sigma: 0.5}\n",
                               "f.yaml")
                  .ok());
  auto o = ReadParams<TestOptions>(p, "t.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->rate_hz, 10.0);
  EXPECT_NEAR(o->max_tilt, 20.0 * kDegree, 1e-12);
  EXPECT_NEAR(o->lead, 0.25, 1e-12);
  EXPECT_EQ(o->cycles, 4);
  EXPECT_EQ(o->id_prefix, 7u);
  EXPECT_FALSE(o->enabled);
  EXPECT_EQ(o->name, "rear");
  EXPECT_EQ(o->gains, (std::vector<double>{3, 4, 5}));
  EXPECT_EQ(o->offset[2], 3.0);
  EXPECT_EQ(o->mode, Mode::kTurn);
  EXPECT_EQ(o->prior.sigma, 0.5);
  EXPECT_EQ(o->unbound, 42.0);
}

TEST(ParamBinder, ValidateFailureNamesTheKeyAndItsOrigin) {
  ParamSet p;
  DeclareParams<TestOptions>(p, "drive.");
  ASSERT_TRUE(p.LoadYamlString("drive:\n  rate_hz: 9\n  max_tilt_deg: 44\n", "d.yaml").ok());
  auto o = ReadParams<TestOptions>(p, "drive.");
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(o.status().message(),
            "d.yaml:3: key 'drive.max_tilt_deg': max_tilt = 0.767945 rad is outside [0, "
            "0.698132]");
}

TEST(ParamBinder, FailureOfNoSingleKeyNamesThePrefix) {
  ParamSet p;
  DeclareParams<TestOptions>(p, "drive.");
  ASSERT_TRUE(p.SetFromString("drive.cycles=7").ok());
  ASSERT_TRUE(p.SetFromString("drive.enabled=false").ok());
  auto o = ReadParams<TestOptions>(p, "drive.");
  ASSERT_FALSE(o.ok());
  // "cycles" starts the message, so it is attributed to that key.
  EXPECT_EQ(o.status().message(), "--set drive.cycles=7: key 'drive.cycles': cycles must be <= 5 when disabled");
}

TEST(ParamBinder, RangeErrorsComeFromTheParamSet) {
  ParamSet p;
  DeclareParams<TestOptions>(p, "");
  ASSERT_TRUE(p.SetFromString("cycles=0").ok());
  EXPECT_EQ(ReadParams<TestOptions>(p, "").status().message(),
            "--set cycles=0: key 'cycles': 0 is out of range [1, 10]");
}

TEST(ParamBinder, BoundParamsListsEveryKeyOnce) {
  const auto bound = BoundParams<TestOptions>();
  ASSERT_EQ(bound.size(), 11u);
  EXPECT_EQ(bound.back().key, "prior.sigma");
}

}  // namespace
}  // namespace rover
