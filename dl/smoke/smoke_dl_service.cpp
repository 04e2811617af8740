// dl-smoke: the device-layer link of the smoke service set. Integrates ddl/imu's yaw rate into
// a heading (dl_smoke library) and publishes it on dl/pose. See dl/smoke/README.md.
#include <cmath>
#include <string>

#include "rover/base/log.hpp"
#include "rover/dl/smoke/heading_integrator.hpp"
#include "rover/runtime/service.hpp"

namespace {

class SmokeDl final : public rover::Service {
 public:
  SmokeDl() : Service("dl-smoke") {}

  void DeclareParameters(rover::ParamSet& p) override {
    p.Declare("warmup_samples", 0,
              "ddl/imu samples integrated before the service reports health OK (until then "
              "DEGRADED, as an estimator that is still levelling)")
        .Range(0, 1000000);
  }

  rover::Status OnConfigure(rover::ServiceContext& ctx, const rover::ParamSet& params) override {
    auto w = ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose");
    if (!w.ok()) return w.status();
    writer_ = std::move(*w);
    warmup_ = params.GetInt("warmup_samples");
    if (warmup_ > 0) ctx.SetHealth(rover_HEALTH_DEGRADED, WarmupMessage());
    return ctx.Subscribe<rover_ddl_Imu>(
        "ddl/imu", [this, &ctx](const rover::dds::Sample<rover_ddl_Imu>& s) {
          const rover::Status st =
              integrator_.Add(rover::Time{s->header.stamp_ns}, s->angular_velocity.z);
          if (!st.ok()) {
            rover::log::Warn("imu sample rejected", {{"reason", st.message()}});
            return;
          }
          if (++samples_ <= warmup_) {
            ctx.SetHealth(samples_ < warmup_ ? rover_HEALTH_DEGRADED : rover_HEALTH_OK,
                          samples_ < warmup_ ? WarmupMessage() : "");
          }
          rover_dl_PoseEstimate p{};
          ctx.Stamp(p.header, "site");
          p.header.stamp_ns = s->header.stamp_ns;
          const double psi = integrator_.heading();
          p.pose.orientation = {std::cos(psi / 2), 0.0, 0.0, std::sin(psi / 2)};
          for (int i = 0; i < 6; ++i) p.covariance[i * 7] = 1.0;
          (void)writer_.Write(p);
        });
  }

 private:
  std::string WarmupMessage() const {
    return "warming up: " + std::to_string(samples_) + " of " + std::to_string(warmup_) +
           " ddl/imu samples";
  }

  std::int64_t warmup_ = 0;
  std::int64_t samples_ = 0;
  rover::dl::smoke::HeadingIntegrator integrator_;
  rover::dds::Writer<rover_dl_PoseEstimate> writer_;
};

}  // namespace

int main(int argc, char** argv) {
  SmokeDl service;
  return rover::RunServiceMain(service, argc, argv);
}
