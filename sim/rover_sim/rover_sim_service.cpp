// rover-sim: the simulated rover and Mars surface, standing in for the hardware. Binds the
// SimEngine (world + Simbody rover + sensors) to topics:
//   in:  hw/motor_goals, hw/camera_request, sim/control
//   out: sim/clock, hw/motor_telemetry, hw/suspension_pots, hw/imu, hw/sun_sensor,
//        hw/camera_frame, sim/truth (judge and tests only)
// Pacing: `sim.real_time_factor` simulated seconds per wall second, 0 = as fast as it can.
// Its run clock is its own simulated time; it never follows sim/clock itself.
// See docs/services/rover-sim.md.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "rover/base/log.hpp"
#include "rover/runtime/service.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"
#include "rover/sim/rover_sim/sim_engine.hpp"

namespace {
using rover::Duration;
using rover::Status;
namespace dds = rover::dds;
namespace hw = rover::hw;

// Lock-step: smallest lead (the services acknowledge every 25 ms of simulated time), and how
// long (wall) a service may go without acknowledging before the simulator stops waiting for it.
constexpr double kMinLockstepLeadS = 0.05;
constexpr double kAckStallS = 2.0;

// Integration time of the sensor model's relative exposure 1 (MER NAVCAM exposures are tens to
// hundreds of milliseconds in daylight).
constexpr double kExposureUnitUs = 100000.0;

void ToIdl(const Eigen::Isometry3d& p, rover_Pose3* out) {
  const Eigen::Quaterniond q(p.linear());
  out->position = {p.translation().x(), p.translation().y(), p.translation().z()};
  out->orientation = {q.w(), q.x(), q.y(), q.z()};
}

class RoverSim final : public rover::Service {
 public:
  RoverSim() : Service("rover-sim") {}

  void DeclareParameters(rover::ParamSet& p) override {
    rover::sim::rover_sim::SimEngine::DeclareParams(p);
    p.Declare("sim.real_time_factor", 1.0,
              "simulated seconds per wall second; 0 = as fast as possible").Range(0.0, 1000.0);
    p.Declare("sim.start_paused", false, "wait for a SIM_RESUME on sim/control before running");
    p.Declare("sim.lockstep_lead_s", 0.0,
              "[s] run at most this far ahead of the slowest service's sim/clock_ack (0 = free "
              "running); a service silent for 2 s of wall time is not waited for")
        .Range(0.0, 10.0);
    p.Declare("camera.image_size", 1024, "[px] side of the rendered camera images (MER: 1024)")
        .Range(64, 2048);
    p.Declare("camera.render_seed", 1, "seed of the rendered textures and image noise").Min(0);
  }

  Status ValidateParameters(const rover::ParamSet& p) const override {
    const double lead = p.GetDouble("sim.lockstep_lead_s");
    if (lead > 0.0 && lead < kMinLockstepLeadS) {
      return rover::InvalidArgument("sim.lockstep_lead_s: " + std::to_string(lead) +
                                    " s is below the services' acknowledgement granularity; use 0 "
                                    "(free running) or at least " +
                                    std::to_string(kMinLockstepLeadS) + " s");
    }
    return Status::Ok();
  }

  Status OnConfigure(rover::ServiceContext& ctx, const rover::ParamSet& p) override {
    auto engine = rover::sim::rover_sim::SimEngine::Create(p);
    if (!engine.ok()) return engine.status();
    engine_ = std::move(*engine);
    rtf_ = p.GetDouble("sim.real_time_factor");
    image_size_ = static_cast<int>(p.GetInt("camera.image_size"));
    render_seed_ = static_cast<std::uint64_t>(p.GetInt("camera.render_seed"));
    cameras_ = rover::sim::render::DefaultStereoCameras(image_size_, engine_->rover());
    terrain_ = std::make_shared<const rover::sim::terrain::Terrain>(engine_->world().terrain);
    paused_ = p.GetBool("sim.start_paused");
    lockstep_lead_s_ = p.GetDouble("sim.lockstep_lead_s");
    ctx_ = &ctx;
    ROVER_RETURN_IF_ERROR(Make(ctx, "sim/clock", &clock_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "sim/truth", &truth_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/motor_telemetry", &telemetry_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/suspension_pots", &pots_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/imu", &imu_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/sun_sensor", &sun_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/camera_frame", &frame_w_));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_CameraRequest>(
        "hw/camera_request", [this](const dds::Sample<rover_hw_CameraRequest>& s) { OnCamera(s.data()); }));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MotorGoals>(
        "hw/motor_goals", [this](const dds::Sample<rover_hw_MotorGoals>& s) { OnGoals(s.data()); }));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_sim_Control>(
        "sim/control", [this](const dds::Sample<rover_sim_Control>& s) { OnControl(s.data()); }));
    if (lockstep_lead_s_ > 0.0) {
      ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_sim_ClockAck>(
          "sim/clock_ack", [this](const dds::Sample<rover_sim_ClockAck>& s) { OnAck(s.data()); }));
    }
    ctx.executor().SetWork([this] { return Work(); });
    rover::log::Info("world ready",
                     {{"rocks", engine_->world().terrain.rocks.size()},
                      {"start_x", engine_->world().start_x}, {"start_y", engine_->world().start_y},
                      {"real_time_factor", rtf_}, {"paused", paused_}});
    return Status::Ok();
  }

  Status OnActivate(rover::ServiceContext&) override {
    Anchor();
    PublishClock();
    return Status::Ok();
  }

 private:
  template <class T>
  Status Make(rover::ServiceContext& ctx, const char* topic, dds::Writer<T>* w) {
    auto r = ctx.MakeWriter<T>(topic);
    if (!r.ok()) return r.status();
    *w = std::move(*r);
    return Status::Ok();
  }

  void Anchor() {
    wall_anchor_ = rover::MonotonicNow();
    sim_anchor_ = engine_->time();
  }

  rover::Time SimTime() const { return rover::Time::FromSeconds(engine_->time()); }

  void Stamp(rover_Header& h, const char* frame) {
    ctx_->Stamp(h, frame);
    h.stamp_ns = SimTime().ns;  // the simulator's run clock is its own simulated time
  }

  void PublishClock() {
    rover_sim_Clock c{};
    Stamp(c.header, "sim");
    c.sim_time_ns = SimTime().ns;
    const double wall = rover::ToSeconds(rover::MonotonicNow() - wall_anchor_);
    c.real_time_factor = wall > 0 ? (engine_->time() - sim_anchor_) / wall : 0.0;
    c.paused = paused_;
    (void)clock_w_.Write(c);
  }

  // Called by the executor between polls: one step when one is due.
  Duration Work() {
    if (paused_) {
      // Keep late joiners' clocks valid while paused.
      if (rover::MonotonicNow() - last_paused_clock_ > rover::Seconds(0.2)) {
        PublishClock();
        last_paused_clock_ = rover::MonotonicNow();
      }
      return std::chrono::milliseconds(50);
    }
    if (lockstep_lead_s_ > 0.0 && !StackKeepsUp()) return std::chrono::microseconds(200);
    if (rtf_ > 0) {
      const rover::Time due = wall_anchor_ + rover::Seconds((engine_->time() - sim_anchor_) / rtf_);
      const rover::Time now = rover::MonotonicNow();
      if (now < due) return due - now;
    }
    auto out = engine_->Step();
    if (!out.ok()) {
      rover::log::Error("simulation step failed; pausing", {{"error", out.status().message()}});
      ctx_->SetHealth(rover_HEALTH_FAILED, out.status().message());
      paused_ = true;
      return std::chrono::milliseconds(50);
    }
    Publish(*out);
    return Duration::zero();
  }

  // Lock-step: a service's acknowledged sim time, and when (wall) it last moved.
  struct AckState {
    std::int64_t sim_time_ns = 0;
    rover::Time changed;
    bool waited_on = true;  // false while it is considered gone (silent too long)
  };

  void OnAck(const rover_sim_ClockAck& a) {
    const std::string name(a.service);
    if (name == ctx_->name()) return;
    AckState& s = acks_[name];
    if (a.sim_time_ns != s.sim_time_ns || s.changed.ns == 0) {
      s.sim_time_ns = a.sim_time_ns;
      s.changed = rover::MonotonicNow();
      if (!s.waited_on) {
        rover::log::Info("lock-step: service is keeping up again", {{"service", name}});
        s.waited_on = true;
      }
    }
  }

  // True when every live service has acknowledged sim time within the lead of the next step.
  bool StackKeepsUp() {
    const std::int64_t need = rover::Time::FromSeconds(engine_->time() - lockstep_lead_s_).ns;
    const rover::Time now = rover::MonotonicNow();
    for (auto& [name, s] : acks_) {
      if (!s.waited_on || s.sim_time_ns >= need) continue;
      if (now - s.changed > rover::Seconds(kAckStallS)) {
        rover::log::Warn("lock-step: not waiting for a service that stopped acknowledging",
                         {{"service", name},
                          {"acknowledged_s", rover::Time{s.sim_time_ns}.seconds()},
                          {"sim_time_s", engine_->time()}});
        s.waited_on = false;
        continue;
      }
      return false;
    }
    return true;
  }

  void Publish(const rover::sim::rover_sim::StepOutput& o) {
    PublishClock();
    const auto& s = o.sensors;
    if (s.motor_telemetry) {
      rover_hw_MotorTelemetry m{};
      Stamp(m.header, "rover");
      m.command_id = s.motor_telemetry->command_id;
      for (int i = 0; i < hw::kNumMotors; ++i) {
        const auto& r = s.motor_telemetry->motors[static_cast<std::size_t>(i)];
        m.motors[i] = {r.position, r.velocity, r.current_adc, r.temperature_adc, r.flags};
      }
      (void)telemetry_w_.Write(m);
    }
    if (s.suspension_pots) {
      rover_hw_SuspensionPots m{};
      Stamp(m.header, "rover");
      for (int i = 0; i < hw::kNumPots; ++i) m.adc[i] = s.suspension_pots->adc[static_cast<std::size_t>(i)];
      (void)pots_w_.Write(m);
    }
    if (s.imu) {
      rover_hw_ImuRaw m{};
      Stamp(m.header, "imu");
      for (int i = 0; i < 3; ++i) {
        m.gyro[i] = s.imu->gyro[static_cast<std::size_t>(i)];
        m.accel[i] = s.imu->accel[static_cast<std::size_t>(i)];
      }
      m.temperature = s.imu->temperature;
      m.status = s.imu->status;
      (void)imu_w_.Write(m);
    }
    if (s.sun_sensor) {
      rover_hw_SunSensorRaw m{};
      Stamp(m.header, "sun_sensor");
      m.spot[0] = s.sun_sensor->spot[0];
      m.spot[1] = s.sun_sensor->spot[1];
      m.intensity = s.sun_sensor->intensity;
      (void)sun_w_.Write(m);
    }
    if (o.truth) {
      const auto& t = *o.truth;
      rover_sim_Truth m{};
      Stamp(m.header, "site");
      ToIdl(t.pose, &m.pose);
      m.velocity = {t.velocity_site.x(), t.velocity_site.y(), t.velocity_site.z()};
      m.angular_velocity = {t.angular_velocity_body.x(), t.angular_velocity_body.y(),
                            t.angular_velocity_body.z()};
      for (int i = 0; i < 6; ++i) {
        const auto& w = t.wheels[static_cast<std::size_t>(i)];
        m.wheels[i] = {w.slip_ratio, w.normal_force_n, w.in_contact, w.sinkage_m};
      }
      for (int i = 0; i < 2; ++i) {
        m.rocker_angle[i] = t.rocker_angle[i];
        m.bogie_angle[i] = t.bogie_angle[i];
      }
      m.odometer = t.odometer;
      m.rock_contacts = t.rock_contacts;
      m.max_contact_rock_height = t.max_contact_rock_height;
      (void)truth_w_.Write(m);
    }
  }

  void OnGoals(const rover_hw_MotorGoals& in) {
    hw::MotorGoals g;
    g.stamp_ns = in.header.stamp_ns;
    g.command_id = in.command_id;
    for (int i = 0; i < hw::kNumMotors; ++i) {
      const auto& src = in.goals[i];
      auto& dst = g.goals[static_cast<std::size_t>(i)];
      if (src.mode < rover_hw_MOTOR_IDLE || src.mode > rover_hw_MOTOR_BRAKE) {
        rover::log::Warn("motor goal with an unknown mode ignored", {{"motor", i}, {"mode", static_cast<int>(src.mode)}});
        continue;
      }
      dst.mode = static_cast<hw::MotorMode>(src.mode);
      dst.position = src.position;
      dst.velocity = src.velocity;
      dst.current_limit_ma = src.current_limit_ma;
    }
    const Status s = engine_->ApplyMotorGoals(g);
    if (!s.ok()) rover::log::Warn("motor goal refused by the controller", {{"error", s.message()}});
  }

  void OnControl(const rover_sim_Control& c) {
    switch (c.command) {
      case rover_sim_SIM_PAUSE:
        paused_ = true;
        break;
      case rover_sim_SIM_RESUME:
        paused_ = false;
        Anchor();
        break;
      case rover_sim_SIM_RESET: {
        const Status s = engine_->Reset();
        if (!s.ok()) rover::log::Error("reset failed", {{"error", s.message()}});
        Anchor();
        break;
      }
      case rover_sim_SIM_SET_SPEED:
        if (!(c.real_time_factor >= 0 && c.real_time_factor <= 1000)) {
          rover::log::Warn("sim/control: real_time_factor out of range [0, 1000]; ignored",
                           {{"value", c.real_time_factor}});
          break;
        }
        rtf_ = c.real_time_factor;
        Anchor();
        break;
      default:
        rover::log::Warn("sim/control: unknown command ignored", {{"command", static_cast<int>(c.command)}});
    }
    PublishClock();
    rover::log::Info("control", {{"command", static_cast<int>(c.command)}, {"paused", paused_},
                                 {"real_time_factor", rtf_}, {"sim_time", engine_->time()}});
  }

  static const char* CameraName(rover_CameraId id) {
    switch (id) {
      case rover_CAMERA_NAVCAM: return "navcam";
      case rover_CAMERA_FRONT_HAZCAM: return "front_hazcam";
      case rover_CAMERA_REAR_HAZCAM: return "rear_hazcam";
    }
    return nullptr;
  }

  // Takes a stereo pair now, as on MER: the rover holds still (simulated time does not advance
  // while the images are made).
  void OnCamera(const rover_hw_CameraRequest& req) {
    const char* name = CameraName(req.camera);
    if (name == nullptr) {
      rover::log::Warn("camera request for a camera that does not exist; ignored",
                       {{"camera", static_cast<int>(req.camera)}, {"request_id", req.request_id}});
      return;
    }
    if (!renderer_) {
      rover::sim::render::RenderOptions o;
      o.seed = render_seed_;
      auto r = rover::sim::render::Renderer::Create(terrain_, o);
      if (!r.ok()) {
        rover::log::Error("cannot render camera images", {{"error", r.status().message()}});
        ctx_->SetHealth(rover_HEALTH_DEGRADED, "cameras unavailable: " + r.status().message());
        return;
      }
      renderer_ = std::move(*r);
    }
    // The true sun; shadows are recomputed only when it has moved noticeably (0.5 deg).
    const Eigen::Vector3d sun = engine_->SunDirectionSite();
    if (!sun_set_ || std::acos(std::clamp(sun.dot(last_sun_), -1.0, 1.0)) > 0.5 * M_PI / 180) {
      rover::sim::render::SunOptions so;
      so.azimuth_deg = std::atan2(sun.y(), sun.x()) * 180.0 / M_PI;
      // Below the horizon the cameras would see nothing; light the scene from just above it.
      so.elevation_deg = std::max(2.0, std::asin(std::clamp(sun.z(), -1.0, 1.0)) * 180.0 / M_PI);
      if (renderer_->SetSun(so).ok()) {
        last_sun_ = sun;
        sun_set_ = true;
      }
    }
    auto def = rover::sim::render::FindStereoCamera(cameras_, name);
    if (!def.ok()) return;
    const auto readings = engine_->physics().Readings();
    rover::sim::render::MastState mast{readings.joint_angle_rad[rover::hw::kMastPan],
                               readings.joint_angle_rad[rover::hw::kMastTilt]};
    auto spec = rover::sim::render::MakeCameraPairSpec(*def, mast, engine_->rover().mast);
    if (!spec.ok()) {
      rover::log::Error("camera pair", {{"error", spec.status().message()}});
      return;
    }
    // Exposure: the sensor model's relative exposure 1 (radiance 1 fills the well) is
    // kExposureUnitUs of integration time; exposure_us 0 asks for auto-exposure.
    rover::sim::render::SensorOptions sensor = renderer_->options().sensor;
    sensor.auto_exposure = req.exposure_us == 0;
    if (req.exposure_us != 0) sensor.exposure = req.exposure_us / kExposureUnitUs;
    if (auto st = renderer_->SetSensor(sensor); !st.ok()) {
      rover::log::Warn("hw/camera_request: exposure rejected; using auto-exposure",
                       {{"exposure_us", req.exposure_us}, {"error", st.message()}});
      sensor.auto_exposure = true;
      (void)renderer_->SetSensor(sensor);
    }
    const rover::Time t0 = rover::MonotonicNow();
    auto images = renderer_->RenderStereoPair(readings.chassis.pose_site, *spec, ++frames_);
    if (!images.ok()) {
      rover::log::Error("rendering failed", {{"error", images.status().message()}});
      return;
    }
    rover_hw_CameraFrame f{};
    Stamp(f.header, name);
    f.request_id = req.request_id;
    f.camera = req.camera;
    f.exposure_us = static_cast<uint32_t>(
        std::clamp(std::lround(images->left.exposure * kExposureUnitUs), 1L, 4000000000L));
    f.width = static_cast<uint16_t>(images->left.image.cols);
    f.height = static_cast<uint16_t>(images->left.image.rows);
    const cv::Mat& l = images->left.image;
    const cv::Mat& r = images->right.image;
    f.left._buffer = const_cast<uint8_t*>(l.ptr<uint8_t>());
    f.left._length = f.left._maximum = static_cast<uint32_t>(l.total());
    f.right._buffer = const_cast<uint8_t*>(r.ptr<uint8_t>());
    f.right._length = f.right._maximum = static_cast<uint32_t>(r.total());
    (void)frame_w_.Write(f);
    rover::log::Info("stereo pair", {{"camera", name}, {"request_id", req.request_id},
                                     {"render_ms", rover::ToSeconds(rover::MonotonicNow() - t0) * 1e3},
                                     {"sim_time", engine_->time()}});
  }

  std::unique_ptr<rover::sim::rover_sim::SimEngine> engine_;
  double lockstep_lead_s_ = 0.0;
  std::map<std::string, AckState> acks_;
  std::shared_ptr<const rover::sim::terrain::Terrain> terrain_;
  std::unique_ptr<rover::sim::render::Renderer> renderer_;
  std::vector<rover::sim::render::StereoCameraDefinition> cameras_;
  int image_size_ = 1024;
  std::uint64_t render_seed_ = 1;
  std::uint64_t frames_ = 0;
  Eigen::Vector3d last_sun_ = Eigen::Vector3d::UnitZ();
  bool sun_set_ = false;
  dds::Writer<rover_hw_CameraFrame> frame_w_;
  rover::ServiceContext* ctx_ = nullptr;
  double rtf_ = 1.0;
  bool paused_ = false;
  rover::Time wall_anchor_{0}, last_paused_clock_{0};
  double sim_anchor_ = 0;
  dds::Writer<rover_sim_Clock> clock_w_;
  dds::Writer<rover_sim_Truth> truth_w_;
  dds::Writer<rover_hw_MotorTelemetry> telemetry_w_;
  dds::Writer<rover_hw_SuspensionPots> pots_w_;
  dds::Writer<rover_hw_ImuRaw> imu_w_;
  dds::Writer<rover_hw_SunSensorRaw> sun_w_;
};

}  // namespace

int main(int argc, char** argv) {
  // The simulator is the source of simulated time; its own timers run on wall time.
  setenv("ROVER_CLOCK", "wall", 1);
  RoverSim service;
  return rover::RunServiceMain(service, argc, argv);
}
