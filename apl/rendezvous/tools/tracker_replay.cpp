// tracker-replay: re-runs the science-target tracker (target_tracker.hpp) offline on the NAVCAM
// pairs of a recorded TARGET_SCIENCE approach (a scenario run's run.mcap), step by step, as
// apl-rendezvous ran it: the designation pair and pixel of the apl/rendezvous_command, then each
// pair the approach asked for (ddl/stereo_frame ids 3 << 24 | 0x800000 | n), each with the last
// dl/pose before it. Prints per step the features, how many were found again, the inliers, the
// measured motion against dl/pose's and why a step failed; with --target, the target's error
// against the truth (sim/truth) at every pair.
//
//   tracker-replay RUN_DIR/run.mcap [--set tracker.KEY=VALUE]... [--target X,Y]
//                  [--features] [--dump DIR]
//
//   --set       a TrackerOptions parameter, as apl-rendezvous takes it (repeatable)
//   --target    the picked point's site x, y [m] (the scenario runner's: the rock's face towards
//               the start, 0.4 radius from its centre); its height is where the designation
//               pixel's ray, seen from the true pose, passes over it
//   --features  one line per feature and step: its ranges, its residual under the measured and
//               under the true motion (sim/truth), along and across the ref ray, and its sigma
//   --dump      the tracker's drawings (target_NN.png) into DIR
//
// The recorded statuses (apl/rendezvous_status) are printed beside for comparison. Needs
// ddl/stereo_frame, dl/pose, apl/rendezvous_command (and sim/truth for --target/--features):
// the scenario runner records them all. Exit 0 when the replay reaches the last recorded pair
// tracked, 1 when it loses the target, 2 for bad input.
#include <dds/ddsi/ddsi_cdrstream.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "rover/apl/rendezvous/rendezvous_executor.hpp"
#include "rover/apl/rendezvous/target_tracker.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/rendezvous_idl.hpp"
#include "rover/recording/cdr.hpp"

namespace {

using rover::Result;
using rover::Status;
using rover::apl::rendezvous::FeatureTrack;
using rover::apl::rendezvous::NavcamPair;
using rover::apl::rendezvous::TargetFix;
using rover::apl::rendezvous::TargetTracker;
using rover::apl::rendezvous::TrackerOptions;
using rover::recording::ByteSpan;

// One recorded sample decoded into its idlc C struct with Cyclone's CDR stream reader (checked
// by dds_stream_normalize_data first, so a corrupt sample is an error, not a crash).
template <class T>
class Decoded {
 public:
  Decoded(const Decoded&) = delete;
  Decoded& operator=(const Decoded&) = delete;
  ~Decoded() {
    if (ops_ != nullptr) dds_stream_free_sample(&sample_, ops_);
  }
  static Result<std::unique_ptr<Decoded>> From(ByteSpan bytes, const dds_topic_descriptor_t& desc,
                                               const char* what) {
    if (bytes.size() < 8) return rover::InvalidArgument(std::string(what) + ": sample too short");
    const unsigned id = (unsigned{bytes[0]} << 8) | bytes[1];
    bool little = false;
    std::uint32_t xcdr = 0;
    switch (id) {
      case 0x0000:
        little = false;
        xcdr = 1;
        break;
      case 0x0001:
        little = true;
        xcdr = 1;
        break;
      case 0x0006:
        little = false;
        xcdr = 2;
        break;
      case 0x0007:
        little = true;
        xcdr = 2;
        break;
      default:
        return rover::InvalidArgument(std::string(what) + ": encapsulation " + std::to_string(id) +
                                      " is not plain CDR");
    }
    const bool host_little = std::endian::native == std::endian::little;
    std::unique_ptr<Decoded> d(new Decoded());
    d->buf_.assign(bytes.begin() + 4, bytes.end());
    std::uint32_t off = 0;
    if (dds_stream_normalize_data(reinterpret_cast<char*>(d->buf_.data()), &off,
                                  static_cast<std::uint32_t>(d->buf_.size()), little != host_little,
                                  xcdr, desc.m_ops) == nullptr) {
      return rover::InvalidArgument(std::string(what) + ": malformed sample");
    }
    dds_istream_t is;
    dds_istream_init(&is, static_cast<std::uint32_t>(d->buf_.size()), d->buf_.data(), xcdr);
    dds_stream_read(&is, reinterpret_cast<char*>(&d->sample_), desc.m_ops);
    dds_istream_fini(&is);
    d->ops_ = desc.m_ops;
    return d;
  }
  const T& operator*() const { return sample_; }

 private:
  Decoded() { std::memset(static_cast<void*>(&sample_), 0, sizeof sample_); }
  T sample_;
  std::vector<std::uint8_t> buf_;
  const std::uint32_t* ops_ = nullptr;
};

struct Args {
  std::string mcap;
  std::vector<std::string> sets;
  std::optional<Eigen::Vector2d> target;
  bool features = false;
  std::string dump;
};

int Usage() {
  std::fprintf(stderr,
               "usage: tracker-replay RUN.mcap [--set tracker.KEY=VALUE]... [--target X,Y] "
               "[--features] [--dump DIR]\n");
  return 2;
}

struct StatusLine {
  double t = 0;
  std::string text;
};

// What the replay needs of the command and statuses (first pass over the small topics).
struct Command {
  bool found = false;
  double t = 0;
  std::uint32_t image_id = 0;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  std::vector<StatusLine> statuses;
};

Result<Command> ReadCommand(const rover::mcap::Reader& reader) {
  Command c;
  rover::mcap::MessageFilter f;
  f.topics = {"apl/rendezvous_command", "apl/rendezvous_status"};
  ROVER_RETURN_IF_ERROR(reader.ForEachMessage(f, [&](const rover::mcap::MessageEvent& e) -> Status {
    const ByteSpan data(e.message.data.data(), e.message.data.size());
    const double t = static_cast<double>(e.message.log_time) * 1e-9;
    if (e.channel->topic == "apl/rendezvous_command") {
      ROVER_ASSIGN_OR_RETURN(
          auto s, Decoded<rover_apl_RendezvousCommand>::From(data, rover_apl_RendezvousCommand_desc,
                                                             e.channel->topic.c_str()));
      const rover::msg::RendezvousCommand m = rover::msg::RendezvousCommandFromIdl(**s);
      if (m.target == rover::msg::RendezvousTarget::kScience && m.image_id != 0) {
        c.found = true;  // the last science command by pixel
        c.t = t;
        c.image_id = m.image_id;
        c.pixel = {m.pixel_x, m.pixel_y};
        c.statuses.clear();
      }
    } else {
      ROVER_ASSIGN_OR_RETURN(
          auto s, Decoded<rover_apl_RendezvousStatus>::From(data, rover_apl_RendezvousStatus_desc,
                                                            e.channel->topic.c_str()));
      auto m = rover::msg::RendezvousStatusFromIdl(**s);
      if (m.ok()) {
        c.statuses.push_back({t, std::string(rover::msg::RendezvousPhaseName(m->phase)) +
                                     " pairs " + std::to_string(m->images) + ": " + m->message});
      }
    }
    return Status::Ok();
  }));
  return c;
}

// The picked point in the site frame: (x, y) given, z where the designation ray from the true
// pose passes over it.
Eigen::Vector3d PickedPoint(const Eigen::Vector2d& xy, const Eigen::Isometry3d& truth,
                            const rover::geometry::CameraModel& left, const Eigen::Vector2d& pixel,
                            double* miss) {
  const auto ray = left.Unproject(pixel);
  if (!ray) return {xy.x(), xy.y(), 0.0};
  const Eigen::Vector3d o = truth * ray->origin;
  const Eigen::Vector3d d = truth.linear() * ray->direction;
  const double s = (xy - o.head<2>()).dot(d.head<2>()) / d.head<2>().squaredNorm();
  const Eigen::Vector3d p = o + s * d;
  *miss = (p.head<2>() - xy).norm();
  return {xy.x(), xy.y(), p.z()};
}

// Residual r = m * ref - cur resolved along the ref ray (moved by m; unit d) and across it.
void AlongAcross(const Eigen::Vector3d& r, const Eigen::Vector3d& d, double* along,
                 double* across) {
  *along = r.dot(d);
  *across = (r - *along * d).norm();
}

struct Frame {
  std::unique_ptr<Decoded<rover_ddl_StereoFrame>> sample;
  cv::Mat left, right;
  rover::geometry::CameraModel left_model, right_model;
  std::uint32_t id = 0;
  NavcamPair pair() const {
    NavcamPair p;
    p.request_id = id;
    p.left = &left;
    p.right = &right;
    p.left_model = &left_model;
    p.right_model = &right_model;
    return p;
  }
};

Result<Frame> ToFrame(std::unique_ptr<Decoded<rover_ddl_StereoFrame>> s) {
  ROVER_ASSIGN_OR_RETURN(const rover::msg::StereoFrame f, rover::msg::StereoFrameFromIdl(**s));
  ROVER_ASSIGN_OR_RETURN(rover::geometry::CameraModel lm,
                         rover::msg::CameraModelFromFields(f.left_model));
  ROVER_ASSIGN_OR_RETURN(rover::geometry::CameraModel rm,
                         rover::msg::CameraModelFromFields(f.right_model));
  Frame out{nullptr,
            cv::Mat(f.height, f.width, CV_8UC1, const_cast<std::uint8_t*>(f.left.data())),
            cv::Mat(f.height, f.width, CV_8UC1, const_cast<std::uint8_t*>(f.right.data())),
            std::move(lm),
            std::move(rm),
            f.request_id};
  out.sample = std::move(s);
  return out;
}

std::string Vec(const Eigen::Vector3d& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.3f, %.3f, %.3f)", v.x(), v.y(), v.z());
  return b;
}

int Run(const Args& args) {
  rover::ParamSet params("tracker-replay");
  rover::DeclareParams<TrackerOptions>(params, "tracker.");
  for (const std::string& s : args.sets) {
    if (Status st = params.SetFromString(s); !st.ok()) {
      std::fprintf(stderr, "tracker-replay: %s\n", st.message().c_str());
      return 2;
    }
  }
  auto options = rover::ReadParams<TrackerOptions>(params, "tracker.");
  if (!options.ok()) {
    std::fprintf(stderr, "tracker-replay: %s\n", options.status().message().c_str());
    return 2;
  }
  auto reader = rover::mcap::Reader::Open(args.mcap);
  if (!reader.ok()) {
    std::fprintf(stderr, "tracker-replay: %s\n", reader.status().message().c_str());
    return 2;
  }
  auto command = ReadCommand(**reader);
  if (!command.ok() || !command->found) {
    std::fprintf(stderr, "tracker-replay: %s: %s\n", args.mcap.c_str(),
                 command.ok() ? "no science command by pixel on apl/rendezvous_command"
                              : command.status().message().c_str());
    return 2;
  }
  std::printf("command at %.2f s: pixel (%.2f, %.2f) of pair 0x%08x\n", command->t,
              command->pixel.x(), command->pixel.y(), command->image_id);

  TargetTracker tracker(*options);
  std::optional<Eigen::Isometry3d> pose, truth, truth_ref;
  // The left camera centre of the ref pair, R_ref.
  Eigen::Vector3d ref_camera = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> picked;
  bool designated = false, lost = false;
  int step = 0, tracked = 0;
  TargetFix last;
  std::string last_error;  // the last tracked fix against the truth then
  std::size_t status_at = 0;
  auto print_statuses = [&](double until) {
    for (; status_at < command->statuses.size() && command->statuses[status_at].t <= until;
         ++status_at) {
      std::printf("    recorded %.2f s: %s\n", command->statuses[status_at].t,
                  command->statuses[status_at].text.c_str());
    }
  };
  auto truth_error = [&](const TargetFix& fix) -> std::string {
    if (!picked || !truth) return "";
    const Eigen::Vector3d e = fix.target_rover - truth->inverse() * *picked;
    char b[128];
    std::snprintf(b, sizeof b, ", error %.1f cm (horizontal %.1f; %.1f, %.1f, %.1f)",
                  100 * e.norm(), 100 * e.head<2>().norm(), 100 * e.x(), 100 * e.y(), 100 * e.z());
    return b;
  };
  auto dump = [&] {
    if (args.dump.empty()) return;
    if (auto img = tracker.LastDrawing(); img.bgr)
      cv::imwrite(args.dump + "/" + img.name + ".png", *img.bgr);
  };

  rover::mcap::MessageFilter f;
  f.topics = {"ddl/stereo_frame", "dl/pose", "sim/truth"};
  const Status st = (*reader)->ForEachMessage(f, [&](const rover::mcap::MessageEvent& e) -> Status {
    if (lost) return Status::Ok();
    const ByteSpan data(e.message.data.data(), e.message.data.size());
    const double t = static_cast<double>(e.message.log_time) * 1e-9;
    const std::string& topic = e.channel->topic;
    if (topic == "dl/pose") {
      ROVER_ASSIGN_OR_RETURN(auto s, Decoded<rover_dl_PoseEstimate>::From(
                                         data, rover_dl_PoseEstimate_desc, "dl/pose"));
      if (auto p = rover::msg::PoseSampleFromIdl(**s); p.ok()) pose = p->site_from_rover;
      return Status::Ok();
    }
    if (topic == "sim/truth") {
      ROVER_ASSIGN_OR_RETURN(
          auto s, Decoded<rover_sim_Truth>::From(data, rover_sim_Truth_desc, "sim/truth"));
      truth = rover::msg::IsometryFromIdl((**s).pose);
      return Status::Ok();
    }
    // ddl/stereo_frame: peek at the request id before decoding the images.
    ROVER_ASSIGN_OR_RETURN(rover::recording::CdrReader peek,
                           rover::recording::CdrReader::Open(data));
    ROVER_RETURN_IF_ERROR(peek.Int64("header.stamp_ns").status());
    ROVER_RETURN_IF_ERROR(peek.String("header.frame_id", 31).status());
    ROVER_RETURN_IF_ERROR(peek.Uint32("header.seq").status());
    ROVER_ASSIGN_OR_RETURN(const std::uint32_t id, peek.Uint32("request_id"));
    const bool designation = !designated && id == command->image_id;
    const bool approach = designated &&
                          (id >> 24) == rover::apl::rendezvous::kCameraRequestPrefix &&
                          (id & 0x800000u) != 0 && t > command->t;
    if (!designation && !approach) return Status::Ok();
    ROVER_ASSIGN_OR_RETURN(auto s, Decoded<rover_ddl_StereoFrame>::From(
                                       data, rover_ddl_StereoFrame_desc, "ddl/stereo_frame"));
    ROVER_ASSIGN_OR_RETURN(const Frame frame, ToFrame(std::move(s)));
    if (!pose)
      return rover::FailedPrecondition("no dl/pose before the pair 0x" + std::to_string(id));
    if (designation) {
      auto fix = tracker.Designate(frame.pair(), *pose, command->pixel);
      dump();
      if (!fix.ok()) {
        std::printf("designation at %.2f s refused: %s\n", t, fix.status().message().c_str());
        lost = true;
        return Status::Ok();
      }
      designated = true;
      if (args.target && truth) {
        double miss = 0;
        picked = PickedPoint(*args.target, *truth, frame.left_model, command->pixel, &miss);
        std::printf("picked point %s (site; the designation ray passes %.1f mm from it)\n",
                    Vec(*picked).c_str(), 1e3 * miss);
      }
      truth_ref = truth;
      ref_camera = frame.left_model.Center();
      std::printf("designation at %.2f s: target %s, %.2f m, sigma %.1f cm, %d features%s\n", t,
                  Vec(fix->target_rover).c_str(), fix->target_rover.head<2>().norm(),
                  100 * fix->sigma, fix->features, truth_error(*fix).c_str());
      last = *fix;
      last_error = truth_error(*fix);
      return Status::Ok();
    }
    ++step;
    auto fix = tracker.Track(frame.pair(), *pose);
    dump();
    if (!fix.ok())
      return rover::InvalidArgument("pair " + std::to_string(step) + ": " + fix.status().message());
    const Eigen::Vector3d slip = fix->predicted_motion.translation() - fix->motion.translation();
    std::printf("pair %2d at %.2f s: %d features, %d found again, %d inliers, rms %.1f cm", step, t,
                fix->features, fix->matched, fix->inliers, 100 * fix->rms);
    if (fix->tracked) {
      ++tracked;
      std::printf(", target %s %.2f m (%s, sigma %.1f cm)%s, odometry off by %.1f cm\n",
                  Vec(fix->target_rover).c_str(), fix->target_rover.head<2>().norm(),
                  fix->target_measured ? "measured" : "carried", 100 * fix->sigma,
                  truth_error(*fix).c_str(), 100 * slip.head<2>().norm());
      if (!fix->why.empty()) std::printf("    note: %s\n", fix->why.c_str());
    } else {
      std::printf("\n    LOST (%s): %s\n", rover::apl::rendezvous::TargetLossName(fix->loss),
                  fix->why.c_str());
      lost = true;
    }
    if (args.features && truth && truth_ref) {
      // The true motion R_cur <- R_ref, from sim/truth.
      const Eigen::Isometry3d true_motion = truth->inverse() * *truth_ref;
      const Eigen::Isometry3d measured = fix->tracked ? fix->motion : fix->predicted_motion;
      const Eigen::Vector3d tm = true_motion.translation(), mm = measured.translation();
      std::printf(
          "    motion: measured (%.3f, %.3f, %.3f), true (%.3f, %.3f, %.3f), dl/pose (%.3f, %.3f, "
          "%.3f)\n",
          mm.x(), mm.y(), mm.z(), tm.x(), tm.y(), tm.z(), fix->predicted_motion.translation().x(),
          fix->predicted_motion.translation().y(), fix->predicted_motion.translation().z());
      auto deg = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
        return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
      };
      std::printf("    rotation against the true one: measured %.3f deg, dl/pose %.3f deg\n",
                  deg(measured, true_motion), deg(fix->predicted_motion, true_motion));
      std::printf("    %3s %5s %6s %5s %5s | %7s %7s | %7s %7s %5s | %s\n", "i", "ncc", "t_ref",
                  "s_ref", "s_cur", "m_along", "m_acrs", "t_along", "t_acrs", "t/sig", "");
      const auto& tracks = tracker.tracks();
      for (std::size_t i = 0; i < tracks.size(); ++i) {
        const FeatureTrack& ft = tracks[i];
        const double t_ref = ft.ref_point.norm();
        if (!ft.matched) {
          std::printf("    %3zu %5.2f %6.2f %5.1f       | not found\n", i, ft.ncc, t_ref,
                      100 * ft.ref_sigma);
          continue;
        }
        const Eigen::Vector3d d_m = (measured.linear() * (ft.ref_point - ref_camera)).normalized();
        const Eigen::Vector3d d_t =
            (true_motion.linear() * (ft.ref_point - ref_camera)).normalized();
        double ma, mc, ta, tc;
        AlongAcross(measured * ft.ref_point - ft.point, d_m, &ma, &mc);
        AlongAcross(true_motion * ft.ref_point - ft.point, d_t, &ta, &tc);
        const double sc = std::hypot(ft.ref_sigma, ft.sigma);
        std::printf("    %3zu %5.2f %6.2f %5.1f %5.1f | %7.1f %7.1f | %7.1f %7.1f %5.1f | %s\n", i,
                    ft.ncc, t_ref, 100 * ft.ref_sigma, 100 * ft.sigma, 100 * ma, 100 * mc, 100 * ta,
                    100 * tc, sc > 0 ? ta / sc : 0.0,
                    i == 0      ? "target"
                    : ft.inlier ? "inlier"
                                : "outlier");
      }
      std::printf(
          "    (cm; residual of m * X_ref - X_cur along and across the moved ref ray, under the "
          "measured motion m and the true one; t/sig: true along / hypot(s_ref, s_cur))\n");
    }
    print_statuses(t + 1.0);
    if (fix->tracked) {
      last = *fix;
      last_error = truth_error(*fix);
    }
    truth_ref = truth;
    ref_camera = frame.left_model.Center();
    return Status::Ok();
  });
  if (!st.ok()) {
    std::fprintf(stderr, "tracker-replay: %s: %s\n", args.mcap.c_str(), st.message().c_str());
    return 2;
  }
  print_statuses(1e300);
  if (!designated) {
    std::fprintf(stderr, "tracker-replay: the designation pair 0x%08x is not in the recording\n",
                 command->image_id);
    return 2;
  }
  std::printf("%s after %d pairs tracked: last target %s, %.3f m%s\n", lost ? "LOST" : "END",
              tracked, Vec(last.target_rover).c_str(), last.target_rover.head<2>().norm(),
              last_error.c_str());
  return lost ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" && i + 1 < argc) {
      args.sets.push_back(argv[++i]);
    } else if (a == "--target" && i + 1 < argc) {
      double x = 0, y = 0;
      if (std::sscanf(argv[++i], "%lf,%lf", &x, &y) != 2) return Usage();
      args.target = Eigen::Vector2d(x, y);
    } else if (a == "--features") {
      args.features = true;
    } else if (a == "--dump" && i + 1 < argc) {
      args.dump = argv[++i];
    } else if (!a.empty() && a[0] != '-' && args.mcap.empty()) {
      args.mcap = a;
    } else {
      return Usage();
    }
  }
  if (args.mcap.empty()) return Usage();
  return Run(args);
}
