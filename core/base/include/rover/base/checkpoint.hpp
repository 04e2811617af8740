#pragma once
/// @file
/// Checkpoints of stateful services: what a service restarted by its supervisor (roverctl,
/// after a crash or kill -9) resumes from, instead of silently starting over. No DDS.
///
/// A checkpoint belongs to one supervised service set: it lives at
/// `$ROVER_STATE_DIR/checkpoints/<service>.ckpt` and records the set's `$ROVER_SET_ID`
/// (roverctl sets both; supervisor.hpp). A checkpoint written under another set id (an earlier
/// `up` of the same project) is not this set's and is ignored, so a fresh start never resumes
/// from a stale run. Outside a supervised set (either variable missing) there is no store.
///
/// Format: text, one `key value` per line (the value runs to the end of the line), first line
/// `rover-checkpoint 1`, then `set_id`. Saves are atomic (written to a temporary file, then
/// renamed), so a kill -9 mid-save leaves the previous checkpoint.

#include <map>
#include <optional>
#include <string>

#include "rover/base/status.hpp"

namespace rover {

class CheckpointStore {
 public:
  /// The store of service `service` from $ROVER_STATE_DIR and $ROVER_SET_ID; disabled when
  /// either is unset or empty.
  static CheckpointStore FromEnvironment(const std::string& service);
  /// A store at `path` for set `set_id` (tests, tools).
  CheckpointStore(std::string path, std::string set_id);
  CheckpointStore() = default;

  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }
  const std::string& set_id() const { return set_id_; }

  /// Writes `fields` (keys without spaces or newlines, values without newlines) atomically.
  /// Errors: disabled store, a bad key or value, the file cannot be written (names the path).
  Status Save(const std::map<std::string, std::string>& fields) const;
  /// This set's checkpoint: nullopt when there is none (or it is another set's). Errors: the
  /// file is not a checkpoint (names the path and line).
  Result<std::optional<std::map<std::string, std::string>>> Load() const;
  /// Removes the checkpoint (a clean stop: the next start is a fresh one).
  void Remove() const;

 private:
  std::string path_;
  std::string set_id_;
};

}  // namespace rover
