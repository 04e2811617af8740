#pragma once
/// @file
/// Fault specs from an already-parsed YAML node, for tools that read a larger YAML document
/// (roverctl: `x-rover.faults` of a compose file, `faults:` of a scenario). Line numbers in
/// errors are those of the node's document. Include only where yaml-cpp is linked.

#include <yaml-cpp/yaml.h>

#include <string_view>
#include <vector>

#include "rover/runtime/fault_spec.hpp"

namespace rover::faults {

/// `node` is a list of faults, or a map whose `faults` key holds one; `source` names the
/// document in messages. Nothing is returned unless every fault is valid.
Result<std::vector<FaultSpec>> ParseFaults(const YAML::Node& node, std::string_view source);

}  // namespace rover::faults
