// arm-placement-plot: draws the last instrument placement of a recorded run (run.mcap) as a PNG:
// the instrument face's true height (sim/truth tool_point) over time, relative to where it came
// to rest, with dl-arm's states along the bottom, and its horizontal path seen from above. The
// pictures on dl/arm/README.md come from it.
//
//   arm-placement-plot RUN_DIR/run.mcap OUT.png
//   arm-placement-plot --focus [N] RUN_DIR/run.mcap OUT.png
//
// --focus: the auto-focus sweeps instead. Prints one line per AUTOFOCUS command and per
// microscopic-imager frame (the face's true height at the frame relative to where the command
// ended, the wavelet focus measure dl-arm computes) and draws the N-th sweep (default: the last):
// the measure against the face's height, and the top, sharpest and final frames.
//
// Needs a recording with sim/truth and dl/arm_status (the scenario runner records both), and
// ddl/mi_frame for --focus.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/base/status.hpp"
#include "rover/dl/arm/focus.hpp"
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

// rover::dl::ArmStatus, up to the auto-focus fields.
struct FocusStatus {
  double t = 0;
  std::uint32_t command_id = 0, state = 0;
  double focus_height = 0;
  bool predicted = false;
  std::uint32_t image_id = 0;
};
Result<FocusStatus> ReadFocusStatus(ByteSpan data, double t) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(data));
  FocusStatus a;
  a.t = t;
  ROVER_RETURN_IF_ERROR(r.Int64("header.stamp_ns").status());
  ROVER_RETURN_IF_ERROR(r.String("header.frame_id", 31).status());
  ROVER_RETURN_IF_ERROR(r.Uint32("header.seq").status());
  ROVER_ASSIGN_OR_RETURN(a.command_id, r.Uint32("command_id"));
  ROVER_ASSIGN_OR_RETURN(a.state, r.Uint32("state"));
  ROVER_RETURN_IF_ERROR(Skip(r, 4 + 4 + 3));  // joints, joint_goals, tool_point
  ROVER_RETURN_IF_ERROR(r.Bool("contact").status());
  ROVER_RETURN_IF_ERROR(r.Bool("stowed").status());
  ROVER_ASSIGN_OR_RETURN(a.focus_height, r.Double("focus_height"));
  ROVER_ASSIGN_OR_RETURN(a.predicted, r.Bool("focus_predicted"));
  ROVER_RETURN_IF_ERROR(r.Uint16("focus_images").status());
  ROVER_ASSIGN_OR_RETURN(a.image_id, r.Uint32("focus_image_id"));
  return a;
}

// rover::ddl::MiFrame: the image and its focus measure.
struct MiFrame {
  double t = 0;
  std::uint32_t request_id = 0;
  cv::Mat image;
  double measure = 0;
};
Result<MiFrame> ReadMiFrame(ByteSpan data) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(data));
  MiFrame f;
  ROVER_ASSIGN_OR_RETURN(const std::int64_t stamp, r.Int64("header.stamp_ns"));
  f.t = static_cast<double>(stamp) * 1e-9;
  ROVER_RETURN_IF_ERROR(r.String("header.frame_id", 31).status());
  ROVER_RETURN_IF_ERROR(r.Uint32("header.seq").status());
  ROVER_ASSIGN_OR_RETURN(f.request_id, r.Uint32("request_id"));
  ROVER_RETURN_IF_ERROR(r.Uint32("exposure_us").status());
  ROVER_ASSIGN_OR_RETURN(const std::uint16_t w, r.Uint16("width"));
  ROVER_ASSIGN_OR_RETURN(const std::uint16_t h, r.Uint16("height"));
  ROVER_ASSIGN_OR_RETURN(const ByteSpan pixels, r.Octets("image"));
  if (pixels.size() != static_cast<std::size_t>(w) * h || w == 0) {
    return rover::InvalidArgument("ddl/mi_frame " + std::to_string(f.request_id) + ": " +
                                  std::to_string(pixels.size()) + " bytes for " +
                                  std::to_string(w) + " x " + std::to_string(h));
  }
  f.image = cv::Mat(h, w, CV_8UC1, const_cast<std::uint8_t*>(pixels.data())).clone();
  ROVER_ASSIGN_OR_RETURN(f.measure, rover::dl::arm::WaveletFocusMeasure(f.image));
  return f;
}

const char* StateName(std::uint32_t s) {
  static const char* kNames[] = {"IDLE",  "MOVING",   "AT_GOAL", "PLACED",
                                 "STOWED", "FAULT", "REJECTED", "FOCUSED"};
  return s < 8 ? kNames[s] : "?";
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

int RunFocus(const std::string& path, const std::string& out, int which) {
  auto reader = rover::mcap::Reader::Open(path);
  if (!reader.ok()) {
    std::fprintf(stderr, "arm-placement-plot: %s\n", reader.status().message().c_str());
    return 2;
  }
  std::vector<FacePoint> face;
  std::vector<FocusStatus> states;
  std::vector<MiFrame> frames;
  rover::mcap::MessageFilter filter;
  filter.topics = {"sim/truth", "dl/arm_status", "ddl/mi_frame"};
  const Status st = (*reader)->ForEachMessage(filter, [&](const rover::mcap::MessageEvent& e) -> Status {
    const ByteSpan data(e.message.data.data(), e.message.data.size());
    if (e.channel->topic == "sim/truth") {
      ROVER_ASSIGN_OR_RETURN(FacePoint p, ReadTruth(data));
      face.push_back(p);
    } else if (e.channel->topic == "dl/arm_status") {
      ROVER_ASSIGN_OR_RETURN(FocusStatus a, ReadFocusStatus(data, face.empty() ? 0.0 : face.back().t));
      states.push_back(a);
    } else {
      ROVER_ASSIGN_OR_RETURN(MiFrame f, ReadMiFrame(data));
      frames.push_back(std::move(f));
    }
    return Status::Ok();
  });
  if (!st.ok()) {
    std::fprintf(stderr, "arm-placement-plot: %s: %s\n", path.c_str(), st.message().c_str());
    return 2;
  }
  // Each AUTOFOCUS command that ended (FOCUSED or FAULT after a frame): its frames are those
  // taken between its first status and its end.
  struct Sweep {
    std::uint32_t id = 0;
    double t0 = 0, t1 = 0;
    FocusStatus end;
    std::vector<std::size_t> frames;
  };
  std::vector<Sweep> sweeps;
  for (const FocusStatus& a : states) {
    if (a.state != 7 && a.state != 5) continue;  // FOCUSED, FAULT
    Sweep s;
    s.id = a.command_id;
    s.t1 = a.t;
    s.t0 = a.t;
    for (const FocusStatus& b : states) {
      if (b.command_id == a.command_id && b.t < s.t0) s.t0 = b.t;
    }
    s.end = a;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (frames[i].t >= s.t0 - 0.5 && frames[i].t <= s.t1 + 0.5) s.frames.push_back(i);
    }
    if (!s.frames.empty()) sweeps.push_back(s);
  }
  if (sweeps.empty()) {
    std::fprintf(stderr, "arm-placement-plot: %s has no auto-focus sweep (ddl/mi_frame)\n", path.c_str());
    return 1;
  }
  auto face_at = [&](double t) {
    const FacePoint* best = &face.front();
    for (const FacePoint& p : face) {
      if (std::abs(p.t - t) < std::abs(best->t - t)) best = &p;
    }
    return *best;
  };
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    const Sweep& s = sweeps[k];
    const FacePoint end = face_at(s.t1);
    std::printf("sweep %zu: command %u %s, %zu frames, dl-arm's face height %.2f mm%s\n", k + 1,
                s.id, StateName(s.end.state), s.frames.size(), 1000.0 * s.end.focus_height,
                s.end.predicted ? " (predicted from the contact)" : "");
    for (std::size_t i : s.frames) {
      std::printf("  frame %u  face %+7.2f mm from the end  measure %.5f\n", frames[i].request_id,
                  1000.0 * (face_at(frames[i].t).z - end.z), frames[i].measure);
    }
  }
  const Sweep& s = sweeps[static_cast<std::size_t>(
      which > 0 ? std::min<int>(which, static_cast<int>(sweeps.size())) - 1 : static_cast<int>(sweeps.size()) - 1)];
  const FacePoint end = face_at(s.t1);
  // Left: the measure against the face's height; right: top, sharpest and final frames.
  const int W = 1000, H = 420, L = 70, R = 560, T = 40, B = 360;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  double hmin = 1e9, hmax = -1e9, mmax = 0;
  std::size_t sharpest = s.frames.front();
  for (std::size_t i : s.frames) {
    const double h = 1000.0 * (face_at(frames[i].t).z - end.z);
    hmin = std::min(hmin, h);
    hmax = std::max(hmax, h);
    if (frames[i].measure > mmax) {
      mmax = frames[i].measure;
      if (i != s.frames.back()) sharpest = i;
    }
  }
  hmin = std::floor(hmin / 10.0) * 10.0 - 5.0;
  hmax = std::ceil(hmax / 10.0) * 10.0 + 5.0;
  auto px = [&](double h) { return L + static_cast<int>((h - hmin) / (hmax - hmin) * (R - L)); };
  auto py = [&](double m) { return B - static_cast<int>(m / (1.1 * mmax) * (B - T)); };
  cv::rectangle(img, {L, T}, {R, B}, {0, 0, 0}, 1);
  cv::line(img, {px(0), T}, {px(0), B}, {160, 160, 160}, 1);
  char text[200];
  for (double h = std::ceil(hmin / 10.0) * 10.0; h <= hmax; h += 10.0) {
    std::snprintf(text, sizeof text, "%.0f", h);
    cv::putText(img, text, {px(h) - 10, B + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
  }
  std::snprintf(text, sizeof text, "face height relative to the final frame [mm] (true); command %u %s%s",
                s.id, StateName(s.end.state), s.end.predicted ? ", predicted from the contact" : "");
  cv::putText(img, text, {L, B + 40}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  cv::putText(img, "wavelet focus measure of each microscopic-imager frame", {L, T - 12},
              cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1, cv::LINE_AA);
  cv::Point prev(-1, -1);
  for (std::size_t i : s.frames) {
    const cv::Point p(px(1000.0 * (face_at(frames[i].t).z - end.z)), py(frames[i].measure));
    const bool last = i == s.frames.back();
    if (prev.x >= 0 && !last) cv::line(img, prev, p, {200, 80, 0}, 1, cv::LINE_AA);
    cv::circle(img, p, last ? 7 : 4, last ? cv::Scalar(0, 0, 220) : cv::Scalar(200, 80, 0), last ? 2 : -1,
               cv::LINE_AA);
    if (!last) prev = p;
  }
  const std::size_t shown[3] = {s.frames.front(), sharpest, s.frames.back()};
  const char* label[3] = {"first frame", "sharpest in the sweep", "final frame"};
  for (int k = 0; k < 3; ++k) {
    cv::Mat thumb, colour;
    cv::resize(frames[shown[k]].image, thumb, cv::Size(200, 200), 0, 0, cv::INTER_AREA);
    cv::cvtColor(thumb, colour, cv::COLOR_GRAY2BGR);
    const int x = 580 + (k % 2) * 210, y = 20 + (k / 2) * 200;
    colour.copyTo(img(cv::Rect(x, y, 200, 200)));
    std::snprintf(text, sizeof text, "%s %+.1f mm", label[k],
                  1000.0 * (face_at(frames[shown[k]].t).z - end.z));
    cv::putText(img, text, {x + 4, y + 194}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 255, 255}, 1, cv::LINE_AA);
  }
  if (!cv::imwrite(out, img)) {
    std::fprintf(stderr, "arm-placement-plot: cannot write %s\n", out.c_str());
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 4 && std::string(argv[1]) == "--focus") {
    const bool numbered = argc == 5;
    return RunFocus(argv[numbered ? 3 : 2], argv[numbered ? 4 : 3], numbered ? std::atoi(argv[2]) : 0);
  }
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: arm-placement-plot RUN.mcap OUT.png\n"
                 "       arm-placement-plot --focus [N] RUN.mcap OUT.png\n");
    return 2;
  }
  return Run(argv[1], argv[2]);
}
