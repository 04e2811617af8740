#include "rover/deploy/runner/recorder.hpp"

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "rover/geometry/transforms.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::deploy::runner {
namespace {

// One track point per this many simulated seconds.
constexpr double kTrackStepS = 0.2;

// Adds a point when kTrackStepS has passed; returns whether it did.
bool AddTrackPoint(Time t, const rover_Pose3& pose, double* last_s,
                   std::vector<std::array<double, 3>>* track) {
  if (t.seconds() - *last_s < kTrackStepS) return false;
  track->push_back({t.seconds(), pose.position.x, pose.position.y});
  *last_s = t.seconds();
  return true;
}

}  // namespace

Result<std::unique_ptr<Recorder>> Recorder::Create(const dds::Participant& participant,
                                                   sim::judge::Judge* judge, RunResult* result) {
  std::unique_ptr<Recorder> r(new Recorder(participant, judge, result));
  ROVER_ASSIGN_OR_RETURN(r->truth_, dds::Reader<rover_sim_Truth>::Create(participant, "sim/truth"));
  ROVER_ASSIGN_OR_RETURN(r->pose_,
                         dds::Reader<rover_dl_PoseEstimate>::Create(participant, "dl/pose"));
  ROVER_ASSIGN_OR_RETURN(
      r->odometry_, dds::Reader<rover_dl_PoseEstimate>::Create(participant, "dl/pose_odometry"));
  return r;
}

void Recorder::Pump() {
  truth_.TakeEach([&](const dds::Sample<rover_sim_Truth>& s) {
    truth_writers_.insert(s.info().publication_handle);
    result_->truth_publishers = static_cast<int>(truth_writers_.size());
    const Time t{s->header.stamp_ns};
    const Eigen::Isometry3d pose = msg::IsometryFromIdl(s->pose);
    if (judge_) judge_->AddTruth(t, pose);
    if (AddTrackPoint(t, s->pose, &last_truth_track_, &result_->truth_track)) {
      result_->truth_yaw.push_back(geometry::RpyFromRotation(pose.linear()).z());
    }
  });
  pose_.TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
    const Time t{s->header.stamp_ns};
    if (judge_) judge_->AddEstimate(t, msg::IsometryFromIdl(s->pose));
    has_estimate_ = true;
    rejected_measurements_ = static_cast<double>(s->rejected_measurements);
    AddTrackPoint(t, s->pose, &last_estimate_track_, &result_->estimate_track);
  });
  odometry_.TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
    const Time t{s->header.stamp_ns};
    if (judge_) judge_->AddOdometryOnlyEstimate(t, msg::IsometryFromIdl(s->pose));
    AddTrackPoint(t, s->pose, &last_odometry_track_, &result_->odometry_only_track);
  });
  for (auto& e : extra_) e();
}

std::string Recorder::CrossTalk(int domain) const {
  if (truth_writers_.size() <= 1) return "";
  return "cross-talk: " + std::to_string(truth_writers_.size()) + " simulators heard on domain " +
         std::to_string(domain);
}

std::vector<sim::judge::Criterion> Recorder::Figures() const {
  std::vector<sim::judge::Criterion> out;
  if (rejected_measurements_) {
    out.push_back({"estimator_rejected_measurements", *rejected_measurements_,
                   std::numeric_limits<double>::quiet_NaN(), "count", true,
                   "measurements dl-pose gated out or refused (dl/pose)"});
  }
  out.insert(out.end(), added_figures_.begin(), added_figures_.end());
  return out;
}

Result<std::unique_ptr<recording::BusRecorder>> StartRunRecording(
    const dds::Participant& participant, const Scenario& scenario, std::uint32_t seed,
    const std::string& run_dir, int domain, const std::map<std::string, std::string>& qos) {
  if (!scenario.record.enabled) return std::unique_ptr<recording::BusRecorder>();
  recording::BusRecorderOptions o;
  o.record = scenario.record;
  if (o.record.path.empty()) o.record.path = DefaultRunRecording().path;
  if (o.record.path.front() != '/') o.record.path = run_dir + "/" + o.record.path;
  o.clock = recording::LogClock::Mode::kSim;
  o.qos_overrides = qos;
  o.metadata = {{"scenario", scenario.name},
                {"scenario_file", scenario.file},
                {"seed", std::to_string(seed)},
                {"domain", std::to_string(domain)},
                {"recorder", "roverctl run"}};
  ROVER_ASSIGN_OR_RETURN(auto recorder, recording::BusRecorder::Create(participant, o));
  ROVER_RETURN_IF_ERROR(recorder->Start());
  return recorder;
}

nlohmann::json RecordingFigures(const recording::RecordingReport& report) {
  const auto& st = report.stats;
  const double wall = report.wall_s > 0 ? report.wall_s : 1e-9;
  const double span_s =
      st.last_log_time_ns > st.first_log_time_ns
          ? static_cast<double>(st.last_log_time_ns - st.first_log_time_ns) * 1e-9
          : 0.0;
  nlohmann::json j;
  j["file"] = report.path;
  j["complete"] = report.status.ok();
  j["messages"] = st.messages;
  j["bytes"] = st.bytes;
  j["file_bytes"] = st.file_bytes;
  j["lost"] = st.lost;
  j["dropped_after_cap"] = st.dropped;
  j["wall_s"] = report.wall_s;
  j["cpu_s"] = report.cpu_s;
  j["cpu_share"] = report.cpu_s / wall;
  j["mb_per_s"] = static_cast<double>(st.bytes) / 1e6 / wall;
  j["samples_per_s"] = static_cast<double>(st.messages) / wall;
  j["run_clock_span_s"] = span_s;
  j["file_mb_per_sim_minute"] =
      span_s > 0 ? static_cast<double>(st.file_bytes) / 1e6 / (span_s / 60.0) : 0.0;
  nlohmann::json topics = nlohmann::json::object();
  for (const auto& t : st.topics) {
    if (t.messages == 0 && t.lost == 0) continue;
    topics[t.topic] = {{"messages", t.messages}, {"bytes", t.bytes}, {"lost", t.lost},
                       {"per_sim_s", span_s > 0 ? static_cast<double>(t.messages) / span_s : 0.0}};
  }
  j["topics"] = std::move(topics);
  return j;
}

std::string FinishRunRecording(recording::BusRecorder* recorder, double* cpu_s) {
  if (recorder == nullptr) return "";
  const recording::RecordingReport report = recorder->Stop();
  if (cpu_s != nullptr) *cpu_s = report.cpu_s;
  // The recorder's own figures beside the file: rate, CPU share, losses, size per minute.
  const std::string figures = report.path + ".json";
  std::ofstream(figures) << RecordingFigures(report).dump(1) << "\n";
  if (report.status.ok()) return "";
  return "recording failed: " + report.status.message() + "; " + report.path + " is incomplete";
}

}  // namespace rover::deploy::runner
