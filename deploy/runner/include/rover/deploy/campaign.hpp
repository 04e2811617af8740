#pragma once
/// @file
/// A campaign: one scenario over a range of seeds, `jobs` runs at a time, each on its own DDS
/// domain. On a terminal it shows a progress bar with ETA and one live line per running job;
/// otherwise (CI) plain lines. The campaign folder holds campaign.json, summary.json,
/// junit.xml and one folder per run. Ctrl-C stops the running jobs, keeps finished results and
/// writes the summary of what finished.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/runner.hpp"
#include "rover/deploy/scenario.hpp"

namespace rover::deploy {

struct CampaignOptions {
  std::vector<std::uint32_t> seeds;
  int jobs = 1;
  std::string out_dir;
  std::string bin_dir;
  std::string dds_config_uri;
  bool security = false;      ///< RunOptions::security for every run
  std::string security_dir;   ///< RunOptions::security_dir
  bool tty = false;                      ///< draw a progress bar (stderr is a terminal)
  const std::atomic<bool>* abort = nullptr;
  /// Runs one seed; RunScenario unless set (tests run the campaign without processes).
  std::function<Result<RunResult>(const Scenario&, std::uint32_t seed, const RunOptions&)> run_one;
};

struct CampaignResult {
  std::vector<RunResult> runs;           ///< finished runs, by seed
  CampaignSummary summary;
  bool interrupted = false;
  std::vector<std::string> errors;       ///< runs that could not be made at all
  std::vector<MissingRun> missing;       ///< seeds without a result (interrupted, errors)
  bool all_passed() const;
};

/// Checks the output folder: it may not exist, be empty, or be an earlier campaign folder of the
/// same scenario (`scenario`; "" accepts any): a folder holds one scenario's runs, so that a
/// report never mixes two.
Status CheckOutputFolder(const std::string& dir, const std::string& scenario = "");

Result<CampaignResult> RunCampaign(const Scenario& scenario, const CampaignOptions& options);

/// Fills `result`'s summary (with `wall_s`) and missing seeds from its runs and writes the
/// campaign folder's summary.json, junit.xml and summary.txt: what every backend ends with.
void WriteCampaignFiles(const std::string& dir, const std::string& scenario,
                        const std::vector<std::uint32_t>& seeds, double wall_s,
                        CampaignResult* result);

}  // namespace rover::deploy
