#include "fake_world.hpp"

#include <algorithm>
#include <cmath>

#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"
#include "rover/base/check.hpp"

namespace rover::apl::mobility::testing {

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

FakeWorld::FakeWorld(MobilityManager* manager, WorldOptions options)
    : manager_(manager), options_(options) {}

void FakeWorld::AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing,
                        double radius, double height) {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    rocks_.push_back({p.x(), p.y(), radius, height});
  }
}

void FakeWorld::Scatter(std::uint32_t seed, int n, double x0, double x1, double y0, double y1,
                        double radius, double height, const std::vector<Eigen::Vector2d>& keep_clear,
                        double clear) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  int placed = 0;
  for (int tries = 0; placed < n && tries < 100 * n; ++tries) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    bool ok = true;
    for (const auto& k : keep_clear) ok = ok && (p - k).norm() > clear;
    if (!ok) continue;
    rocks_.push_back({p.x(), p.y(), radius, height});
    ++placed;
  }
}

double FakeWorld::HeightAt(double x, double y) const {
  double z = 0.0;
  for (const Rock& r : rocks_) {
    const double d2 = (x - r.x) * (x - r.x) + (y - r.y) * (y - r.y);
    if (d2 < r.radius * r.radius) z = std::max(z, r.height * std::sqrt(1.0 - d2 / (r.radius * r.radius)));
  }
  return z;
}

nav_core::RangeScan FakeWorld::Capture(Camera camera) const {
  nav_core::RangeScan scan;
  scan.width = options_.cols;
  scan.height = options_.rows;
  scan.xyz.assign(3 * scan.pixel_count(), 0.0f);
  scan.valid.assign(scan.pixel_count(), 0);
  scan.capture_time = now_;
  scan.camera = std::string(CameraName(camera));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(pose_.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(pose_.x, pose_.y, 0.0);
  scan.site_from_rover = pose;
  const double facing = camera == Camera::kRearHazcam ? M_PI : 0.0;
  const double c = std::cos(pose_.heading), s = std::sin(pose_.heading);
  for (int u = 0; u < options_.cols; ++u) {
    const double az = facing + options_.fov * (0.5 - (u + 0.5) / options_.cols);
    double horizon = -1e9;  // steepest elevation tangent seen so far along the ray
    // Rows run far (v = 0) to near; march near to far for occlusion.
    for (int r = 0; r < options_.rows; ++r) {
      const double range = options_.near_range +
                           (options_.far_range - options_.near_range) * r / (options_.rows - 1);
      const double xr = range * std::cos(az), yr = range * std::sin(az);
      const double xs = pose_.x + c * xr - s * yr, ys = pose_.y + s * xr + c * yr;
      const double z = HeightAt(xs, ys);
      const double tangent = (z - options_.camera_height) / range;
      const int v = options_.rows - 1 - r;
      const std::size_t k = static_cast<std::size_t>(v) * options_.cols + u;
      if (tangent >= horizon) {
        scan.valid[k] = 1;
        scan.xyz[3 * k] = static_cast<float>(xr);
        scan.xyz[3 * k + 1] = static_cast<float>(yr);
        scan.xyz[3 * k + 2] = static_cast<float>(z);
        horizon = tangent;
      }
    }
  }
  return scan;
}

void FakeWorld::Absorb(const MobilityOutput& out) {
  for (const MobilityStatus& s : out.statuses) statuses_.push_back(s);
  arc_votes_ += static_cast<int>(out.arc_votes.size());
  for (const DriveRequest& d : out.drives) {
    drives_.push_back(d);
    if (d.kind == PrimitiveKind::kStop) {
      if (drive_) {
        DriveReport rep{drive_->command_id, DriveState::kFailed, DriveTermination::kStopCommand,
                        drive_done_, "stopped"};
        drive_.reset();
        Absorb(manager_->OnDriveStatus(rep, now_));
      }
      continue;
    }
    if (drive_) {
      Absorb(manager_->OnDriveStatus({d.command_id, DriveState::kRejected,
                                      DriveTermination::kRejectedBusy, 0.0, "busy"},
                                     now_));
      continue;
    }
    drive_ = d;
    drive_done_ = 0.0;
  }
  for (const RangeRequest& r : out.range_requests) {
    ranges_.push_back(r);
    if (!options_.deliver_images) continue;
    images_.push_back({Capture(r.camera), r.camera, r.request_id,
                       now_ + Seconds(options_.image_latency_s)});
  }
}

void FakeWorld::Tick() {
  now_ = now_ + Seconds(options_.dt);
  if (drive_) {
    const bool turn = drive_->kind == PrimitiveKind::kTurnInPlace;
    const double goal = turn ? std::abs(drive_->angle) : std::abs(drive_->distance);
    const double inc = std::min(goal - drive_done_,
                                (turn ? options_.turn_rate : options_.speed) * options_.dt);
    Primitive p;
    p.kind = drive_->kind;
    p.curvature = drive_->curvature;
    p.distance = turn ? 0.0 : std::copysign(inc, drive_->distance);
    p.angle = turn ? std::copysign(inc, drive_->angle) : 0.0;
    pose_ = Propagate(pose_, p);
    drive_done_ += inc;
    if (drive_done_ >= goal - 1e-9) {
      const DriveReport rep{drive_->command_id, DriveState::kDone, DriveTermination::kNominal,
                            turn ? 0.0 : goal, ""};
      drive_.reset();
      Absorb(manager_->OnDriveStatus(rep, now_));
    }
  }
  for (const Rock& r : rocks_) {
    min_clearance_ = std::min(min_clearance_, std::hypot(pose_.x - r.x, pose_.y - r.y) - r.radius);
  }
  if (options_.deliver_poses) {
    PoseSample ps;
    ps.stamp = now_;
    ps.site_from_rover.linear() =
        Eigen::AngleAxisd(pose_.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    ps.site_from_rover.translation() = Eigen::Vector3d(pose_.x, pose_.y, 0.0);
    if (tamper_pose) tamper_pose(&ps);
    Absorb(manager_->OnPose(ps, now_));
  }
  for (std::size_t i = 0; i < images_.size();) {
    if (images_[i].due <= now_) {
      Image img = std::move(images_[i]);
      images_.erase(images_.begin() + static_cast<std::ptrdiff_t>(i));
      if (tamper_image) tamper_image(&img.scan, &img.camera);
      Absorb(manager_->OnRangeImage(img.scan, img.camera, img.id, now_));
    } else {
      ++i;
    }
  }
  Absorb(manager_->Step(now_));
}

MobilityStatus FakeWorld::Run(const MobilityCommand& command, double max_s) {
  if (options_.deliver_poses) {
    // A current pose so the command is not rejected for want of one.
    PoseSample ps;
    ps.stamp = now_;
    ps.site_from_rover.linear() =
        Eigen::AngleAxisd(pose_.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    ps.site_from_rover.translation() = Eigen::Vector3d(pose_.x, pose_.y, 0.0);
    Absorb(manager_->OnPose(ps, now_));
  }
  const std::size_t first = statuses_.size();
  Absorb(manager_->OnCommand(command, now_));
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
