#pragma once
/// @file
/// Results of scenario runs and campaigns: the per-run JSON (`result.json`), the campaign
/// summary (`summary.json`, pass rate, mean / 95th percentile / worst of each figure), the JUnit
/// XML for CI systems (`junit.xml`, one test case per run) and the summary table that
/// `roverctl run` and `roverctl report` print. No DDS.

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/sim/judge/judge.hpp"

namespace rover::deploy {

struct StepResult {
  std::string primitive;
  std::uint32_t command_id = 0;
  std::string state;        ///< "done", "failed", "rejected", "timeout"
  std::string termination;  ///< e.g. "nominal", "tilt"
  std::string message;
  double sim_start_s = 0, sim_end_s = 0;
};

/// The last apl/goodness_map of a run (GESTALT's 8-bit cells), for the judge and the map plot.
/// Cell (i, j) covers x in [origin_x + i r, origin_x + (i+1) r), y likewise; index j * width + i.
struct GoodnessGrid {
  double origin_x = 0, origin_y = 0;  ///< [m] site frame
  double resolution = 0.2;            ///< [m]
  int width = 0, height = 0;          ///< cells
  std::uint8_t unknown_goodness = 0;
  std::vector<std::uint8_t> goodness;  ///< 0 = obstacle, 255 = perfect
  std::vector<std::uint8_t> flags;     ///< bit 0 known, bit 1 border of unknown, bit 2 FOV edge
  bool Known(int i, int j) const;
  /// Index of the cell holding site point (x, y); -1 outside the grid.
  int CellAt(double x, double y) const;
};

/// One decision of arc voting (apl/arc_votes): where the rover was and what it chose.
struct ChosenArc {
  double x = 0, y = 0, yaw = 0;  ///< [m], [rad] pose the votes were computed from
  bool point_turn = false;
  double curvature = 0;   ///< [1/m] arcs
  int direction = 1;      ///< arcs: +1 forward, -1 backward
  double turn_angle = 0;  ///< [rad] point turns
};

/// The mobility manager's verdict on the run's command (mobility tasks only).
struct MobilityOutcome {
  std::string task;         ///< "autonav", "goto_waypoint", "guarded", "guarded_arc"
  std::string mode;         ///< the IDL mode ("autonav_visodom", ...)
  std::string expect;       ///< what the scenario expects ("reached", "NOPATH", ...)
  std::string outcome;      ///< what happened: "reached", a fault code, or "none" (no verdict)
  std::string state;        ///< "succeeded", "failed", "rejected", "interrupted"
  std::string fault;        ///< fault code name, "NONE" when there was none
  std::string fault_class;  ///< "none", "goal error", "motion error"
  std::string message;
  double distance_to_goal = -1;  ///< [m] as the service reported it
  std::uint32_t steps = 0, images = 0;
  double sim_start_s = 0, sim_end_s = 0;  ///< [s] command sent, terminal status heard
  /// Not in result.json (map.png shows them): the last goodness map and every decision.
  std::optional<GoodnessGrid> last_map;
  std::vector<ChosenArc> arcs;
  /// The command's keep-out zones (site frame [m]), for the judge; not in result.json.
  std::vector<std::vector<Eigen::Vector2d>> keep_out;
};

/// What one fault of the run's set (x-rover.faults, the scenario's `faults:`) did, from the
/// services' sys/fault_event records (docs/faults.md "Records").
struct InjectedFault {
  std::uint32_t id = 0;
  std::string name;         ///< the spec's label ("" if none)
  std::string kind;         ///< "drop", "delay", ...
  std::string topic;        ///< the topic pattern
  std::string service;      ///< the service glob
  std::string side;         ///< "writer", "reader", "both"
  std::string description;  ///< FaultSpec::Describe()
  double start_s = -1;      ///< [s] run clock when its window opened in a service; < 0: never
  double end_s = -1;        ///< [s] run clock when it ended; < 0: still active at the end
  std::uint64_t samples_seen = 0;  ///< samples of its endpoints while active, all services
  std::uint64_t samples_hit = 0;   ///< samples it touched (dropped, delayed, changed, ...)
  std::vector<std::string> services;  ///< where it started
};

/// One line: "fault 1 drop dl/pose (writer of *): 20.0 s to 30.0 s, 55 of 110 samples hit in dl-pose".
std::string DescribeInjected(const InjectedFault& f);

/// A change of one service's health as its sys/health heartbeats said it (the runner records
/// the first heartbeat of each service and every change of health or message after it).
struct HealthChange {
  double t_s = 0;       ///< [s] run clock when the runner took the heartbeat
  std::string service;
  std::string health;   ///< "ok", "degraded", "failed", "stale"
  std::string message;  ///< the heartbeat's message ("" when healthy)
};

/// A kill -9 of a service during the run (RunOptions::kills) and whether it came back.
struct KillRecord {
  std::string service;
  double at_s = 0;          ///< [s] run clock, as asked
  double killed_s = -1;     ///< [s] run clock when it was killed; < 0: never (see error)
  double restarted_s = -1;  ///< [s] run clock when it ran again; < 0: not in the run
  std::string error;        ///< why it was not killed ("" when it was)
};

/// Where one service's time went in a run (its last heartbeat: runtime/activity.hpp).
struct ServiceTiming {
  std::string service;
  double cpu_s = 0;  ///< [s] CPU time of its process, every thread
  struct Activity {
    std::string name;
    double wall_s = 0;  ///< [s] wall time summed
    std::uint32_t count = 0;
  };
  std::vector<Activity> activities;  ///< physics, render, stereo, vo, planning, lockstep_wait...
};

struct RunResult {
  std::string scenario;
  std::uint32_t seed = 0;
  int domain = -1;
  bool pass = false;
  std::string failure;             ///< one line: why it failed ("" when it passed)
  std::vector<sim::judge::Criterion> criteria;
  std::vector<StepResult> steps;
  double distance_driven = 0;      ///< [m]
  double sim_time_s = 0;           ///< simulated seconds run
  double wall_time_s = 0;          ///< wall seconds of the whole run
  double startup_s = 0;            ///< wall seconds to bring the service set up
  double ready_s = 0;              ///< wall seconds from starting the set to every service ready
  double teardown_s = 0;           ///< wall seconds to stop it
  /// Per service, in name order: CPU time and the wall time of its named activities.
  std::vector<ServiceTiming> service_timing;
  double recording_mb = 0;         ///< [MB = 10^6 bytes] size of the run's recording
  std::string lockstep;            ///< "strict", "lead" or "off" (the scenario's sim.lockstep)
  std::uint64_t late_samples = 0;  ///< strict lock-step: samples that came a tick late (0 = exact)
  std::vector<sim::judge::ErrorSample> estimate_error;
  std::vector<sim::judge::ErrorSample> odometry_only_error;  ///< the dl/pose_odometry baseline
  /// Measured, not judged (sim::judge::Verdict::figures): estimate and odometry-only errors.
  std::vector<sim::judge::Criterion> figures;
  /// Rocks over the traversable height the rover touched: where, by which part, when (the map
  /// marks them).
  std::vector<sim::judge::HazardContact> hazard_contacts;
  std::vector<std::string> crashes;  ///< "service: how it ended; last log line"
  std::string run_dir;
  /// Distinct sim/truth writers heard: 1 unless another run's simulator leaked into this one.
  int truth_publishers = 0;
  /// FNV-1a digest of the world's heights and rock list (same seed -> same digest).
  std::string terrain_digest;
  /// Paths of the truth (x, y) and estimated (x, y) tracks, downsampled, for plots and replay.
  std::vector<std::array<double, 3>> truth_track;     ///< t, x, y
  std::vector<double> truth_yaw;  ///< [rad] the yaw at each truth_track point (may be empty)
  std::vector<std::array<double, 3>> estimate_track;  ///< t, x, y
  std::vector<std::array<double, 3>> odometry_only_track;  ///< t, x, y (dl/pose_odometry)
  /// Set by the mobility tasks (autonav, goto_waypoint, guarded, guarded_arc).
  std::optional<MobilityOutcome> mobility;
  /// A phased task's phases (lander_return: MID_RANGE, CLOSE_RANGE, ...): the sim time [s] each
  /// began, in order; the map colours the driven path by phase.
  std::vector<std::pair<double, std::string>> phases;
  /// Every fault of the run's set, in id order, with what it did.
  std::vector<InjectedFault> faults;
  /// The services' health over the run (sys/health), in arrival order; at most
  /// kMaxHealthChanges are kept (`health_changes_dropped` counts the rest).
  std::vector<HealthChange> health_changes;
  std::uint64_t health_changes_dropped = 0;
  std::vector<KillRecord> kills;
  static constexpr std::size_t kMaxHealthChanges = 500;
};

nlohmann::json ToJson(const RunResult& r);
Result<RunResult> RunResultFromJson(const nlohmann::json& j);

/// Mean, 95th percentile and worst (max) of one figure across runs.
struct FigureStats {
  std::string name, unit;
  double mean = 0, p95 = 0, worst = 0;
  int count = 0;
  /// A criterion (it has a limit and a verdict per run) rather than a measured figure.
  bool criterion = false;
  double limit = 0;  ///< criterion: its threshold (the first run's; NaN if the runs disagree)
  int passing = 0;   ///< criterion: runs in which it held
};

/// The run was cut off by stopping roverctl (its failure starts with "interrupted"): it says
/// nothing about the stack, so a summary counts it apart and keeps it out of the figures.
bool Interrupted(const RunResult& r);

struct CampaignSummary {
  std::string scenario;
  int runs = 0, passed = 0;
  int interrupted = 0;   ///< runs cut off (Interrupted): not in `passed`, the rate or the figures
  double pass_rate = 0;  ///< passed / (runs - interrupted)
  /// Runs whose field had a contact-free path (the figure `passable` = 1; judging.hpp), and how
  /// many of them passed; both 0 when no run measured it.
  int passable = 0, passed_passable = 0;
  /// The criteria first (limit, runs passing), then the measured figures (a figure that is also
  /// a criterion is listed once, as the criterion), then the run timings.
  std::vector<FigureStats> figures;
  double wall_time_s = 0;            ///< of the whole campaign
  double sim_seconds_per_wall_second = 0;
  double runs_per_hour = 0;
  /// Where the time went, mean per run: each service's CPU time, then each activity's wall time
  /// ("render (rover-sim)"), with its share of the runs' mean wall time.
  struct TimeShare {
    std::string name;
    double mean_s = 0;
    double share = 0;  ///< of the mean run wall time
  };
  std::vector<TimeShare> time_shares;
  double recording_mb_mean = 0;  ///< [MB] per run
};

CampaignSummary Summarize(const std::vector<RunResult>& runs, double campaign_wall_s);
nlohmann::json ToJson(const CampaignSummary& s);

/// JUnit XML: one <testsuite> per scenario, one <testcase> per run, <failure> for failed runs.
std::string ToJunitXml(const std::vector<RunResult>& runs, const std::string& suite_name);

/// A seed of a campaign without a result.json: under way when the campaign stopped (its run
/// folder exists) or never started.
struct MissingRun {
  std::uint32_t seed = 0;
  bool started = false;
};

/// The seeds of a campaign of `scenario` in `dir` that none of `runs` covers.
std::vector<MissingRun> MissingRuns(const std::string& dir, const std::string& scenario,
                                    const std::vector<std::uint32_t>& seeds,
                                    const std::vector<RunResult>& runs);

/// The human-readable table: one line per run (then one per injected fault), the pass count ("x: 3/4 passed (75%)", then
/// "; 2 of 6 seeds have no result" and one line per missing seed), the results left out of the
/// report (`ignored`, one line each), then the statistics.
std::string FormatSummaryTable(const std::vector<RunResult>& runs, const CampaignSummary& s,
                               const std::vector<MissingRun>& missing = {},
                               const std::vector<std::string>& ignored = {});

/// Reads every `*/result.json` under a run folder (for `roverctl report`).
Result<std::vector<RunResult>> LoadRunFolder(const std::string& dir);
/// The result.json of every run sub-folder of `dir`, by seed, without requiring `dir` to be a
/// campaign folder (a fault campaign's per-fault folders). Errors: no such folder, a result
/// that does not parse (naming the file).
Result<std::vector<RunResult>> LoadRunResults(const std::string& dir);

/// A campaign folder read back (campaign.json names its scenario and seeds): its runs, their
/// summary (with the campaign's wall time from summary.json, 0 if that is missing) and the
/// table `roverctl run` printed. Only results of the campaign's scenario and seeds count; others
/// (a folder mixed by hand, or older runs of seeds the last campaign did not run) are listed in
/// `ignored`, and the campaign's seeds without a result in `missing`.
struct CampaignReport {
  std::vector<RunResult> runs;
  CampaignSummary summary;
  std::vector<MissingRun> missing;
  std::vector<std::string> ignored;  ///< "<folder> (why)"
  std::string table;
  /// At least one run, every seed has a result, and every run passed (`roverctl report` exits
  /// 0 only then).
  bool all_passed = false;
  /// The roverctl that runs the campaign is still alive (campaign.json `pid`, no summary.json
  /// yet): the table holds the runs finished so far.
  bool running = false;
};
Result<CampaignReport> LoadCampaignReport(const std::string& dir);
/// True if `dir` looks like a campaign folder written by `roverctl run` (has campaign.json).
bool IsRunFolder(const std::string& dir);

}  // namespace rover::deploy
