#include "rover/runtime/topic_access.hpp"

#include <algorithm>
#include <set>

#include "rover/runtime/topic_catalog.hpp"

namespace rover::dds {

const std::vector<RoleAccess>& RoleAccessTable() {
  static const std::vector<RoleAccess> kTable = [] {
    std::vector<RoleAccess> t = {
        // apl/
        {"apl-mobility", "mobility manager", true,
         {"apl/mobility_status", "apl/goodness_map", "apl/arc_votes", "dl/drive_command",
          "dl/mast_command", "dl/range_request", "dl/vo_command"},
         {"apl/mobility_command", "dl/drive_status", "dl/mast_status", "dl/pose",
          "dl/range_image", "dl/relative_pose"}},
        {"apl-rendezvous", "lander and science-target rendezvous", true,
         {"apl/rendezvous_status", "apl/mobility_command", "ddl/camera_request",
          "dl/mast_command", "dl/arm_command"},
         {"apl/rendezvous_command", "apl/mobility_status", "ddl/stereo_frame", "dl/mast_status",
          "dl/pose", "dl/arm_status"}},
        {"apl-sequencer", "command sequences", true,
         {"apl/sequence_status", "apl/mobility_command", "dl/mast_command",
          "apl/rendezvous_command", "dl/arm_command"},
         {"apl/sequence_command", "apl/mobility_status", "dl/mast_status", "dl/pose",
          "dl/relative_pose", "apl/rendezvous_status", "dl/arm_status"}},
        {"apl-smoke", "smoke set's application", true, {"apl/mobility_status"}, {"dl/pose"}},
        // ddl/
        {"ddl-camera", "camera driver", true,
         {"ddl/stereo_frame", "hw/camera_request", "ddl/mi_frame", "hw/mi_request"},
         {"ddl/camera_request", "ddl/joint_state", "hw/camera_frame", "ddl/mi_request",
          "hw/mi_frame"}},
        {"ddl-imu", "IMU driver", true, {"ddl/imu"}, {"hw/imu"}},
        {"ddl-joints", "encoder, potentiometer and contact-switch reader", true,
         {"ddl/joint_state"}, {"hw/motor_telemetry", "hw/suspension_pots", "hw/arm_contact"}},
        {"ddl-motor", "motor driver", true, {"ddl/motor_status", "hw/motor_goals"},
         {"ddl/motor_command", "hw/motor_telemetry"}},
        {"ddl-smoke", "smoke set's driver", true, {"ddl/imu"}, {}},
        {"ddl-sun-sensor", "sun-sensor driver", true, {"ddl/sun_sensor"}, {"hw/sun_sensor"}},
        // dl/
        {"dl-locomotion", "drive primitives", true, {"dl/drive_status", "ddl/motor_command"},
         {"dl/drive_command", "ddl/joint_state", "ddl/motor_status", "dl/pose"}},
        {"dl-arm", "instrument arm and microscopic imager", true,
         {"dl/arm_status", "ddl/motor_command", "ddl/mi_request"},
         {"dl/arm_command", "ddl/joint_state", "ddl/motor_status", "ddl/mi_frame"}},
        {"dl-mast", "mast pointing", true, {"dl/mast_status", "ddl/motor_command"},
         {"dl/mast_command", "ddl/joint_state", "ddl/motor_status", "dl/pose"}},
        {"dl-pose", "pose estimator", true,
         {"dl/pose", "dl/pose_odometry", "dl/estimator_event"},
         {"ddl/imu", "ddl/joint_state", "ddl/sun_sensor", "dl/relative_pose"}},
        {"dl-smoke", "smoke set's estimator", true, {"dl/pose"}, {"ddl/imu"}},
        {"dl-stereo", "stereo ranging", true, {"dl/range_image", "ddl/camera_request"},
         {"dl/range_request", "ddl/stereo_frame", "dl/pose"}},
        {"dl-vo", "visual odometry", true, {"dl/relative_pose", "ddl/camera_request"},
         {"dl/vo_command", "ddl/stereo_frame", "dl/pose"}},
        // the simulator
        {"rover-sim", "simulator", true,
         {"hw/motor_telemetry", "hw/suspension_pots", "hw/arm_contact", "hw/imu", "hw/sun_sensor",
          "hw/camera_frame", "hw/mi_frame", "sim/clock", "sim/truth"},
         {"hw/motor_goals", "hw/camera_request", "hw/mi_request", "sim/clock_ack",
          "sim/control"}},
        // operator tools
        {"rover-drive", "operator drive tool", false, {"dl/drive_command"},
         {"dl/drive_status", "sim/clock"}},
        // roverctl's participants
        {"scenario-runner", "roverctl run: runner, judge and recorder", false,
         {"sim/clock_ack", "sim/control", "dl/drive_command", "apl/mobility_command",
          "apl/rendezvous_command", "apl/sequence_command", "dl/mast_command",
          "dl/arm_command", "ddl/camera_request", "sys/fault_control"},
         {"*"}},
        {"sequence-operator", "roverctl seq", false, {"apl/sequence_command"},
         {"apl/sequence_status"}},
        {"recorder", "roverctl record", false, {}, {"*"}},
        {"replayer", "roverctl replay", false, {"*"}, {"sim/clock"}},
        {"fault-controller", "roverctl fault", false, {"sys/fault_control"},
         {"sys/fault_event"}},
        {"supervisor", "roverctl up", false, {}, {"sys/health"}},
        // benchmarks: their own topics only
        {"rover-dds-bench", "DDS benchmark (its bench/ topics)", false,
         {"bench/ping", "bench/pong", "bench/data"}, {"bench/ping", "bench/pong", "bench/data"}},
    };
    std::sort(t.begin(), t.end(),
              [](const RoleAccess& a, const RoleAccess& b) { return a.role < b.role; });
    return t;
  }();
  return kTable;
}

std::optional<RoleAccess> FindRole(std::string_view role) {
  for (const RoleAccess& r : RoleAccessTable()) {
    if (r.role == role) return r;
  }
  return std::nullopt;
}

namespace {

std::vector<std::string> Expand(const RoleAccess& r, const std::vector<std::string_view>& own,
                                 bool writes) {
  std::set<std::string> out;
  for (std::string_view t : own) {
    if (t == "*") {
      for (const TopicInfo& info : TopicCatalog()) out.emplace(info.name);
    } else {
      out.emplace(t);
    }
  }
  if (r.service) {
    if (writes) {
      for (std::string_view t : kServiceWrites) out.emplace(t);
    } else {
      for (std::string_view t : kServiceReads) out.emplace(t);
    }
  }
  return {out.begin(), out.end()};
}

}  // namespace

std::vector<std::string> TopicsWritten(std::string_view role) {
  const auto r = FindRole(role);
  return r ? Expand(*r, r->writes, true) : std::vector<std::string>{};
}

std::vector<std::string> TopicsRead(std::string_view role) {
  const auto r = FindRole(role);
  return r ? Expand(*r, r->reads, false) : std::vector<std::string>{};
}

}  // namespace rover::dds
