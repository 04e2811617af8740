// arm-placement-plot: draws the last instrument placement of a recorded run (run.mcap) as a PNG:
// the instrument face's true height (sim/truth tool_point) over time, relative to where it came
// to rest, with dl-arm's states along the bottom, and its horizontal path seen from above. The
// pictures on dl/arm/README.md come from it.
//
//   arm-placement-plot RUN_DIR/run.mcap OUT.png
//
// Needs a recording with sim/truth and dl/arm_status (the scenario runner records both).
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/base/status.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/recording/cdr.hpp"

namespace {

using rover::Result;
using rover::Status;
using rover::recording::ByteSpan;
using rover::recording::CdrReader;

struct FacePoint {
  double t = 0, x = 0, y = 0, z = 0;
  bool contact = false;
};
struct ArmState {
  double t = 0;
  std::uint32_t command_id = 0, state = 0;
};

Status Skip(CdrReader& r, int doubles) {
  for (int i = 0; i < doubles; ++i) ROVER_RETURN_IF_ERROR(r.Double("field").status());
  return Status::Ok();
}

// rover::sim::Truth, field by field (idl/rover_sim.idl).
Result<FacePoint> ReadTruth(ByteSpan data) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(data));
  FacePoint p;
  ROVER_ASSIGN_OR_RETURN(const std::int64_t stamp, r.Int64("header.stamp_ns"));
  p.t = static_cast<double>(stamp) * 1e-9;
  ROVER_RETURN_IF_ERROR(r.String("header.frame_id", 31).status());
  ROVER_RETURN_IF_ERROR(r.Uint32("header.seq").status());
  ROVER_RETURN_IF_ERROR(Skip(r, 7 + 3 + 3));  // pose, velocity, angular velocity
  for (int w = 0; w < 6; ++w) {
    ROVER_RETURN_IF_ERROR(Skip(r, 2));
    ROVER_RETURN_IF_ERROR(r.Bool("wheels.in_contact").status());
    ROVER_RETURN_IF_ERROR(Skip(r, 1));
  }
  ROVER_RETURN_IF_ERROR(Skip(r, 2 + 2 + 1));  // rocker, bogie, odometer
  ROVER_RETURN_IF_ERROR(r.Uint32("rock_contacts").status());
  ROVER_RETURN_IF_ERROR(Skip(r, 1));
  ROVER_ASSIGN_OR_RETURN(p.x, r.Double("tool_point.x"));
  ROVER_ASSIGN_OR_RETURN(p.y, r.Double("tool_point.y"));
  ROVER_ASSIGN_OR_RETURN(p.z, r.Double("tool_point.z"));
  ROVER_ASSIGN_OR_RETURN(p.contact, r.Bool("tool_contact"));
  return p;
}

// rover::dl::ArmStatus up to its state.
Result<ArmState> ReadArmStatus(ByteSpan data, double t) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(data));
  ArmState a;
  a.t = t;
  ROVER_RETURN_IF_ERROR(r.Int64("header.stamp_ns").status());
  ROVER_RETURN_IF_ERROR(r.String("header.frame_id", 31).status());
  ROVER_RETURN_IF_ERROR(r.Uint32("header.seq").status());
  ROVER_ASSIGN_OR_RETURN(a.command_id, r.Uint32("command_id"));
  ROVER_ASSIGN_OR_RETURN(a.state, r.Uint32("state"));
  return a;
}

const char* StateName(std::uint32_t s) {
  static const char* kNames[] = {"IDLE", "MOVING", "AT_GOAL", "PLACED", "STOWED", "FAULT", "REJECTED"};
  return s < 7 ? kNames[s] : "?";
}

int Run(const std::string& path, const std::string& out) {
  auto reader = rover::mcap::Reader::Open(path);
  if (!reader.ok()) {
    std::fprintf(stderr, "arm-placement-plot: %s\n", reader.status().message().c_str());
    return 2;
  }
  std::vector<FacePoint> face;
  std::vector<ArmState> states;
  rover::mcap::MessageFilter filter;
  filter.topics = {"sim/truth", "dl/arm_status"};
  const Status st = (*reader)->ForEachMessage(filter, [&](const rover::mcap::MessageEvent& e) -> Status {
    const ByteSpan data(e.message.data.data(), e.message.data.size());
    if (e.channel->topic == "sim/truth") {
      ROVER_ASSIGN_OR_RETURN(FacePoint p, ReadTruth(data));
      face.push_back(p);
    } else {
      ROVER_ASSIGN_OR_RETURN(ArmState a, ReadArmStatus(data, face.empty() ? 0.0 : face.back().t));
      states.push_back(a);
    }
    return Status::Ok();
  });
  if (!st.ok()) {
    std::fprintf(stderr, "arm-placement-plot: %s: %s\n", path.c_str(), st.message().c_str());
    return 2;
  }
  // The last placement: from the last MOVING before the last PLACED to 10 s after it.
  int placed = -1;
  for (int i = static_cast<int>(states.size()) - 1; i >= 0 && placed < 0; --i) {
    if (states[static_cast<std::size_t>(i)].state == 3) placed = i;
  }
  if (placed < 0) {
    std::fprintf(stderr, "arm-placement-plot: %s has no PLACED dl/arm_status\n", path.c_str());
    return 1;
  }
  const std::uint32_t id = states[static_cast<std::size_t>(placed)].command_id;
  double t0 = states[static_cast<std::size_t>(placed)].t;
  for (const ArmState& a : states) {
    if (a.command_id == id && a.t < t0) t0 = a.t;
  }
  const double t1 = states[static_cast<std::size_t>(placed)].t + 10.0;
  std::vector<FacePoint> w;
  for (const FacePoint& p : face) {
    if (p.t >= t0 - 2.0 && p.t <= t1) w.push_back(p);
  }
  if (w.size() < 2) {
    std::fprintf(stderr, "arm-placement-plot: too few sim/truth samples in the placement\n");
    return 1;
  }
  const FacePoint rest = w.back();
  // Left: height above the rest point [cm] over time; right: the path seen from above [mm].
  const int W = 960, H = 420, L = 60, R = 600, T = 30, B = 360;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  double zmax = 1.0;
  for (const FacePoint& p : w) zmax = std::max(zmax, 100.0 * (p.z - rest.z));
  zmax = std::min(zmax, 200.0);
  auto px = [&](double t) { return L + static_cast<int>((t - w.front().t) / (w.back().t - w.front().t) * (R - L)); };
  auto py = [&](double cm) { return B - static_cast<int>(std::clamp(cm, -1.0, zmax) / (zmax + 1.0) * (B - T)); };
  cv::line(img, {L, py(0)}, {R, py(0)}, {160, 160, 160}, 1);
  cv::rectangle(img, {L, T}, {R, B}, {0, 0, 0}, 1);
  for (std::size_t i = 1; i < w.size(); ++i) {
    const cv::Scalar c = w[i].contact ? cv::Scalar(0, 0, 220) : cv::Scalar(200, 80, 0);
    cv::line(img, {px(w[i - 1].t), py(100.0 * (w[i - 1].z - rest.z))},
             {px(w[i].t), py(100.0 * (w[i].z - rest.z))}, c, 2, cv::LINE_AA);
  }
  std::uint32_t last = 99;
  for (const ArmState& a : states) {
    if (a.command_id != id || a.t < w.front().t || a.t > w.back().t || a.state == last) continue;
    last = a.state;
    cv::line(img, {px(a.t), T}, {px(a.t), B}, {0, 150, 0}, 1);
    cv::putText(img, StateName(a.state), {px(a.t) + 3, B - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 120, 0}, 1, cv::LINE_AA);
  }
  char text[160];
  std::snprintf(text, sizeof text, "face height above its rest point [cm], 0 .. %.0f; %.0f s", zmax,
                w.back().t - w.front().t);
  cv::putText(img, text, {L, T - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1, cv::LINE_AA);
  // Plan view of the last 6 cm of the descent [mm about the rest point].
  const int cx = 780, cy = 200, half = 150;
  cv::rectangle(img, {cx - half, cy - half}, {cx + half, cy + half}, {0, 0, 0}, 1);
  cv::line(img, {cx - half, cy}, {cx + half, cy}, {200, 200, 200}, 1);
  cv::line(img, {cx, cy - half}, {cx, cy + half}, {200, 200, 200}, 1);
  const double span_mm = 10.0;
  for (std::size_t i = 1; i < w.size(); ++i) {
    if (w[i].z - rest.z > 0.06) continue;
    auto map = [&](const FacePoint& p) {
      return cv::Point(cx + static_cast<int>(1000.0 * (p.x - rest.x) / span_mm * half),
                       cy - static_cast<int>(1000.0 * (p.y - rest.y) / span_mm * half));
    };
    cv::line(img, map(w[i - 1]), map(w[i]), {200, 80, 0}, 2, cv::LINE_AA);
  }
  cv::circle(img, {cx, cy}, 4, {0, 0, 220}, -1);
  cv::putText(img, "from above, +-10 mm (last 6 cm)", {cx - half, cy - half - 10},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  if (!cv::imwrite(out, img)) {
    std::fprintf(stderr, "arm-placement-plot: cannot write %s\n", out.c_str());
    return 2;
  }
  std::printf("placement of arm command %u: %zu truth samples, rest at (%.4f, %.4f, %.4f) m, contact %d\n",
              id, w.size(), rest.x, rest.y, rest.z, rest.contact ? 1 : 0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: arm-placement-plot RUN.mcap OUT.png\n");
    return 2;
  }
  return Run(argv[1], argv[2]);
}
