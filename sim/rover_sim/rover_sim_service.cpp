// rover-sim: the simulated rover and Mars surface, standing in for the hardware. Binds the
// DDS-free pieces of sim/rover_sim to topics:
//   SimEngine  (world + Simbody rover + sensors)  -> hw/motor_telemetry, hw/suspension_pots,
//              hw/imu, hw/sun_sensor, sim/truth (judge and tests only); <- hw/motor_goals
//   Pacer      (real-time factor, pause, lock-step on sim/clock_ack)   <- sim/control
//   CameraHead (rendered stereo pairs)            <- hw/camera_request -> hw/camera_frame
//   CameraHead (microscopic imager on the arm)    <- hw/mi_request -> hw/mi_frame
// and publishes sim/clock every step. Its run clock is its own simulated time; it never follows
// sim/clock itself. See docs/services/rover-sim.md.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "rover/base/clock.hpp"
#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/runtime/activity.hpp"
#include "rover/runtime/fault_control.hpp"
#include "rover/runtime/lockstep.hpp"
#include "rover/runtime/service.hpp"
#include "rover/sim/rover_sim/camera_head.hpp"
#include "rover/sim/rover_sim/pacer.hpp"
#include "rover/sim/rover_sim/sim_engine.hpp"
#include "rover/sim/rover_sim/truth_idl.hpp"

namespace {
using rover::Duration;
using rover::Status;
namespace dds = rover::dds;
namespace msg = rover::msg;
namespace rs = rover::sim::rover_sim;

class RoverSim final : public rover::Service {
 public:
  RoverSim() : Service("rover-sim") {}

  void DeclareParameters(rover::ParamSet& p) override {
    rs::SimEngine::DeclareParams(p);
    rover::DeclareParams<rs::PacerOptions>(p, "sim.");
    rover::DeclareParams<rs::CameraHeadOptions>(p, "camera.");
  }

  Status ValidateParameters(const rover::ParamSet& p) const override {
    ROVER_ASSIGN_OR_RETURN(const rs::PacerOptions pacing,
                           rover::ReadParams<rs::PacerOptions>(p, "sim."));
    if (pacing.lockstep_strict) {
      const double period = p.GetDouble("sim.period_s");
      const double steps = pacing.lockstep_quantum_s / period;
      if (std::abs(steps - std::round(steps)) > 1e-6 || std::round(steps) < 1) {
        return rover::InvalidArgument(
            "sim.lockstep_quantum_s: " + rover::FormatNumber(pacing.lockstep_quantum_s) +
            " s is not a whole number of sim.period_s (" + rover::FormatNumber(period) + " s)");
      }
    }
    return rover::ReadParams<rs::CameraHeadOptions>(p, "camera.").status();
  }

  Status OnConfigure(rover::ServiceContext& ctx, const rover::ParamSet& p) override {
    ROVER_ASSIGN_OR_RETURN(engine_, rs::SimEngine::Create(p));
    ROVER_ASSIGN_OR_RETURN(const rs::PacerOptions pacing,
                           rover::ReadParams<rs::PacerOptions>(p, "sim."));
    ROVER_ASSIGN_OR_RETURN(const rs::CameraHeadOptions camera,
                           rover::ReadParams<rs::CameraHeadOptions>(p, "camera."));
    pacer_.emplace(pacing);
    pacer_->set_self(ctx.name());
    stall_s_ = pacing.lockstep_stall_s;
    pipelined_ = pacing.lockstep_strict && pacing.lockstep_pipelined;
    steps_per_quantum_ =
        std::max<long>(1, std::lround(pacing.lockstep_quantum_s / p.GetDouble("sim.period_s")));
    camera_.emplace(camera,
                    std::make_shared<const rover::sim::terrain::Terrain>(engine_->world().terrain),
                    engine_->rover());
    ctx_ = &ctx;
    // Faults on the simulator's own endpoints (hw/*, sim/clock) are timed on the run clock it
    // makes, as every other service's are, not on the wall time it runs on.
    if (auto* faults = ctx.faults()) faults->UseClock(run_clock_, rover::Time{0});
    ROVER_RETURN_IF_ERROR(Make(ctx, "sim/clock", &clock_w_));
    if (pacing.lockstep_strict) {
      // Each lock-step service hears only the ticks it must serve (lockstep.hpp "idle").
      for (const auto& name : rs::Pacer::ParseServices(pacing.lockstep_services)) {
        ROVER_ASSIGN_OR_RETURN(auto w, dds::Writer<rover_sim_Clock>::CreateInPartition(
                                           ctx.participant(), "sim/clock",
                                           rover::dds::lockstep::ClockPartition(name)));
        service_clocks_.emplace_back(name, std::move(w));
      }
    }
    ROVER_RETURN_IF_ERROR(Make(ctx, "sim/truth", &truth_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/motor_telemetry", &telemetry_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/suspension_pots", &pots_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/arm_contact", &contact_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/imu", &imu_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/sun_sensor", &sun_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/camera_frame", &frame_w_));
    ROVER_RETURN_IF_ERROR(Make(ctx, "hw/mi_frame", &mi_w_));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MiRequest>(
        "hw/mi_request",
        [this](const dds::Sample<rover_hw_MiRequest>& s) { OnMicroscope(s.data()); }));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_CameraRequest>(
        "hw/camera_request",
        [this](const dds::Sample<rover_hw_CameraRequest>& s) { OnCamera(s.data()); }));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MotorGoals>(
        "hw/motor_goals", [this](const dds::Sample<rover_hw_MotorGoals>& s) { OnGoals(s.data()); }));
    ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_sim_Control>(
        "sim/control", [this](const dds::Sample<rover_sim_Control>& s) { OnControl(s.data()); }));
    if (pacer_->lockstep() || pacer_->strict()) {
      ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_sim_ClockAck>(
          "sim/clock_ack", [this](const dds::Sample<rover_sim_ClockAck>& s) { OnAck(s.data()); }));
    }
    ctx.executor().SetWork([this] { return Work(); });
    rover::log::Info("world ready", {{"rocks", engine_->world().terrain.rocks.size()},
                                     {"start_x", engine_->world().start_x},
                                     {"start_y", engine_->world().start_y},
                                     {"real_time_factor", pacer_->real_time_factor()},
                                     {"paused", pacer_->paused()},
                                     {"lockstep", pacer_->strict()     ? "strict"
                                                  : pacer_->lockstep() ? "lead"
                                                                       : "off"}});
    return Status::Ok();
  }

  Status OnActivate(rover::ServiceContext&) override {
    pacer_->Anchor(rover::MonotonicNow(), engine_->time());
    if (pacer_->strict()) StartQuantum();
    PublishClock();
    return Status::Ok();
  }

 private:
  template <class T>
  Status Make(rover::ServiceContext& ctx, const char* topic, dds::Writer<T>* w) {
    ROVER_ASSIGN_OR_RETURN(*w, ctx.MakeWriter<T>(topic));
    return Status::Ok();
  }

  // The simulator's run clock is its own simulated time.
  void Stamp(rover_Header& h, const char* frame) {
    ctx_->Stamp(h, frame);
    h.stamp_ns = rover::Time::FromSeconds(engine_->time()).ns;
  }

  void PublishClock(bool repeat = false) {
    rover_sim_Clock c{};
    Stamp(c.header, "sim");
    c.sim_time_ns = c.header.stamp_ns;
    c.real_time_factor = pacer_->MeasuredRealTimeFactor(rover::MonotonicNow(), engine_->time());
    c.paused = pacer_->paused();
    // Strict lock-step: the frontier, what every participant had written when this tick was
    // first published (its latest acknowledgement, of the tick before) and this simulator
    // itself (rover/runtime/lockstep.hpp). A repeat of the tick repeats it: acknowledgements
    // that came since may count samples written while serving this very tick.
    if (pacer_->strict()) {
      bool fresh = false;
      const auto& frontier = pacer_->FrontierFor(
          c.sim_time_ns, rover::dds::lockstep::WrittenBy(ctx_->participant().handle()), &fresh);
      if (fresh && pipelined_) rover::dds::lockstep::SetFrontier(frontier);  // own gated readers
      c.written._buffer = const_cast<std::uint64_t*>(frontier.data());
      c.written._length = c.written._maximum = static_cast<std::uint32_t>(frontier.size());
      c.written._release = false;
    }
    (void)clock_w_.Write(c);
    // Strict: to each service the tick is due for; a repeat (the simulator waits) to all.
    for (auto& [name, w] : service_clocks_) {
      if (pacer_->SendsTickTo(name, repeat)) (void)w.Write(c);
    }
  }

  // Strict lock-step: the quantum that starts now (at the barrier just published); its samples
  // carry the barrier as their tick (core/runtime lockstep.hpp).
  void StartQuantum() {
    const std::int64_t barrier = rover::Time::FromSeconds(engine_->time()).ns;
    pacer_->SetBarrier(barrier, rover::MonotonicNow());
    rover::dds::lockstep::SetWriteTick(barrier);
    // Pipelined: the inputs this quantum applies are those written before it started; what the
    // services write while serving this barrier waits for the next quantum.
    // Not pipelined: what the services write while serving this barrier applies to this
    // quantum, from its first step on, whenever it arrives (AbsorbInputs); until then the gate
    // holds it back.
    rover::dds::lockstep::SetReadGate(barrier);
    steps_in_quantum_ = 0;
    absorbed_ = false;
  }

  // Strict lock-step stalled: a named service never acknowledged the barrier. Say so (stamped
  // with the wall time, so that gated readers see it at once) and stop stepping.
  void ReportStall() {
    const std::string what = "lock-step stalled: '" + pacer_->stalled() +
                             "' has not served sim time " +
                             rover::FormatNumber(engine_->time(), 3) + " s within " +
                             rover::FormatNumber(stall_s_) + " s of wall time";
    rover::dds::lockstep::SetWriteTick(rover::dds::lockstep::kOff);
    rover::log::Error(what, {{"service", pacer_->stalled()}, {"sim_time_s", engine_->time()}});
    ctx_->SetHealth(rover_HEALTH_FAILED, what);
    stall_reported_ = true;
  }

  // Called by the executor between polls: one step when one is due.
  Duration Work() {
    const rover::Time now = rover::MonotonicNow();
    std::vector<std::string> dropped;
    // Strict lock-step: a quantum is stepped; its end's clock goes out once the barrier that
    // began it has been served (at once without pipelining: the quantum waited for that).
    const bool quantum_done = pacer_->strict() && steps_in_quantum_ >= steps_per_quantum_;
    const Duration wait = quantum_done ? pacer_->UntilBarrierServed(now)
                                       : pacer_->UntilNextStep(now, engine_->time(), &dropped);
    for (const auto& name : dropped) {
      rover::log::Warn("lock-step: not waiting for a service that stopped acknowledging",
                       {{"service", name}, {"sim_time_s", engine_->time()}});
    }
    if (!pacer_->stalled().empty() && !stall_reported_) ReportStall();
    const bool waiting = wait == rs::Pacer::kLockstepPoll || wait == rs::Pacer::kStrictWait;
    if (waiting && !waiting_) {
      waiting_ = true;
      wait_start_ = now;
    } else if (!waiting && waiting_) {
      waiting_ = false;
      ctx_->activities().Add("lockstep_wait", now - wait_start_);
    }
    // Keeps late joiners' clocks valid while paused; under strict lock-step also while waiting
    // at a barrier (an acknowledgement that was lost, or a restarted service, is made good).
    const bool repeat = pacer_->paused() || (pacer_->strict() && waiting);
    if (repeat && now - last_paused_clock_ > rover::Seconds(pacer_->paused() ? 0.2 : 0.5)) {
      PublishClock(/*repeat=*/true);
      last_paused_clock_ = now;
    }
    if (wait > Duration::zero()) return wait;
    if (quantum_done) {
      PublishClock();
      StartQuantum();
      // Pipelined: hand out the inputs written while serving the barrier just passed (held back
      // until now by the read gate) before the first step of the new quantum.
      if (pipelined_) ctx_->executor().DrainAll();
      return Duration::zero();
    }
    if (pacer_->strict() && !pipelined_ && !absorbed_) AbsorbInputs();
    auto out = [&] {
      rover::runtime::ScopedActivity a(ctx_->activities(), "physics");
      return engine_->Step();
    }();
    run_clock_.Set(rover::Time::FromSeconds(engine_->time()));
    if (!out.ok()) {
      rover::dds::lockstep::SetWriteTick(rover::dds::lockstep::kOff);  // seen at once
      rover::log::Error("simulation step failed; pausing", {{"error", out.status().message()}});
      ctx_->SetHealth(rover_HEALTH_FAILED, out.status().message());
      pacer_->Pause();
      return rs::Pacer::kPausedPoll;
    }
    Publish(*out);
    return Duration::zero();
  }

  // Strict, not pipelined, before a quantum's first step (every service due at its barrier has
  // acknowledged it): hand out every input written up to the barrier. The acknowledgements
  // count what was written; the readers wait until that much has arrived, so a motor goal that
  // travelled slower than its writer's acknowledgement is applied at the quantum's first step
  // and not at whichever step it happened to arrive before (core/runtime lockstep.hpp).
  void AbsorbInputs() {
    const std::int64_t barrier = pacer_->barrier_ns();
    rover::dds::lockstep::SetFrontier(
        pacer_->CurrentCounts(rover::dds::lockstep::WrittenBy(ctx_->participant().handle())));
    rover::dds::lockstep::SetReadGate(barrier + 1);
    ctx_->executor().DrainAll();
    rover::dds::lockstep::SetReadGate(barrier);
    absorbed_ = true;
    // Counted like a service's (result.json timings.late_samples): a run with any is suspect.
    const std::uint64_t late =
        rover::dds::lockstep::LateSamples() + rover::dds::lockstep::MissingSamples();
    for (; late_reported_ < late; ++late_reported_) {
      ctx_->activities().Add("late_samples", rover::Duration::zero());
    }
  }

  void OnAck(const rover_sim_ClockAck& a) {
    pacer_->OnWritten(a.service, {a.written._buffer, a.written._buffer + a.written._length});
    pacer_->OnIdleState(a.service, a.sim_time_ns, a.next_due_ns, a.reads);
    const std::string back = pacer_->OnAck(a.service, a.sim_time_ns, rover::MonotonicNow());
    if (!back.empty())
      rover::log::Info("lock-step: service is keeping up again", {{"service", back}});
  }

  template <class T, class In>
  void Send(dds::Writer<T>& w, const In& in, void (*to_idl)(const In&, T*), const char* frame) {
    T m{};
    to_idl(in, &m);
    Stamp(m.header, frame);
    (void)w.Write(m);
  }

  void Publish(const rs::StepOutput& o) {
    // Strict lock-step: sim/clock only at the end of a quantum, after its samples (Work()).
    if (pacer_->strict()) {
      ++steps_in_quantum_;
    } else {
      PublishClock();
    }
    const auto& s = o.sensors;
    if (s.motor_telemetry)
      Send(telemetry_w_, *s.motor_telemetry, &msg::MotorTelemetryToIdl, "rover");
    if (s.suspension_pots) Send(pots_w_, *s.suspension_pots, &msg::SuspensionPotsToIdl, "rover");
    if (s.arm_contact) Send(contact_w_, *s.arm_contact, &msg::ArmContactToIdl, "rover");
    if (s.imu) Send(imu_w_, *s.imu, &msg::ImuRawToIdl, "imu");
    if (s.sun_sensor) Send(sun_w_, *s.sun_sensor, &msg::SunSensorRawToIdl, "sun_sensor");
    if (o.truth) Send(truth_w_, *o.truth, &rs::TruthToIdl, "site");
  }

  // A goal whose mode is not a MotorMode makes the whole sample invalid: nothing of it is applied.
  void OnGoals(const rover_hw_MotorGoals& in) {
    auto goals = msg::MotorGoalsFromIdl(in);
    if (!goals.ok()) {
      rover::log::Warn("hw/motor_goals rejected", {{"error", goals.status().message()}});
      return;
    }
    const Status s = engine_->ApplyMotorGoals(*goals);
    if (!s.ok()) rover::log::Warn("motor goal refused by the controller", {{"error", s.message()}});
  }

  void OnControl(const rover_sim_Control& c) {
    const rover::Time now = rover::MonotonicNow();
    switch (c.command) {
      case rover_sim_SIM_PAUSE:
        pacer_->Pause();
        break;
      case rover_sim_SIM_RESUME:
        pacer_->Resume(now, engine_->time());
        break;
      case rover_sim_SIM_RESET:
        if (const Status s = engine_->Reset(); !s.ok()) {
          rover::log::Error("reset failed", {{"error", s.message()}});
        }
        pacer_->Anchor(now, engine_->time());
        if (pacer_->strict()) StartQuantum();
        break;
      case rover_sim_SIM_SET_SPEED:
        if (const Status s = pacer_->SetRealTimeFactor(c.real_time_factor, now, engine_->time());
            !s.ok()) {
          rover::log::Warn("sim/control: SIM_SET_SPEED ignored", {{"error", s.message()}});
        }
        break;
      default:
        rover::log::Warn("sim/control: unknown command ignored",
                         {{"command", static_cast<int>(c.command)}});
    }
    PublishClock();
    rover::log::Info("control", {{"command", static_cast<int>(c.command)},
                                 {"paused", pacer_->paused()},
                                 {"real_time_factor", pacer_->real_time_factor()},
                                 {"sim_time", engine_->time()}});
  }

  // Takes a stereo pair now, as on MER: the rover holds still (simulated time does not advance
  // while the images are made).
  void OnCamera(const rover_hw_CameraRequest& in) {
    const rover::hw::CameraRequest req = msg::CameraRequestFromIdl(in);
    const auto id = static_cast<msg::CameraId>(req.camera);
    if (!msg::IsKnownCamera(id)) {
      rover::log::Warn("camera request for a camera that does not exist; ignored",
                       {{"camera", req.camera}, {"request_id", req.request_id}});
      return;
    }
    const auto readings = engine_->physics().Readings();
    const rover::sim::render::MastState mast{readings.joint_angle_rad[rover::hw::kMastPan],
                                             readings.joint_angle_rad[rover::hw::kMastTilt]};
    const rover::Time t0 = rover::MonotonicNow();
    rover::runtime::ScopedActivity rendering(ctx_->activities(), "render");
    auto shot = camera_->Take(msg::CameraName(id), req.exposure_us, readings.chassis.pose_site,
                              mast, engine_->SunDirectionSite(), req.readout_width);
    if (!shot.ok()) {
      rover::log::Error("no stereo pair", {{"camera", msg::CameraName(id)},
                                           {"request_id", req.request_id},
                                           {"error", shot.status().message()}});
      if (shot.status().code() == rover::StatusCode::kUnavailable) {
        ctx_->SetHealth(rover_HEALTH_DEGRADED, shot.status().message());
      }
      return;
    }
    if (!shot->exposure_refused.empty()) {
      rover::log::Warn("hw/camera_request: exposure rejected; using auto-exposure",
                       {{"exposure_us", req.exposure_us}, {"error", shot->exposure_refused}});
    }
    const cv::Mat& l = shot->images.left.image;
    const cv::Mat& r = shot->images.right.image;
    rover::hw::CameraFrame frame;
    frame.request_id = req.request_id;
    frame.camera = req.camera;
    frame.exposure_us = shot->exposure_us;
    frame.width = l.cols;
    frame.height = l.rows;
    frame.left = {l.ptr<std::uint8_t>(), l.total()};
    frame.right = {r.ptr<std::uint8_t>(), r.total()};
    Send(frame_w_, frame, &msg::CameraFrameToIdl, msg::CameraName(id));
    rover::log::Info("stereo pair",
                     {{"camera", msg::CameraName(id)},
                      {"request_id", req.request_id},
                      {"render_ms", rover::ToSeconds(rover::MonotonicNow() - t0) * 1e3},
                      {"sim_time", engine_->time()}});
  }

  // The microscopic imager, likewise taken with the rover and arm holding still.
  void OnMicroscope(const rover_hw_MiRequest& in) {
    const rover::hw::MiRequest req = msg::MiRequestFromIdl(in);
    const auto readings = engine_->physics().Readings();
    rover::hwconfig::ArmAngles arm{};
    for (int j = 0; j < rover::hwconfig::kArmJoints; ++j) {
      arm[static_cast<std::size_t>(j)] = readings.joint_angle_rad[rover::hw::kArmAzimuth + j];
    }
    const rover::Time t0 = rover::MonotonicNow();
    rover::runtime::ScopedActivity rendering(ctx_->activities(), "render");
    auto shot = camera_->TakeMicroscope(req.exposure_us, readings.chassis.pose_site, arm,
                                        engine_->SunDirectionSite());
    if (!shot.ok()) {
      rover::log::Error("no microscopic-imager frame",
                        {{"request_id", req.request_id}, {"error", shot.status().message()}});
      if (shot.status().code() == rover::StatusCode::kUnavailable) {
        ctx_->SetHealth(rover_HEALTH_DEGRADED, shot.status().message());
      }
      return;
    }
    if (!shot->exposure_refused.empty()) {
      rover::log::Warn("hw/mi_request: exposure rejected; using auto-exposure",
                       {{"exposure_us", req.exposure_us}, {"error", shot->exposure_refused}});
    }
    const cv::Mat& img = shot->image.image;
    rover::hw::MiFrame frame;
    frame.request_id = req.request_id;
    frame.exposure_us = shot->exposure_us;
    frame.width = img.cols;
    frame.height = img.rows;
    frame.image = {img.ptr<std::uint8_t>(), img.total()};
    Send(mi_w_, frame, &msg::MiFrameToIdl, "mi");
    rover::log::Info("microscopic-imager frame",
                     {{"request_id", req.request_id},
                      {"render_ms", rover::ToSeconds(rover::MonotonicNow() - t0) * 1e3},
                      {"sim_time", engine_->time()}});
  }

  rover::ServiceContext* ctx_ = nullptr;
  rover::ManualClock run_clock_{rover::Time{0}};  // simulated time, for the fault agent
  std::unique_ptr<rs::SimEngine> engine_;
  std::optional<rs::Pacer> pacer_;
  std::optional<rs::CameraHead> camera_;
  rover::Time last_paused_clock_{0};
  long steps_per_quantum_ = 1;
  long steps_in_quantum_ = 0;
  bool absorbed_ = false;  // strict: this quantum's inputs handed out (AbsorbInputs)
  std::uint64_t late_reported_ = 0;  // late and missing samples already counted
  double stall_s_ = 30.0;
  bool stall_reported_ = false;
  bool pipelined_ = false;
  bool waiting_ = false;
  rover::Time wait_start_{0};
  dds::Writer<rover_sim_Clock> clock_w_;
  // Strict lock-step: sim/clock on each service's own partition (lockstep::ClockPartition).
  std::vector<std::pair<std::string, dds::Writer<rover_sim_Clock>>> service_clocks_;
  dds::Writer<rover_sim_Truth> truth_w_;
  dds::Writer<rover_hw_MotorTelemetry> telemetry_w_;
  dds::Writer<rover_hw_SuspensionPots> pots_w_;
  dds::Writer<rover_hw_ArmContact> contact_w_;
  dds::Writer<rover_hw_ImuRaw> imu_w_;
  dds::Writer<rover_hw_SunSensorRaw> sun_w_;
  dds::Writer<rover_hw_CameraFrame> frame_w_;
  dds::Writer<rover_hw_MiFrame> mi_w_;
};

}  // namespace

int main(int argc, char** argv) {
  // The simulator is the source of simulated time; its own timers run on wall time.
  setenv("ROVER_CLOCK", "wall", 1);
  RoverSim service;
  return rover::RunServiceMain(service, argc, argv);
}
