#include "rover/hwconfig/rover_description.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::hwconfig {
namespace {

using Binder = ParamBinder<RoverDescription>;

std::span<const double> Span(const Eigen::Vector3d& v) { return {v.data(), 3}; }

// "name = 1.2 m" for the other side of a cross-field rule.
std::string Ref(const char* name, double v) {
  return std::string(name) + " (" + FormatNumber(v) + ")";
}

// A number reached through `field` (a generic lambda returning a reference to the member),
// given in the key's unit: member = value * scale.
template <class Field>
Binder::Binding BindNumber(Binder& b, std::string key, Field field, double scale, std::string unit,
                           std::string doc) {
  return b.BindCustom(
      std::move(key), ParamType::kDouble, std::move(unit), std::move(doc),
      [field, scale](const RoverDescription& d) -> ParamValue { return field(d) / scale; },
      [field, scale](RoverDescription& d, const ParamValue& v) {
        field(d) = std::get<double>(v) * scale;
      });
}

// A point [m] given as [x, y, z].
template <class Field>
Binder::Binding BindPoint(Binder& b, std::string key, Field field, std::string doc) {
  return b
      .BindCustom(
          std::move(key), ParamType::kDoubleList, "m", std::move(doc),
          [field](const RoverDescription& d) -> ParamValue {
            const Eigen::Vector3d& v = field(d);
            return std::vector<double>{v.x(), v.y(), v.z()};
          },
          [field](RoverDescription& d, const ParamValue& v) {
            const auto& l = std::get<std::vector<double>>(v);
            field(d) = Eigen::Vector3d(l[0], l[1], l[2]);
          })
      .Size(3);
}

void BindMount(Binder& b, const std::string& name, StereoMount RoverDescription::*m,
               const std::string& what) {
  BindPoint(
      b, name + ".position", [m](auto& d) -> auto& { return (d.*m).position; },
      what + ": pair centre (midway between the optical centres)");
  BindNumber(
      b, name + ".yaw_deg", [m](auto& d) -> auto& { return (d.*m).yaw; }, kDegree, "deg",
      name + " boresight azimuth about the parent z (180 = backwards)");
  BindNumber(
      b, name + ".depression_deg", [m](auto& d) -> auto& { return (d.*m).depression; }, kDegree,
      "deg", name + " boresight below the parent x-y plane");
  BindNumber(
      b, name + ".baseline", [m](auto& d) -> auto& { return (d.*m).baseline; }, 1.0, "m",
      name + " distance between the two optical centres");
}

// Points whose distance from `c` bounds the rectangle [x0, x1] x [y0, y1].
double FarthestCorner(const Eigen::Vector2d& c, double x0, double x1, double y0, double y1) {
  const double dx = std::max(std::abs(x0 - c.x()), std::abs(x1 - c.x()));
  const double dy = std::max(std::abs(y0 - c.y()), std::abs(y1 - c.y()));
  return std::hypot(dx, dy);
}

}  // namespace

const char* WheelName(int wheel) {
  static constexpr const char* kNames[kNumWheels] = {"LF", "LM", "LR", "RF", "RM", "RR"};
  return wheel >= 0 && wheel < kNumWheels ? kNames[wheel] : "?";
}

Eigen::Isometry3d StereoMount::Pose() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = position;
  t.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(depression, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return t;
}

Eigen::Vector3d StereoMount::CameraCentre(int side) const {
  ROVER_DEMAND(side == kLeft || side == kRight);
  const double half = side == kLeft ? 0.5 * baseline : -0.5 * baseline;
  return position + Pose().linear() * Eigen::Vector3d(0.0, half, 0.0);
}

Status StereoMount::Validate(const std::string& name) const {
  ROVER_RETURN_IF_ERROR(
      CheckAllInRange(name + ".position", Span(position), Bounds::Closed(-10, 10), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".yaw", yaw / kDegree, -360.0, 360.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".depression", depression / kDegree, -90.0, 90.0, "deg"));
  return CheckRange(name + ".baseline", baseline, Bounds::OpenLow(0.0, 5.0), "m");
}

Status MastDescription::Validate() const {
  ROVER_RETURN_IF_ERROR(
      CheckAllInRange("mast.pan_joint", Span(pan_joint), Bounds::Closed(-10, 10), "m"));
  return CheckRange("mast.head_height", head_height, 0.0, 10.0, "m");
}

Eigen::Isometry3d MastDescription::HeadPose(double pan, double tilt) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = pan_joint + Eigen::Vector3d(0.0, 0.0, head_height);
  t.linear() = (Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return t;
}

void RoverDescription::BindParams(Binder& b) {
  using D = RoverDescription;
  b.Bind("wheel_radius", &D::wheel_radius, "m", "drive wheel radius");
  b.Bind("wheel_width", &D::wheel_width, "m", "drive wheel width");
  b.Bind("front_wheel_x", &D::front_wheel_x, "m", "x of the front wheel centres");
  b.Bind("middle_wheel_x", &D::middle_wheel_x, "m", "x of the unsteered middle axle");
  b.Bind("rear_wheel_x", &D::rear_wheel_x, "m", "x of the rear wheel centres");
  b.Bind("half_track", &D::half_track, "m", "|y| of every wheel centre");
  b.Bind("steer_height", &D::steer_height, "m", "steering joint above the wheel centre");
  b.Bind("rocker_pivot_x", &D::rocker_pivot_x, "m", "x of the rocker (differential) pivots");
  b.Bind("rocker_pivot_y", &D::rocker_pivot_y, "m", "|y| of the rocker pivots on the body");
  b.Bind("rocker_pivot_z", &D::rocker_pivot_z, "m", "z of the rocker pivots");
  b.Bind("bogie_pivot_x", &D::bogie_pivot_x, "m", "x of the bogie pivots at zero angles");
  b.Bind("bogie_pivot_z", &D::bogie_pivot_z, "m", "z of the bogie pivots at zero angles");
  b.Bind("rocker_limit", &D::rocker_limit, "rad", "rocker mechanical stops at +-limit");
  b.Bind("bogie_limit", &D::bogie_limit, "rad", "bogie mechanical stops at +-limit");
  BindPoint(
      b, "body_size", [](auto& d) -> auto& { return d.body_size; },
      "body box extents along x, y, z");
  BindPoint(
      b, "body_centre", [](auto& d) -> auto& { return d.body_centre; },
      "body box centre (and centre of mass)");
  BindPoint(
      b, "imu_position", [](auto& d) -> auto& { return d.imu_position; }, "IMU reference point");
  BindPoint(
      b, "mast.pan_joint", [](auto& d) -> auto& { return d.mast.pan_joint; },
      "mast pan joint (the pan axis is vertical through it)");
  BindNumber(
      b, "mast.head_height", [](auto& d) -> auto& { return d.mast.head_height; }, 1.0, "m",
      "tilt axis (mast-head frame origin) above the pan joint");
  BindMount(b, "navcam", &D::navcam, "NAVCAM, mast-head frame");
  BindMount(b, "front_hazcam", &D::front_hazcam, "front HAZCAM, rover frame");
  BindMount(b, "rear_hazcam", &D::rear_hazcam, "rear HAZCAM, rover frame");
  BindPoint(
      b, "arm.shoulder", [](auto& d) -> auto& { return d.arm.shoulder; },
      "arm shoulder pivot (the azimuth axis is vertical through it)");
  BindNumber(
      b, "arm.upper_arm", [](auto& d) -> auto& { return d.arm.upper_arm; }, 1.0, "m",
      "arm shoulder to elbow");
  BindNumber(
      b, "arm.forearm", [](auto& d) -> auto& { return d.arm.forearm; }, 1.0, "m",
      "arm elbow to wrist");
  BindNumber(
      b, "arm.tool_length", [](auto& d) -> auto& { return d.arm.tool_length; }, 1.0, "m",
      "arm wrist to the instrument's face centre");
  BindNumber(
      b, "arm.link_radius", [](auto& d) -> auto& { return d.arm.link_radius; }, 1.0, "m",
      "radius of the capsule about each arm link (swept-volume checks)");
  BindNumber(
      b, "arm.clearance", [](auto& d) -> auto& { return d.arm.clearance; }, 1.0, "m",
      "distance every arm pose keeps from the rover's keep-out boxes");
  BindNumber(
      b, "arm.face_radius", [](auto& d) -> auto& { return d.arm.face_radius; }, 1.0, "m",
      "radius of the instrument face's contact ring");
  BindNumber(
      b, "arm.contact_standoff", [](auto& d) -> auto& { return d.arm.contact_standoff; }, 1.0,
      "m", "the contact switch closes when the face comes within this of a surface");
  BindNumber(
      b, "arm.imager.focal_px", [](auto& d) -> auto& { return d.arm.imager.focal_px; }, 1.0,
      "px", "microscopic imager focal length in pixels");
  BindNumber(
      b, "arm.imager.working_distance",
      [](auto& d) -> auto& { return d.arm.imager.working_distance; }, 1.0, "m",
      "instrument face to the microscopic imager's plane of best focus");
  BindNumber(
      b, "arm.imager.aperture", [](auto& d) -> auto& { return d.arm.imager.aperture; }, 1.0,
      "m", "microscopic imager entrance-pupil diameter (depth of field)");
  b.BindDegrees("max_steer_angle_deg", &D::max_steer_angle,
                "corner-wheel steering limit for driving");
  b.Bind("min_turn_radius", &D::min_turn_radius, "m",
         "tightest arc radius (middle-axle centre point)");
  b.Bind("max_wheel_speed", &D::max_wheel_speed, "m/s",
         "fastest rim speed commanded to a drive motor");
}

Status RoverDescription::Validate() const {
  ROVER_RETURN_IF_ERROR(arm.Validate());
  ROVER_RETURN_IF_ERROR(CheckRange("wheel_radius", wheel_radius, 0.01, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("wheel_width", wheel_width, 0.005, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("front_wheel_x", front_wheel_x, -5.0, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("middle_wheel_x", middle_wheel_x, -5.0, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("rear_wheel_x", rear_wheel_x, -5.0, 5.0, "m"));
  if (!(middle_wheel_x < front_wheel_x)) {
    return InvalidArgument(Describe("middle_wheel_x", middle_wheel_x, "m") + " must be behind " +
                           Ref("front_wheel_x", front_wheel_x));
  }
  if (!(rear_wheel_x < middle_wheel_x)) {
    return InvalidArgument(Describe("rear_wheel_x", rear_wheel_x, "m") + " must be behind " +
                           Ref("middle_wheel_x", middle_wheel_x));
  }
  ROVER_RETURN_IF_ERROR(CheckRange("half_track", half_track, wheel_width, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("steer_height", steer_height, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("bogie_pivot_x", bogie_pivot_x, -5.0, 5.0, "m"));
  if (!(bogie_pivot_x > rear_wheel_x && bogie_pivot_x < middle_wheel_x)) {
    return InvalidArgument(Describe("bogie_pivot_x", bogie_pivot_x, "m") + " must lie between " +
                           Ref("rear_wheel_x", rear_wheel_x) + " and " +
                           Ref("middle_wheel_x", middle_wheel_x));
  }
  ROVER_RETURN_IF_ERROR(CheckRange("rocker_pivot_x", rocker_pivot_x, -5.0, 5.0, "m"));
  if (!(rocker_pivot_x > bogie_pivot_x && rocker_pivot_x < front_wheel_x)) {
    return InvalidArgument(Describe("rocker_pivot_x", rocker_pivot_x, "m") + " must lie between " +
                           Ref("bogie_pivot_x", bogie_pivot_x) + " and " +
                           Ref("front_wheel_x", front_wheel_x));
  }
  ROVER_RETURN_IF_ERROR(CheckRange("rocker_pivot_y", rocker_pivot_y, 0.0, half_track, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("rocker_pivot_z", rocker_pivot_z, wheel_radius, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("bogie_pivot_z", bogie_pivot_z, wheel_radius, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("rocker_limit", rocker_limit, 0.01, 1.5, "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("bogie_limit", bogie_limit, 0.01, 1.5, "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckAllInRange("body_size", Span(body_size), Bounds::Closed(0.01, 10), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckAllInRange("body_centre", Span(body_centre), Bounds::Closed(-10, 10), "m"));
  if (!(BellyClearance() > 0.0)) {
    return InvalidArgument("body_centre: the body's underside (z = " +
                           FormatNumber(BellyClearance()) + " m) must be above the ground plane");
  }
  ROVER_RETURN_IF_ERROR(
      CheckAllInRange("imu_position", Span(imu_position), Bounds::Closed(-10, 10), "m"));
  ROVER_RETURN_IF_ERROR(mast.Validate());
  ROVER_RETURN_IF_ERROR(navcam.Validate("navcam"));
  ROVER_RETURN_IF_ERROR(front_hazcam.Validate("front_hazcam"));
  ROVER_RETURN_IF_ERROR(rear_hazcam.Validate("rear_hazcam"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_steer_angle", max_steer_angle / kDegree,
                                   Bounds{0.0, 90.0, true, true}, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange("min_turn_radius", min_turn_radius, 0.1, 100.0, "m"));
  if (!(min_turn_radius > half_track)) {
    return InvalidArgument(Describe("min_turn_radius", min_turn_radius, "m") +
                           " must exceed the largest wheel |y|, " + Ref("half_track", half_track));
  }
  ROVER_RETURN_IF_ERROR(
      CheckRange("max_wheel_speed", max_wheel_speed, Bounds::OpenLow(0.0, 5.0), "m/s"));
  // Steering the corner wheels need (steer angles atan2(k (x - x_m), 1 - k y), dl/locomotion's
  // ackermann.hpp): the inner corner on the tightest arc, and tangent to the turn-in-place circle.
  const double lever = std::max(front_wheel_x - middle_wheel_x, middle_wheel_x - rear_wheel_x);
  const std::pair<double, const char*> needs[] = {
      {std::atan2(lever, min_turn_radius - half_track), "on the tightest arc (min_turn_radius)"},
      {std::atan2(lever, half_track), "to turn in place"}};
  for (const auto& [angle, what] : needs) {
    if (angle > max_steer_angle) {
      return InvalidArgument(Describe("max_steer_angle", max_steer_angle / kDegree, "deg") +
                             " is below the " + FormatNumber(angle / kDegree, 3) +
                             " deg the inner corner wheels need " + what);
    }
  }
  return Status::Ok();
}

Eigen::Vector3d RoverDescription::WheelCentre(int wheel) const {
  ROVER_DEMAND(wheel >= 0 && wheel < kNumWheels);
  const double x[3] = {front_wheel_x, middle_wheel_x, rear_wheel_x};
  const double y = SideOfWheel(wheel) == kLeft ? half_track : -half_track;
  return Eigen::Vector3d(x[wheel % 3], y, wheel_radius);
}

Eigen::Vector3d RoverDescription::RockerPivot(int side) const {
  ROVER_DEMAND(side == kLeft || side == kRight);
  return Eigen::Vector3d(rocker_pivot_x, side == kLeft ? rocker_pivot_y : -rocker_pivot_y,
                         rocker_pivot_z);
}

Eigen::Vector3d RoverDescription::BogiePivot(int side) const {
  ROVER_DEMAND(side == kLeft || side == kRight);
  return Eigen::Vector3d(bogie_pivot_x, side == kLeft ? half_track : -half_track, bogie_pivot_z);
}

Footprint RoverDescription::GroundFootprint() const {
  // The wheels, straight ahead.
  Footprint f{rear_wheel_x - wheel_radius, front_wheel_x + wheel_radius,
              -(half_track + 0.5 * wheel_width), half_track + 0.5 * wheel_width};
  auto include = [&f](double x, double y) {
    f.min_x = std::min(f.min_x, x);
    f.max_x = std::max(f.max_x, x);
    f.min_y = std::min(f.min_y, y);
    f.max_y = std::max(f.max_y, y);
  };
  const Eigen::Vector3d half_body = 0.5 * body_size;
  include(body_centre.x() - half_body.x(), body_centre.y() - half_body.y());
  include(body_centre.x() + half_body.x(), body_centre.y() + half_body.y());
  include(mast.pan_joint.x(), mast.pan_joint.y());
  for (const StereoMount* m : {&front_hazcam, &rear_hazcam}) {
    for (int side : {kLeft, kRight}) {
      const Eigen::Vector3d c = m->CameraCentre(side);
      include(c.x(), c.y());
    }
  }
  return f;
}

std::vector<ContactPart> RoverDescription::ContactParts() const {
  std::vector<ContactPart> parts;
  static const char* const kWheelName[kNumWheels] = {"wheel_lf", "wheel_lm", "wheel_lr",
                                                     "wheel_rf", "wheel_rm", "wheel_rr"};
  const double wheel_reach = std::hypot(wheel_radius, 0.5 * wheel_width);
  for (int w = 0; w < kNumWheels; ++w) {
    ContactPart p;
    p.name = kWheelName[w];
    p.is_disc = true;
    p.centre = WheelCentre(w).head<2>();
    p.radius = wheel_reach;
    parts.push_back(p);
  }
  const double hw = 0.5 * wheel_width;
  // The rocker link from its pivot to the front steering joint, where it leaves the wheel disc.
  const double front_joint_z = wheel_radius + steer_height;
  const double leave_x = front_wheel_x - wheel_reach;
  const double run = front_wheel_x - rocker_pivot_x;
  const double frac = run > 0.0 ? std::clamp((leave_x - rocker_pivot_x) / run, 0.0, 1.0) : 1.0;
  const double rocker_clearance = rocker_pivot_z + frac * (front_joint_z - rocker_pivot_z);
  for (int side : {kLeft, kRight}) {
    const double y = side == kLeft ? half_track : -half_track;
    const char* tag = side == kLeft ? "l" : "r";
    ContactPart bogie;
    bogie.name = std::string("bogie_") + tag;
    bogie.min = {rear_wheel_x, y - hw};
    bogie.max = {middle_wheel_x, y + hw};
    parts.push_back(bogie);
    ContactPart rocker;
    rocker.name = std::string("rocker_") + tag;
    rocker.min = {middle_wheel_x, y - hw};
    rocker.max = {front_wheel_x, y + hw};
    rocker.clearance = rocker_clearance;
    parts.push_back(rocker);
  }
  ContactPart body;
  body.name = "body";
  const Eigen::Vector3d half_body = 0.5 * body_size;
  body.min = {body_centre.x() - half_body.x(), body_centre.y() - half_body.y()};
  body.max = {body_centre.x() + half_body.x(), body_centre.y() + half_body.y()};
  body.clearance = BellyClearance();
  parts.push_back(body);
  return parts;
}

TurnCircle RoverDescription::TurnInPlaceCircle() const {
  TurnCircle c;
  c.centre = TurnCentre();
  // Corner wheels: any steering angle, i.e. a disc about the wheel centre.
  const double wheel_reach = std::hypot(wheel_radius, 0.5 * wheel_width);
  for (int wheel : kSteeredWheel) {
    const Eigen::Vector2d w = WheelCentre(wheel).head<2>();
    c.radius = std::max(c.radius, (w - c.centre).norm() + wheel_reach);
  }
  // Middle wheels (never steered) and the body: their rectangles.
  const double hw = 0.5 * wheel_width;
  c.radius = std::max(
      c.radius, FarthestCorner(c.centre, middle_wheel_x - wheel_radius,
                               middle_wheel_x + wheel_radius, -half_track - hw, half_track + hw));
  const Eigen::Vector3d half_body = 0.5 * body_size;
  c.radius = std::max(
      c.radius,
      FarthestCorner(c.centre, body_centre.x() - half_body.x(), body_centre.x() + half_body.x(),
                     body_centre.y() - half_body.y(), body_centre.y() + half_body.y()));
  // Whatever else the footprint holds (mast, camera mounts) as points.
  c.radius = std::max(c.radius, (mast.pan_joint.head<2>() - c.centre).norm());
  for (const StereoMount* m : {&front_hazcam, &rear_hazcam}) {
    for (int side : {kLeft, kRight}) {
      c.radius = std::max(c.radius, (m->CameraCentre(side).head<2>() - c.centre).norm());
    }
  }
  return c;
}

Eigen::Isometry3d RoverDescription::NavcamPose(double pan, double tilt) const {
  return mast.HeadPose(pan, tilt) * navcam.Pose();
}


std::vector<KeepOutBox> RoverDescription::ArmKeepOut() const {
  std::vector<KeepOutBox> out;
  const Eigen::Vector3d half_body = 0.5 * body_size;
  out.push_back({"body", body_centre - half_body, body_centre + half_body});
  // The front HAZCAM pair's housing: 6 cm deep, 8 cm tall, the baseline plus 6 cm wide.
  const Eigen::Vector3d hazcam_half(0.03, 0.5 * front_hazcam.baseline + 0.03, 0.04);
  out.push_back({"front_hazcam", front_hazcam.position - hazcam_half,
                 front_hazcam.position + hazcam_half});
  // The mast column, 10 cm square, from the pan joint up to the head.
  out.push_back({"mast", mast.pan_joint - Eigen::Vector3d(0.05, 0.05, 0.0),
                 mast.pan_joint + Eigen::Vector3d(0.05, 0.05, mast.head_height)});
  for (int w = 0; w < kNumWheels; ++w) {
    const Eigen::Vector3d c = WheelCentre(w);
    const Eigen::Vector3d half(wheel_radius, 0.5 * wheel_width, wheel_radius);
    out.push_back({std::string("wheel_") + WheelName(w), c - half, c + half});
  }
  return out;
}

Status RoverDescription::CheckArmPose(const ArmAngles& q) const {
  const ArmPoints p = arm.Forward(q);
  const double need = arm.link_radius + arm.clearance;
  struct Link {
    const char* name;
    Eigen::Vector3d a, b;
    bool ground;
  };
  const Link links[] = {{"upper arm", p.shoulder, p.elbow, true},
                        {"forearm", p.elbow, p.wrist, true},
                        {"instrument", p.wrist, p.face, false}};
  const std::vector<KeepOutBox> boxes = ArmKeepOut();
  for (const Link& l : links) {
    const int n = std::max(2, static_cast<int>(std::ceil((l.b - l.a).norm() / 0.01)) + 1);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = l.a + (l.b - l.a) * (static_cast<double>(i) / (n - 1));
      if (l.ground && x.z() < need) {
        return FailedPrecondition(std::string("the arm's ") + l.name + " would be " +
                                  FormatNumber(x.z()) + " m above the ground plane (needs " +
                                  FormatNumber(need) + ")");
      }
      for (const KeepOutBox& box : boxes) {
        const double d = box.DistanceTo(x);
        if (d < need) {
          return FailedPrecondition(std::string("the arm's ") + l.name + " would come " +
                                    FormatNumber(d) + " m from the rover's " + box.name +
                                    " (needs " + FormatNumber(need) + ")");
        }
      }
    }
  }
  return Status::Ok();
}

Status RoverDescription::CheckArmMove(const ArmAngles& from, const ArmAngles& to) const {
  double largest = 0.0;
  for (int j = 0; j < kArmJoints; ++j) {
    const auto k = static_cast<std::size_t>(j);
    largest = std::max(largest, std::abs(to[k] - from[k]));
  }
  const int steps = std::max(1, static_cast<int>(std::ceil(largest / arm.check_step)));
  for (int i = 0; i <= steps; ++i) {
    const double s = static_cast<double>(i) / steps;
    ArmAngles q;
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = from[k] + s * (to[k] - from[k]);
    const Status st = CheckArmPose(q);
    if (!st.ok()) {
      return FailedPrecondition("arm move refused at " + FormatNumber(100.0 * s) +
                                " % of the way: " + st.message());
    }
  }
  return Status::Ok();
}

}  // namespace rover::hwconfig
