// apl-smoke: the application end of the smoke service set. Listens to dl/pose and reports what
// it saw on apl/mobility_status (latched), closing the ddl -> dl -> apl chain.
#include <cmath>
#include <cstdio>

#include "rover/runtime/service.hpp"

namespace {

class SmokeApl final : public rover::Service {
 public:
  SmokeApl() : Service("apl-smoke") {}

  void DeclareParameters(rover::ParamSet& p) override {
    p.Declare("report_every", 10, "publish a status after this many poses").Range(1, 10000);
  }

  rover::Status OnConfigure(rover::ServiceContext& ctx, const rover::ParamSet& p) override {
    report_every_ = p.GetInt("report_every");
    auto w = ctx.MakeWriter<rover_apl_MobilityStatus>("apl/mobility_status");
    if (!w.ok()) return w.status();
    writer_ = std::move(*w);
    return ctx.Subscribe<rover_dl_PoseEstimate>(
        "dl/pose", [this, &ctx](const rover::dds::Sample<rover_dl_PoseEstimate>& s) {
          ++poses_;
          if (poses_ % report_every_ != 0) return;
          const auto& q = s->pose.orientation;
          const double yaw = std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
          rover_apl_MobilityStatus m{};
          ctx.Stamp(m.header, "site");
          m.command_id = static_cast<uint32_t>(poses_);
          m.mode = rover_apl_MOBILITY_DIRECTED;
          m.state = rover_apl_MOBILITY_RUNNING;
          char text[128];
          std::snprintf(text, sizeof text, "poses=%lld heading_rad=%.4f", poses_, yaw);
          rover::dds::CopyString(m.message, text);
          (void)writer_.Write(m);
        });
  }

 private:
  long long poses_ = 0;
  long long report_every_ = 10;
  rover::dds::Writer<rover_apl_MobilityStatus> writer_;
};

}  // namespace

int main(int argc, char** argv) {
  SmokeApl service;
  return rover::RunServiceMain(service, argc, argv);
}
