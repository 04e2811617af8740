#include "rover/runtime/topic_catalog.hpp"

#include "rover/idl/types.hpp"

namespace rover::dds {

const std::vector<TopicInfo>& TopicCatalog() {
  using P = QosProfile;
  static const std::vector<TopicInfo> kCatalog = {
      // hw/: simulated hardware bus (simulator <-> DDL)
      {"hw/motor_goals", "rover_hw_MotorGoals", P::kCommand},
      {"hw/motor_telemetry", "rover_hw_MotorTelemetry", P::kStream},
      {"hw/suspension_pots", "rover_hw_SuspensionPots", P::kStream},
      {"hw/arm_contact", "rover_hw_ArmContact", P::kStream},
      {"hw/imu", "rover_hw_ImuRaw", P::kStream},
      {"hw/sun_sensor", "rover_hw_SunSensorRaw", P::kStream},
      {"hw/camera_request", "rover_hw_CameraRequest", P::kCommand},
      {"hw/camera_frame", "rover_hw_CameraFrame", P::kCommand},
      {"hw/mi_request", "rover_hw_MiRequest", P::kCommand},
      {"hw/mi_frame", "rover_hw_MiFrame", P::kCommand},
      // ddl/: engineering units (DDL <-> DL)
      {"ddl/motor_command", "rover_ddl_MotorCommand", P::kCommand},
      {"ddl/motor_status", "rover_ddl_MotorStatus", P::kLatched},
      {"ddl/joint_state", "rover_ddl_JointState", P::kStream},
      {"ddl/imu", "rover_ddl_Imu", P::kStream},
      {"ddl/sun_sensor", "rover_ddl_SunSensor", P::kState},
      {"ddl/camera_request", "rover_ddl_StereoRequest", P::kCommand},
      {"ddl/stereo_frame", "rover_ddl_StereoFrame", P::kCommand},
      {"ddl/mi_request", "rover_ddl_MiRequest", P::kCommand},
      {"ddl/mi_frame", "rover_ddl_MiFrame", P::kCommand},
      // dl/: rover-level state and primitives (DL <-> APL)
      {"dl/drive_command", "rover_dl_DriveCommand", P::kCommand},
      {"dl/drive_status", "rover_dl_DriveStatus", P::kLatched},
      {"dl/pose", "rover_dl_PoseEstimate", P::kState},
      {"dl/pose_odometry", "rover_dl_PoseEstimate", P::kState},
      {"dl/relative_pose", "rover_dl_RelativePose", P::kCommand},
      {"dl/estimator_event", "rover_dl_EstimatorEvent", P::kCommand},
      {"dl/vo_command", "rover_dl_VoCommand", P::kLatched},
      {"dl/range_request", "rover_dl_RangeRequest", P::kCommand},
      {"dl/range_image", "rover_dl_RangeImage", P::kState},
      {"dl/mast_command", "rover_dl_MastCommand", P::kCommand},
      {"dl/mast_status", "rover_dl_MastStatus", P::kLatched},
      {"dl/arm_command", "rover_dl_ArmCommand", P::kCommand},
      {"dl/arm_status", "rover_dl_ArmStatus", P::kLatched},
      // apl/: goals and decisions
      {"apl/mobility_command", "rover_apl_MobilityCommand", P::kCommand},
      {"apl/mobility_status", "rover_apl_MobilityStatus", P::kLatched},
      {"apl/goodness_map", "rover_apl_GoodnessMap", P::kState},
      {"apl/arc_votes", "rover_apl_ArcVotes", P::kStream},
      {"apl/plan", "rover_apl_Plan", P::kLatched},
      {"apl/rendezvous_command", "rover_apl_RendezvousCommand", P::kCommand},
      {"apl/rendezvous_status", "rover_apl_RendezvousStatus", P::kLatched},
      {"apl/sequence_command", "rover_apl_SequenceCommand", P::kCommand},
      {"apl/sequence_status", "rover_apl_SequenceStatus", P::kLatched},
      // sys/: platform
      {"sys/health", "rover_sys_Heartbeat", P::kState},
      {"sys/event", "rover_sys_Event", P::kCommand},
      {"sys/fault_control", "rover_sys_FaultControl", P::kCommand},
      {"sys/fault_event", "rover_sys_FaultEvent", P::kCommand},
      // sim/: simulator (sim/truth: judge and tests only)
      {"sim/clock", "rover_sim_Clock", P::kState},
      {"sim/clock_ack", "rover_sim_ClockAck", P::kState},
      {"sim/truth", "rover_sim_Truth", P::kStream},
      {"sim/control", "rover_sim_Control", P::kCommand},
  };
  return kCatalog;
}

std::optional<TopicInfo> FindTopic(std::string_view name) {
  for (const auto& t : TopicCatalog()) {
    if (t.name == name) return t;
  }
  return std::nullopt;
}

const dds_topic_descriptor_t* DescriptorForType(std::string_view type_name) {
  for (const auto& e : kTopicTypes) {
    if (type_name == e.type_name) return e.descriptor;
  }
  return nullptr;
}

}  // namespace rover::dds
