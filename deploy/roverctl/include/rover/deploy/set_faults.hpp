#pragma once
/// @file
/// The faults of a service set: `x-rover.faults` of a compose file and `faults:` of a scenario
/// (docs/faults.md). They are parsed and validated when the file is read, so that a bad spec
/// stops everything before a process starts ("deploy/x.yaml:14: key 'kind': 'dorp' is not a
/// fault kind ..."); the set's list is then handed to every service as one file in
/// ROVER_FAULTS (the supervisor writes it into the set's state folder), with
/// ROVER_FAULTS_EPOCH_NS = the set's start under wall time (under `clock: sim`, start_s counts
/// from simulated time zero).

#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/runtime/fault_engine.hpp"
#include "rover/runtime/fault_spec.hpp"

namespace YAML {
class Node;
}

namespace rover::deploy {

/// One fault of a set.
struct SetFault {
  faults::FaultSpec spec;  ///< validated; spec.source and spec.line say where it was written
  std::string yaml;        ///< its map as written, in YAML flow style (for the services' file)
};

/// `node` in YAML flow style, on one line ("{kind: drop, topic: dl/pose}").
std::string FlowYaml(const YAML::Node& node);

/// Parses a YAML list of fault maps from the document `file` (lines are the document's).
/// Nothing is returned unless every fault is valid; errors are one line with file, line, key.
Result<std::vector<SetFault>> ParseSetFaults(const YAML::Node& list, const std::string& file);

/// Appends `more` (e.g. a scenario's faults) to `faults` (the compose file's): a fault of
/// `more` that did not set `id` is renumbered to the next id above every id in use; an `id` it
/// set that is already in use is an error naming its file and line.
Status AppendSetFaults(std::vector<SetFault> more, std::vector<SetFault>* faults);

/// The ROVER_FAULTS file of a set: a YAML list, one fault per line, each with its id.
std::string SetFaultsFileText(const std::vector<SetFault>& faults);

/// <state_dir>/faults.yaml.
std::string SetFaultsPath(const std::string& state_dir);

/// Writes SetFaultsFileText to SetFaultsPath(state_dir) (creating the folder).
Status WriteSetFaults(const std::vector<SetFault>& faults, const std::string& state_dir);

/// Whether a service's record is about a fault that acts there: every service holds every fault
/// of the set, and its ADDED and LISTED records end with "(not for this service)" where the
/// fault's `service` glob does not match it.
bool AppliesInService(const faults::FaultRecord& record);

}  // namespace rover::deploy
