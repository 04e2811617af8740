// roverctl's recording commands: `record`, `replay`, `info`, and the recording of a set that is
// up with x-rover.record. roverctl_main.cpp parses the command line and finds the project;
// these do the work (core/recording).
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "rover/base/status.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/recording/bus_recorder.hpp"
#include "rover/recording/record_options.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::deploy {

/// The running set a command works on (from its state file and compose file).
struct TargetSet {
  std::string project;  ///< "" when only a domain was given
  int domain = -1;
  std::string clock;    ///< "sim" or "wall"; "" = unknown (a bare domain)
  std::map<std::string, std::string> qos;  ///< x-rover.qos
  std::function<bool()> alive;             ///< false once the set is down; null = unknown
  std::string security_dir;                ///< a secured set's keys; "" = open
};

struct RecordArgs {
  TargetSet target;
  recording::RecordOptions record;  ///< record.path = -o
  std::string clock = "auto";       ///< auto | sim | wall
  double duration_s = 0;            ///< [s] run clock; 0 = until Ctrl-C
  const std::atomic<bool>* stop = nullptr;
};

/// `roverctl record`: exit code 0 (recorded), 1 (the recording failed), 2 (bad arguments).
int RunRecord(const RecordArgs& args, std::ostream& out, std::ostream& err);

struct ReplayArgs {
  std::string file;
  TargetSet target;
  recording::TopicFilter topics;
  double rate = 1.0;
  bool clock = true;
  bool force = false;                  ///< replay onto a domain where others publish its topics
  bool accept_schema_changes = false;
  double discovery_s = 1.5;            ///< [s] wall: how long to look for other publishers
  const std::atomic<bool>* stop = nullptr;
};

/// `roverctl replay`: exit code 0 (replayed), 1 (refused: domain in use; or interrupted or a
/// DDS failure), 2 (bad arguments or a bad file: nothing was published).
int RunReplay(const ReplayArgs& args, std::ostream& out, std::ostream& err);

/// `roverctl info FILE`: 0, or 2 for a file that cannot be read.
int RunInfo(const std::string& file, std::ostream& out, std::ostream& err);

/// The recording of a set that is up with x-rover.record (on its own participant).
class SetRecording {
 public:
  /// Null when the project records nothing. `state_dir` holds the default file.
  static Result<std::unique_ptr<SetRecording>> Start(const ComposeProject& project, int domain,
                                                     const std::string& state_dir);
  /// Ok while recording; the first I/O error otherwise.
  Status health() const { return recorder_->health(); }
  const std::string& path() const { return recorder_->path(); }
  /// Stops and closes the file.
  recording::RecordingReport Stop() { return recorder_->Stop(); }

 private:
  dds::Participant participant_;
  std::unique_ptr<recording::BusRecorder> recorder_;
};

/// "recorded 1234 messages on 18 topics to run.mcap (2.1 MB, 60.0 s of run clock)" and, when
/// it happened, the size cap and lost samples, one line each.
std::string DescribeReport(const recording::RecordingReport& report);

}  // namespace rover::deploy
