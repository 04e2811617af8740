// ddl-smoke: the device-driver end of the smoke service set. Publishes ddl/imu at a fixed rate
// as if the rover turned at a constant yaw rate, so that data can be followed through all three
// layers. See ddl/smoke/README.md.
#include "rover/runtime/service.hpp"

namespace {

class SmokeDdl final : public rover::Service {
 public:
  SmokeDdl() : Service("ddl-smoke") {}

  void DeclareParameters(rover::ParamSet& p) override {
    p.Declare("rate_hz", 20.0, "ddl/imu publication rate [Hz] (run clock)").Range(0.1, 1000.0);
    p.Declare("yaw_rate", 0.1, "simulated yaw rate [rad/s]").Range(-3.0, 3.0);
  }

  rover::Status OnConfigure(rover::ServiceContext& ctx, const rover::ParamSet& p) override {
    auto w = ctx.MakeWriter<rover_ddl_Imu>("ddl/imu");
    if (!w.ok()) return w.status();
    writer_ = std::move(*w);
    yaw_rate_ = p.GetDouble("yaw_rate");
    ctx.executor().AddTimer(rover::Seconds(1.0 / p.GetDouble("rate_hz")), [this, &ctx] {
      rover_ddl_Imu m{};
      ctx.Stamp(m.header, "rover");
      m.angular_velocity.z = yaw_rate_;
      m.linear_acceleration.z = 9.81;
      m.temperature = 20.0;
      m.health = rover_HEALTH_OK;
      (void)writer_.Write(m);
    });
    return rover::Status::Ok();
  }

 private:
  rover::dds::Writer<rover_ddl_Imu> writer_;
  double yaw_rate_ = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  SmokeDdl service;
  return rover::RunServiceMain(service, argc, argv);
}
