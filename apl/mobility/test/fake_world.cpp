#include "fake_world.hpp"

#include <algorithm>
#include <cmath>

#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"
#include "rover/base/check.hpp"
#include "rover/base/cpu_time.hpp"

namespace rover::apl::mobility::testing {

DriveStatus DriveReport(std::uint32_t command_id, DriveState state, DriveTermination termination,
                        double distance_done, std::string message) {
  DriveStatus r;
  r.command_id = command_id;
  r.state = state;
  r.termination = termination;
  r.distance_done = distance_done;
  r.message = std::move(message);
  return r;
}

MobilityManager MakeGestaltManager(const MobilityOptions& options) {
  const gestalt::GestaltOptions g;
  auto map = gestalt::TerrainMap::Create(g);
  auto arcs = gestalt::ArcEvaluator::Create(g);
  ROVER_DEMAND(map.ok() && arcs.ok());
  auto manager = MobilityManager::Create(
      options, std::make_unique<gestalt::TerrainMap>(std::move(map).value()),
      std::make_unique<gestalt::ArcEvaluator>(std::move(arcs).value()));
  ROVER_DEMAND(manager.ok());
  return std::move(manager).value();
}

FakeWorld::FakeWorld(MobilityManager* manager, WorldOptions options, const Scene* scene)
    : manager_(manager), options_(options), scene_(scene) {}

void FakeWorld::AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing,
                        double radius, double height) {
  field_.AddWall(a, b, spacing, radius, height);
}

void FakeWorld::Scatter(std::uint32_t seed, int n, double x0, double x1, double y0, double y1,
                        double radius, double height,
                        const std::vector<Eigen::Vector2d>& keep_clear, double clear) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  int placed = 0;
  for (int tries = 0; placed < n && tries < 100 * n; ++tries) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    bool ok = true;
    for (const auto& k : keep_clear) ok = ok && (p - k).norm() > clear;
    if (!ok) continue;
    field_.rocks().push_back({p.x(), p.y(), radius, height});
    ++placed;
  }
}

double FakeWorld::HeightAt(double x, double y) const { return field_.HeightAt(x, y); }

nav_core::RangeScan FakeWorld::Capture(CameraId camera) const {
  nav_core::RangeScan scan;
  if (scene_ != nullptr) {
    scan = scene_->Capture(pose_, camera);
  } else {
    rover::testing::SyntheticScan img = field_.Capture(
        pose_.x, pose_.y, pose_.heading, camera == CameraId::kRearHazcam, options_.camera);
    scan.width = img.width;
    scan.height = img.height;
    scan.xyz = std::move(img.xyz);
    scan.valid = std::move(img.valid);
  }
  scan.capture_time = now_;
  scan.camera = std::string(CameraName(camera));
  scan.site_from_rover = PoseNow().site_from_rover;
  return scan;
}

PoseSample FakeWorld::PoseNow() const {
  PoseSample ps;
  ps.stamp = now_;
  if (scene_ != nullptr) {
    ps.site_from_rover = scene_->SiteFromRover(pose_);
    return ps;
  }
  ps.site_from_rover.linear() =
      Eigen::AngleAxisd(pose_.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  ps.site_from_rover.translation() = Eigen::Vector3d(pose_.x, pose_.y, 0.0);
  return ps;
}

void FakeWorld::Absorb(const MobilityOutput& out) {
  for (const MobilityStatus& s : out.statuses) statuses_.push_back(s);
  arc_votes_ += static_cast<int>(out.arc_votes.size());
  if (on_arc_votes) {
    for (const ArcVotesSnapshot& v : out.arc_votes) on_arc_votes(v);
  }
  for (const DriveCommand& d : out.drives) {
    drives_.push_back(d);
    if (d.primitive == PrimitiveKind::kStop) {
      if (drive_) {
        const DriveStatus rep = DriveReport(drive_->command_id, DriveState::kFailed,
                                            DriveTermination::kStopCommand, drive_done_, "stopped");
        drive_.reset();
        Absorb(Timed([&] { return manager_->OnDriveStatus(rep, now_); }));
      }
      continue;
    }
    if (drive_) {
      Absorb(Timed([&] { return manager_->OnDriveStatus(DriveReport(d.command_id, DriveState::kRejected,
                                                 DriveTermination::kRejectedBusy, 0.0, "busy"),
                                     now_); }));
      continue;
    }
    drive_ = d;
    drive_done_ = 0.0;
  }
  for (const RangeRequest& r : out.range_requests) {
    ranges_.push_back(r);
    if (!options_.deliver_images) continue;
    if (static_cast<int>(ranges_.size()) <= options_.lose_requests) continue;
    images_.push_back(
        {Capture(r.camera), r.camera, r.request_id, now_ + Seconds(options_.image_latency_s)});
  }
}

void FakeWorld::Tick() {
  now_ = now_ + Seconds(options_.dt);
  if (drive_) {
    const bool turn = drive_->primitive == PrimitiveKind::kTurnInPlace;
    const double goal = turn ? std::abs(drive_->angle) : std::abs(drive_->distance);
    const double inc =
        std::min(goal - drive_done_, (turn ? options_.turn_rate : options_.speed) * options_.dt);
    Primitive p;
    p.kind = drive_->primitive;
    p.curvature = drive_->curvature;
    p.distance = turn ? 0.0 : std::copysign(inc, drive_->distance);
    p.angle = turn ? std::copysign(inc, drive_->angle) : 0.0;
    pose_ = Propagate(pose_, p);
    drive_done_ += inc;
    if (drive_done_ >= goal - 1e-9) {
      const DriveStatus rep = DriveReport(drive_->command_id, DriveState::kDone,
                                          DriveTermination::kNominal, turn ? 0.0 : goal, "");
      drive_.reset();
      Absorb(Timed([&] { return manager_->OnDriveStatus(rep, now_); }));
    } else if (options_.report_progress) {
      const DriveStatus rep =
          DriveReport(drive_->command_id, turn ? DriveState::kTurning : DriveState::kDriving,
                      DriveTermination::kNominal, turn ? 0.0 : drive_done_, "");
      Absorb(Timed([&] { return manager_->OnDriveStatus(rep, now_); }));
    }
  }
  min_clearance_ = std::min(min_clearance_, scene_ != nullptr
                                                ? scene_->Clearance(pose_.x, pose_.y)
                                                : field_.Clearance(pose_.x, pose_.y));
  if (options_.deliver_poses) {
    PoseSample ps = PoseNow();
    if (tamper_pose) tamper_pose(&ps);
    Absorb(Timed([&] { return manager_->OnPose(ps, now_); }));
  }
  for (std::size_t i = 0; i < images_.size();) {
    if (images_[i].due <= now_) {
      Image img = std::move(images_[i]);
      images_.erase(images_.begin() + static_cast<std::ptrdiff_t>(i));
      if (tamper_image) tamper_image(&img.scan, &img.camera);
      Absorb(Timed([&] { return manager_->OnRangeImage(img.scan, img.camera, img.id, now_); }));
    } else {
      ++i;
    }
  }
  Absorb(Timed([&] { return manager_->Step(now_); }));
}

MobilityStatus FakeWorld::Run(const MobilityCommand& command, double max_s) {
  if (options_.deliver_poses) {
    // A current pose so the command is not rejected for want of one.
    Absorb(Timed([&] { return manager_->OnPose(PoseNow(), now_); }));
  }
  const std::size_t first = statuses_.size();
  Absorb(Timed([&] { return manager_->OnCommand(command, now_); }));
  const Time end = now_ + Seconds(max_s);
  MobilityStatus last;
  last.state = State::kRunning;
  std::size_t seen = first;
  while (true) {
    for (; seen < statuses_.size(); ++seen) {
      const MobilityStatus& s = statuses_[seen];
      if (s.command_id == command.command_id && s.state != State::kRunning) return s;
      if (s.command_id == command.command_id) last = s;
    }
    if (now_ >= end) return last;
    Tick();
  }
}


}  // namespace rover::apl::mobility::testing
