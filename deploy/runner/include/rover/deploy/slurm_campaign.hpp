#pragma once
/// @file
/// A campaign through Slurm (`roverctl run SCENARIO --seeds A..B --backend slurm`): one array job,
/// one task per seed, each task running the same single run as `--jobs` does
/// (`roverctl run-task`, RunScenario into the campaign folder, on a DDS domain leased on its
/// node so that tasks sharing a node never collide). roverctl then waits, printing finished /
/// running / pending on every change (or returns at once with `detach`, and `roverctl report`
/// gathers later), and writes the campaign folder's summary.txt, summary.json and junit.xml as
/// a local campaign does.
///
/// Shared storage: the build (roverctl and the services) and the campaign folder must be at the
/// same paths on every node; a task whose node lacks the build fails at once with a message in
/// its log (slurm/task-<index>.log) and shows as FAILED with its exit code.
///
/// A task that Slurm ended without a result (CANCELLED, TIMEOUT, NODE_FAIL, OUT_OF_MEMORY,
/// FAILED) gets a result.json that says so (failure "slurm: TIMEOUT, exit code 0:15"), so the
/// summary shows it as what it was, not as a missing row. Resubmitting only those and the seeds
/// with no result is one command, which `roverctl report` prints.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rover/base/process.hpp"
#include "rover/base/status.hpp"
#include "rover/deploy/campaign.hpp"
#include "rover/deploy/scenario.hpp"

namespace rover::deploy {

/// sbatch settings: flags of `roverctl run`, or the compose file's `x-rover.slurm` block.
struct SlurmOptions {
  std::string partition;                 ///< --partition; "" = the cluster's default
  std::string time_limit;                ///< --time per task (Slurm's forms: "30", "1:00:00")
  int cpus_per_task = 1;                 ///< --cpus-per-task
  std::vector<std::string> sbatch_args;  ///< more sbatch options, passed as they are
  bool detach = false;                   ///< submit and return; `roverctl report` gathers
  double poll_s = 2.0;                   ///< [s] how often squeue / scontrol are asked
  /// InvalidArgument naming the flag: cpus_per_task outside [1, 256], a time limit with
  /// characters other than digits, ':' and '-', poll_s outside [0.2, 60].
  Status Validate() const;
};

struct SlurmCampaignOptions {
  std::vector<std::uint32_t> seeds;
  std::string out_dir;        ///< the campaign folder (made absolute)
  std::string roverctl;       ///< this roverctl, by absolute path (the tasks run it)
  bool security = false;      ///< `run --security` for every task
  std::string security_dir;
  SlurmOptions slurm;
  const std::atomic<bool>* abort = nullptr;  ///< stop waiting (the job keeps running)
  /// Runs a Slurm command (sbatch, squeue, scontrol); RunCommand unless set (tests).
  std::function<Result<CommandOutput>(const std::vector<std::string>&)> run;
};

/// One task's state as Slurm reports it.
struct SlurmTask {
  std::uint32_t seed = 0;
  std::string state = "PENDING";  ///< PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, ...
  std::string exit_code;          ///< "0:0" (exit:signal), once ended
  bool ended() const;
};

/// Writes slurm/job.sh into the folder and submits it; returns the job id. Errors: sbatch
/// missing (Slurm not installed: one line naming what is missing, nothing submitted), the
/// controller down or a partition refused (sbatch's own message, with the flag that caused it).
Result<std::string> SubmitSlurmCampaign(const Scenario& scenario,
                                        const SlurmCampaignOptions& options);

/// Asks Slurm for every task of `job_id` (squeue for those queued or running, scontrol for the
/// ended ones still remembered). Tasks Slurm no longer knows keep their last state.
Status QuerySlurmTasks(const SlurmCampaignOptions& options, const std::string& job_id,
                       std::map<std::uint32_t, SlurmTask>* tasks);

/// Waits for the job (printing "slurm job 12: 3 finished, 1 running, 0 pending" on every
/// change), gives every task that ended without a result its result.json, and writes the
/// summary files. Returns the campaign as RunCampaign would.
Result<CampaignResult> WaitSlurmCampaign(const Scenario& scenario,
                                         const SlurmCampaignOptions& options,
                                         const std::string& job_id);

/// For `roverctl report` on a Slurm campaign folder (campaign.json "backend": "slurm"): asks
/// Slurm once, writes results for tasks that ended without one, and returns how many tasks are
/// still queued or running (0: the summary files were written).
Result<int> GatherSlurmCampaign(const std::string& dir);

/// The command that resubmits the seeds of `dir` without a real result (none, or one Slurm
/// ended): "roverctl run S --backend slurm --seeds 3,4 --out DIR"; "" when there are none.
std::string ResubmitCommand(const std::string& dir);

}  // namespace rover::deploy
