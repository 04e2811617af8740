#pragma once
/// @file
/// What a run records while it goes: sim/truth, dl/pose and dl/pose_odometry, each fed to the
/// judge at full rate and kept as a track for the plots and result.json (one point per 0.2
/// simulated s: t [s], x [m], y [m] in the site frame); how many simulators publish sim/truth
/// (more than one is cross-talk between runs); the estimator's rejected-measurement count. A
/// task adds what else it wants recorded: figures for result.json, and any other topic.
///
/// The recorder writes the tracks and truth_publishers straight into the run's RunResult, so a
/// run that ends early (a crash, a budget) still has them.

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/runner/rendezvous_judging.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/recording/bus_recorder.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/sim/judge/judge.hpp"

namespace rover::deploy::runner {

class Recorder {
 public:
  /// Readers on `participant`; samples go to `judge` (may be null) and tracks to `*result`. All
  /// three must outlive the recorder.
  static Result<std::unique_ptr<Recorder>> Create(const dds::Participant& participant,
                                                  sim::judge::Judge* judge, RunResult* result);

  /// Takes every sample that has arrived (RunLoop calls it on every pass).
  void Pump();

  /// "" unless more than one simulator publishes sim/truth on `domain`:
  /// "cross-talk: 2 simulators heard on domain 117".
  std::string CrossTalk(int domain) const;
  /// True once a dl/pose sample has arrived.
  bool has_estimate() const { return has_estimate_; }

  /// Records another topic: every sample of `topic` that arrives is handed to `on_sample` when
  /// the recorder pumps (the sample is valid only during the call).
  template <class T>
  Status Record(const std::string& topic, std::function<void(const dds::Sample<T>&)> on_sample) {
    ROVER_ASSIGN_OR_RETURN(auto reader, dds::Reader<T>::Create(participant_, topic));
    auto shared = std::make_shared<dds::Reader<T>>(std::move(reader));
    extra_.push_back([shared, fn = std::move(on_sample)] { shared->TakeEach(fn); });
    return Status::Ok();
  }

  /// The run's mobility outcome (RunResult::mobility), made empty on first use; a mobility task
  /// fills it, and its Record callbacks may keep writing to it while the run goes.
  MobilityOutcome& Mobility() {
    if (!result_->mobility) result_->mobility.emplace();
    return *result_->mobility;
  }
  /// The lander-return task's record of apl/rendezvous_status (for the judge), made on first use.
  RendezvousLog& Rendezvous() {
    if (!rendezvous_) rendezvous_.emplace();
    return *rendezvous_;
  }
  const std::optional<RendezvousLog>& rendezvous() const { return rendezvous_; }
  /// A figure (measured, not judged) for result.json, listed after the judge's own.
  void AddFigure(sim::judge::Criterion figure) { added_figures_.push_back(std::move(figure)); }
  /// The recorder's figures: dl/pose's rejected-measurement count (when dl/pose was heard), then
  /// those added with AddFigure.
  std::vector<sim::judge::Criterion> Figures() const;

 private:
  Recorder(const dds::Participant& participant, sim::judge::Judge* judge, RunResult* result)
      : participant_(participant), judge_(judge), result_(result) {}

  const dds::Participant& participant_;
  sim::judge::Judge* judge_;
  RunResult* result_;
  dds::Reader<rover_sim_Truth> truth_;
  dds::Reader<rover_dl_PoseEstimate> pose_;
  dds::Reader<rover_dl_PoseEstimate> odometry_;
  std::vector<std::function<void()>> extra_;
  std::set<dds_instance_handle_t> truth_writers_;
  double last_truth_track_ = -1, last_estimate_track_ = -1, last_odometry_track_ = -1;
  bool has_estimate_ = false;
  std::optional<double> rejected_measurements_;  // dl/pose's count, last sample
  std::vector<sim::judge::Criterion> added_figures_;
  std::optional<RendezvousLog> rendezvous_;
};

/// The run's MCAP recording (the scenario's `record`, on by default): every catalog topic it
/// selects, taken on the operator's participant, into the run folder (run.mcap unless the
/// scenario names another file), log time on sim/clock. Null when the scenario turns it off.
/// `qos` is the set's x-rover.qos, so that the recorder's readers match its writers.
Result<std::unique_ptr<recording::BusRecorder>> StartRunRecording(
    const dds::Participant& participant, const Scenario& scenario, std::uint32_t seed,
    const std::string& run_dir, int domain, const std::map<std::string, std::string>& qos);

/// The recorder's figures of one recording (written beside it as <file>.json): messages,
/// bytes, samples lost in transport, wall and CPU seconds of its thread, CPU share (CPU / wall),
/// MB/s and samples/s (per wall second), run-clock span and file MB per simulated minute, and
/// per topic messages, bytes, lost and messages per simulated second.
nlohmann::json RecordingFigures(const recording::RecordingReport& report);

/// Stops the run's recording (null: nothing to do) and writes its figures to <file>.json; ""
/// when the file is complete, else the run's failure: "recording failed: <why>; <file> is
/// incomplete".
std::string FinishRunRecording(recording::BusRecorder* recorder, double* cpu_s = nullptr);

}  // namespace rover::deploy::runner
