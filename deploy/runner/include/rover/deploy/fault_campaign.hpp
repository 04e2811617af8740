#pragma once
/// @file
/// A fault campaign (`roverctl run SCENARIO --faults FILE`): every fault of FILE runs alone over
/// the given seeds, plus one fault-free baseline run per seed, and each fault run is judged
/// against its baseline for detection, response, safety and the goal (docs/faults.md
/// "Campaigns" has the definitions). The campaign folder holds campaign.json and campaign.txt
/// (the table), summary.txt (the table, ending with the detection and safe shares), and one
/// folder per fault (`baseline/`, `01-<name>/`, ...) with the usual run folders inside.
///
/// The judging of one run and the table are DDS-free (they read RunResult, as result.json holds
/// it), so `roverctl report DIR` rebuilds the same table from the run folders.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/runner.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/deploy/set_faults.hpp"

namespace rover::deploy {

/// One fault of a campaign file: a topic fault, or a kill -9 of a service.
struct CampaignFault {
  std::string label;  ///< its folder: "01-drop-half-of-dl-pose" (index, then the name's slug)
  std::string name;   ///< the spec's `name`, else its description
  SetFault fault;     ///< topic faults: validated against the catalog
  std::optional<ServiceKill> kill;  ///< kill entries (then `fault` is unused)
  std::string yaml;   ///< the entry as written, in YAML flow style
  std::string source;  ///< "file:line" of the entry
  /// Run clock of the injection as written: the fault's start_s, or the kill's at_s.
  double start_s() const { return kill ? kill->at_s : fault.spec.start_s; }
};

/// Parses a campaign file: a YAML list of faults (or a map whose `faults:` is that list), each
/// with the keys of a scenario's `faults:` (docs/faults.md), or a kill entry
/// `{name: ..., kill: {service: dl-pose, at_s: 40}}` (kill -9 of that service at that run-clock
/// time; the supervisor restarts it by its restart policy). Every entry is checked before
/// anything is returned; errors are one line with file, line and key. Kill services are
/// checked against the scenario's compose file by RunFaultCampaign (CheckCampaignKills).
Result<std::vector<CampaignFault>> ParseCampaignFaults(const std::string& text,
                                                       const std::string& file);
Result<std::vector<CampaignFault>> LoadCampaignFaults(const std::string& path);

/// Every kill entry names a service of the scenario's compose file.
Status CheckCampaignKills(const Scenario& scenario, const std::vector<CampaignFault>& faults);

/// What the stack did about a fault, from one run's result (docs/faults.md "Campaigns").
struct Detection {
  bool detected = false;
  double t_s = -1;  ///< [s] run clock of the first detection
  std::string by;   ///< "sys/health dl-pose stale: ..." / "apl/mobility_status IMG: ..." / ...
};
/// The first detection at or after run-clock `after_s`: a heartbeat going degraded, failed or
/// stale with a reason, a mobility command ending with a fault, or a drive step failed or
/// rejected by the stack.
Detection FirstDetection(const RunResult& run, double after_s);
/// "crashed" (a service crashed), "stopped" (the stack ended the motion: a mobility fault or a
/// failed / rejected drive step at or after `after_s`), "restarted" (a killed service ran
/// again), "degraded" (detected, motion went on), "none".
std::string Response(const RunResult& run, double after_s);
/// No hazard contact, tilt within the scenario's max_tilt, no keep-out entry (the judge's
/// criteria). `why` says what was not (or "not judged: ..." when the run ended before judging).
bool IsSafe(const RunResult& run, std::string* why = nullptr);
/// Mobility tasks: the outcome is "reached". Directed tasks: every step done and, when judged,
/// final_position_error within its tolerance.
bool GoalReached(const RunResult& run);

/// One row of the table: a fault (or the baseline) on one seed.
struct CampaignRow {
  std::string fault;  ///< label; "baseline"
  std::string name;
  std::uint32_t seed = 0;
  double fault_start_s = 0;  ///< [s] run clock: the services' reported start, else the spec's
  bool has_result = false;   ///< false: the run is missing (interrupted, error)
  bool pass = false;
  std::string failure;
  bool detected = false;
  double detection_delay_s = -1;  ///< [s] first detection minus fault_start_s
  std::string detected_by;
  std::string response;
  bool safe = false;
  std::string unsafe_why;
  bool goal = false;
  double wall_time_s = 0;
  std::uint64_t samples_hit = 0;
  /// The baseline run of the same seed: its goal and safety, and whether it "detected"
  /// something after the same run-clock time (a false alarm there means the fault run's
  /// detection may not be about the fault).
  bool baseline_has_result = false;
  bool baseline_goal = false, baseline_safe = false, baseline_pass = false;
  bool baseline_detected = false;
  /// Goal, safety or pass differ from the baseline's.
  bool differs = false;
};

struct FaultCampaignTable {
  std::string scenario;
  std::string faults_file;
  std::vector<std::uint32_t> seeds;
  std::vector<CampaignFault> faults;
  std::vector<CampaignRow> rows;  ///< baseline rows (by seed), then each fault's (by seed)
  /// Fault rows that were detected or whose outcome differs from the baseline (the
  /// denominator of the detection share), of those the detected ones, and those detected
  /// within 1 s of run clock.
  int relevant = 0, detected = 0, detected_within_1s = 0;
  int fault_runs = 0, safe_runs = 0;  ///< fault rows with a result, and the safe ones
  int missing = 0;                    ///< rows without a result
  double wall_time_s = 0;
  std::vector<std::string> errors;
  bool interrupted = false;
};

/// The table from the runs' results (`results[label]` = that fault's runs; "baseline").
FaultCampaignTable MakeCampaignTable(const std::string& scenario, const std::string& faults_file,
                                     const std::vector<std::uint32_t>& seeds,
                                     const std::vector<CampaignFault>& faults,
                                     const std::map<std::string, std::vector<RunResult>>& results);
/// The text of campaign.txt and summary.txt: one line per row, then the shares (the last two
/// lines: detection, then safe).
std::string FormatCampaignTable(const FaultCampaignTable& table);
nlohmann::json ToJson(const FaultCampaignTable& table);

struct FaultCampaignOptions {
  std::vector<std::uint32_t> seeds;
  int jobs = 1;
  std::string out_dir;
  std::string bin_dir;
  std::string dds_config_uri;
  bool security = false;      ///< RunOptions::security for every run
  std::string security_dir;   ///< RunOptions::security_dir
  const std::atomic<bool>* abort = nullptr;
  /// Runs one seed; RunScenario unless set (tests run the campaign without processes).
  std::function<Result<RunResult>(const Scenario&, std::uint32_t seed, const RunOptions&)> run_one;
};

/// The folder may not exist, be empty, or be an earlier fault campaign of the same scenario.
Status CheckFaultCampaignFolder(const std::string& dir, const std::string& scenario);
/// True if `dir/campaign.json` says it is a fault campaign.
bool IsFaultCampaignFolder(const std::string& dir);

/// Runs the baseline and every fault over the seeds, `jobs` at a time, and writes the outputs.
/// Every fault must join the scenario's own `faults:` (ids) before anything starts.
Result<FaultCampaignTable> RunFaultCampaign(const Scenario& scenario, const std::string& faults_file,
                                            const std::vector<CampaignFault>& faults,
                                            const FaultCampaignOptions& options);

/// Rebuilds the table of a fault campaign folder from its run folders (`roverctl report`).
Result<FaultCampaignTable> LoadFaultCampaignReport(const std::string& dir);

}  // namespace rover::deploy
