// The nav_core headers: they compile, the inline helpers index the map as the topic does,
// RangeScan::Validate names the field that is wrong, and the interfaces can be implemented.
#include <gtest/gtest.h>

#include <limits>

#include "rover/apl/nav_core/arc_selector.hpp"
#include "rover/apl/nav_core/global_planner.hpp"
#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/apl/nav_core/terrain_assessor.hpp"

namespace rover::apl::nav_core {
namespace {

GoodnessMap SmallMap() {
  GoodnessMap m;
  m.origin_x = -1.0;
  m.origin_y = 2.0;
  m.resolution = 0.5;
  m.width = 4;
  m.height = 3;
  m.goodness.assign(m.cell_count(), 0);
  m.certainty.assign(m.cell_count(), 0);
  m.flags.assign(m.cell_count(), 0);
  m.unknown_goodness = 11;
  m.unknown_certainty = 0;
  return m;
}

TEST(GoodnessMap, IndexesRowMajorWithRowsAlongY) {
  GoodnessMap m = SmallMap();
  EXPECT_EQ(m.Index(3, 0), 3u);
  EXPECT_EQ(m.Index(0, 1), 4u);
  int i = 0, j = 0;
  m.CellOf(-0.76, 2.9, &i, &j);  // x: 0.24 / 0.5 -> 0; y: 0.9 / 0.5 -> 1
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 1);
  m.CellOf(-1.01, 2.0, &i, &j);  // just below the origin: cell -1
  EXPECT_EQ(i, -1);
  EXPECT_EQ(j, 0);
  EXPECT_DOUBLE_EQ(m.CellCenter(2, 1).x(), 0.25);
  EXPECT_DOUBLE_EQ(m.CellCenter(2, 1).y(), 2.75);
}

TEST(GoodnessMap, OutsideCellsReadAsUnknown) {
  GoodnessMap m = SmallMap();
  m.goodness[m.Index(1, 2)] = 200;
  m.certainty[m.Index(1, 2)] = 255;
  m.flags[m.Index(1, 2)] = kCellKnown;
  const CellValue in = m.AtPoint(-0.3, 3.2);
  EXPECT_EQ(in.goodness, 200);
  EXPECT_TRUE(in.known());
  const CellValue out = m.AtPoint(5.0, 0.0);
  EXPECT_EQ(out.goodness, 11);
  EXPECT_EQ(out.certainty, 0);
  EXPECT_FALSE(out.known());
}

RangeScan TwoByTwo() {
  RangeScan s;
  s.width = 2;
  s.height = 2;
  s.xyz.assign(12, 1.0f);
  s.valid.assign(4, 1);
  return s;
}

TEST(RangeScan, ValidatesShapeAndPose) {
  RangeScan s = TwoByTwo();
  EXPECT_TRUE(s.Validate().ok());
  EXPECT_EQ(s.point(1, 1).x(), 1.0);
  s.xyz.pop_back();
  EXPECT_EQ(s.Validate().message(),
            "RangeScan.xyz: 11 floats for 2 x 2 pixels (need 12 = 3 per pixel)");
  s = TwoByTwo();
  s.valid.resize(3);
  EXPECT_EQ(s.Validate().message(), "RangeScan.valid: 3 bytes for 4 pixels");
  s = TwoByTwo();
  s.width = 0;
  EXPECT_EQ(s.Validate().message(), "RangeScan.width x height = 0 x 2 (both must be > 0)");
  s = TwoByTwo();
  s.site_from_rover.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(s.Validate().message(), "RangeScan.site_from_rover(0, 3) is nan (must be finite)");
  s = TwoByTwo();
  s.site_from_rover.linear() *= 2.0;
  EXPECT_NE(s.Validate().message().find("rotation is not orthonormal"), std::string::npos);
}

// A trivial assessor: the interface is implementable and its default GoodnessAt reads the map.
class ConstantAssessor final : public TerrainAssessor {
 public:
  ConstantAssessor() : map_(SmallMap()) {}
  Result<AssessmentStats> Update(const RangeScan& scan) override {
    ROVER_RETURN_IF_ERROR(scan.Validate());
    AssessmentStats s;
    s.points_total = static_cast<int>(scan.pixel_count());
    return s;
  }
  void Follow(const Eigen::Isometry3d&) override {}
  const GoodnessMap& goodness_map() const override { return map_; }
  void Clear() override { map_ = SmallMap(); }

 private:
  GoodnessMap map_;
};

TEST(TerrainAssessor, DefaultQueryReadsTheMap) {
  ConstantAssessor a;
  EXPECT_EQ(a.GoodnessAt({-0.9, 2.1}).goodness, 0);
  EXPECT_EQ(a.GoodnessAt({9.0, 9.0}).goodness, 11);
  RangeScan bad = TwoByTwo();
  bad.height = 3;
  EXPECT_FALSE(a.Update(bad).ok());
  auto ok = a.Update(TwoByTwo());
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->points_total, 4);
}

TEST(ArcEvaluation, ChoiceRefersToTheChosenCandidate) {
  ArcEvaluation e;
  e.candidates.resize(3);
  e.candidates[2].kind = MotionKind::kPointTurn;
  EXPECT_FALSE(e.has_choice());
  e.chosen = 2;
  EXPECT_TRUE(e.has_choice());
  EXPECT_EQ(e.choice().kind, MotionKind::kPointTurn);
}

// A planner without replanning: only the required members.
class StraightLinePlanner final : public GlobalPlanner {
 public:
  Status AddScan(const RangeScan&) override { return Status::Ok(); }
  Result<GlobalPlan> MakePlan(const PlanRequest& r) override {
    GlobalPlan p;
    p.waypoints = {r.goal};
    return p;
  }
  void Clear() override {}
};

TEST(GlobalPlanner, ReportBlockedDefaultsToAPreconditionError) {
  StraightLinePlanner planner;
  const Status s = planner.ReportBlocked({0, 0}, {1, 0}, 0.6);
  EXPECT_EQ(s.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(s.message().find("does not replan"), std::string::npos);
  const PlanRequest request;
  EXPECT_FALSE(request.allow_partial);
  auto plan = planner.MakePlan(request);
  ASSERT_TRUE(plan.ok());
  EXPECT_TRUE(plan->reaches_goal);
}

TEST(NavCore, RangeScanFromImageCarriesPixelsPoseAndCamera) {
  msg::RangeImage image;
  image.stamp = Time{9};
  image.camera = msg::CameraId::kRearHazcam;
  image.width = 2;
  image.height = 1;
  image.rover_pose =
      Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ());
  image.xyz = {1, 2, 3, 4, 5, 6};
  image.valid = {1, 0};
  image.disparity = {3.5f, -1.0f};
  const RangeScan s = RangeScanFromImage(image);
  EXPECT_TRUE(s.Validate().ok()) << s.Validate().message();
  EXPECT_EQ(s.width, 2);
  EXPECT_EQ(s.height, 1);
  EXPECT_EQ(s.xyz, image.xyz);
  EXPECT_EQ(s.valid, image.valid);
  EXPECT_EQ(s.capture_time.ns, 9);
  EXPECT_EQ(s.camera, "rear_hazcam");
  EXPECT_TRUE(s.site_from_rover.isApprox(image.rover_pose, 1e-12));
  image.xyz.pop_back();  // not checked here: Validate names it
  const Status bad = RangeScanFromImage(image).Validate();
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("RangeScan.xyz: 5 floats"), std::string::npos) << bad.message();
}

TEST(NavCore, GoodnessMapToMessageCopiesTheGrid) {
  GoodnessMap g = SmallMap();
  g.goodness[5] = 200;
  g.certainty[6] = 90;
  g.flags[7] = kCellKnown | kCellBorder;
  g.stamp = Time{77};
  const msg::GoodnessMap m = GoodnessMapToMessage(g);
  EXPECT_TRUE(m.CheckSizes().ok());
  EXPECT_EQ(m.origin_x, -1.0);
  EXPECT_EQ(m.origin_y, 2.0);
  EXPECT_EQ(m.resolution, 0.5);
  EXPECT_EQ(m.width, 4);
  EXPECT_EQ(m.height, 3);
  EXPECT_EQ(m.unknown_goodness, 11);
  EXPECT_EQ(m.goodness, g.goodness);
  EXPECT_EQ(m.certainty, g.certainty);
  EXPECT_EQ(m.flags, g.flags);
  EXPECT_EQ(m.stamp.ns, 77);
}

}  // namespace
}  // namespace rover::apl::nav_core
