#pragma once
/// @file
/// Fault specifications: what the fault seam injects, into which topics of which services,
/// when, and how often (docs/faults.md has the keys, examples and semantics).
///
/// A spec comes from YAML (a file given to services in ROVER_FAULTS, `x-rover.faults` of a
/// compose file, `faults:` of a scenario) or from a sys/fault_control message, and is validated
/// before anything is applied: an unknown kind or key, a topic pattern matching no catalog
/// topic, a field path the topic's type does not have, a probability outside [0, 1] are
/// one-line errors naming the source, line and key, e.g.
///   faults.yaml:7: key 'field': rover::dl::PoseEstimate has no field 'pose.positon.x'
///   (nearest: pose.position.x, pose.position, pose.orientation.x)
///
/// Time: `start_s` counts on the run clock from the run's epoch (run clock zero under
/// sim/clock; under wall time the epoch roverctl passes in ROVER_FAULTS_EPOCH_NS, else the
/// service's start), or, with StartMode::kOnReceipt, from the moment a service receives it.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"

namespace rover::faults {

enum class FaultKind { kDrop, kDelay, kDuplicate, kReorder, kFreeze, kCorrupt, kNoise, kBias, kPartition };
/// "drop", "delay", ...
const char* FaultKindName(FaultKind kind);

/// Which endpoints of the matching services a fault acts on.
enum class Side { kWriter, kReader, kBoth };
const char* SideName(Side side);

/// How kCorrupt changes a field.
enum class Corruption {
  kNan,         ///< quiet NaN (floating-point fields)
  kPosInf,      ///< +inf (floating-point fields)
  kNegInf,      ///< -inf (floating-point fields)
  kValue,       ///< the spec's `value` (numbers, enums, booleans; integers must fit the type)
  kOutOfRange,  ///< one past an enum's last literal; an integer type's maximum; a float's largest finite value
  kBitFlip,     ///< flip `bits` random bits of the value (one character of a string)
};
const char* CorruptionName(Corruption c);

enum class DelayDistribution { kFixed, kUniform, kNormal, kExponential };
const char* DelayDistributionName(DelayDistribution d);

/// A delay in seconds of run-clock time; draws below zero are clamped to zero.
struct DelaySpec {
  DelayDistribution distribution = DelayDistribution::kFixed;
  double a_s = 0.0;  ///< fixed: the delay; uniform: min; normal, exponential: mean
  double b_s = 0.0;  ///< uniform: max; normal: standard deviation
  bool given = false;  ///< whether the spec set it (reorder uses 1 s otherwise)
};

enum class StartMode { kRunEpoch, kOnReceipt };

/// One fault.
struct FaultSpec {
  std::uint32_t id = 0;       ///< unique per set; YAML assigns 1, 2, ... in file order unless `id` is given
  std::string name;           ///< optional label
  FaultKind kind = FaultKind::kDrop;
  /// Globs over topic names, comma-separated ("ddl/*", "dl/pose,dl/pose_odometry"); an item
  /// starting with '!' excludes. Partition defaults to "*,!sim/*".
  std::string topic;
  std::string service = "*";  ///< glob over service names
  Side side = Side::kWriter;  ///< partition defaults to kBoth
  std::string field;          ///< corrupt, noise, bias: a field path (type_layout.hpp)
  Corruption corruption = Corruption::kNan;
  double value = 0.0;         ///< corrupt kValue: the value; bias: the offset [field units]
  double sigma = 0.0;         ///< noise: standard deviation [field units]
  std::uint32_t bits = 1;     ///< corrupt kBitFlip: bits flipped per value, [1, 64]
  std::uint32_t copies = 1;   ///< duplicate: extra copies per hit sample, [1, 100]
  double probability = 1.0;   ///< [0, 1]: share of the samples hit (not for freeze, partition)
  DelaySpec delay;            ///< delay: the delay; reorder: longest hold (default 1 s)
  StartMode start_mode = StartMode::kRunEpoch;
  double start_s = 0.0;       ///< [s] run clock, >= 0
  double duration_s = 0.0;    ///< [s] run clock; 0 = until removed
  std::uint64_t seed = 1;     ///< same seed, same samples hit (docs/faults.md "Determinism")

  /// Where it was written, for messages: "faults.yaml" and the line of the fault and of each key.
  std::string source;
  int line = 0;
  std::map<std::string, int> key_lines;

  /// Checks the spec against itself, the topic catalog and the types of the topics it
  /// matches. Errors are one line: "<source>:<line>: key '<key>': <what>".
  Status Validate() const;
  /// One line, e.g. "drop 50% of dl/pose at the writers of every service, 10 s for 5 s, seed 3".
  std::string Describe() const;
};

/// `*` matches any run of characters (including '/'), `?` one character.
bool GlobMatch(std::string_view glob, std::string_view text);
/// Whether `topic` matches a comma-separated pattern list (FaultSpec::topic).
bool TopicMatches(std::string_view patterns, std::string_view topic);
/// The catalog topics a pattern list matches, in catalog order. The fault topics themselves
/// (sys/fault_control, sys/fault_event) are never matched: the seam leaves them alone.
std::vector<std::string> MatchingCatalogTopics(std::string_view patterns);
/// Whether the seam leaves `topic` alone (the fault control and record topics).
bool IsFaultInfrastructure(std::string_view topic);

/// Parses YAML text holding a list of faults, or a map whose `faults` key holds one. Nothing is
/// returned unless every fault is valid. `source` names the text in messages (a file path).
Result<std::vector<FaultSpec>> ParseFaults(std::string_view yaml_text, std::string_view source);
/// Parses one fault given as a YAML map (e.g. `{kind: drop, topic: dl/pose, probability: 0.5}`).
Result<FaultSpec> ParseFault(std::string_view yaml_text, std::string_view source);
/// Reads and parses a faults file.
Result<std::vector<FaultSpec>> LoadFaultsFile(const std::string& path);

/// Fills a FAULT_ACTION_ADD control message (header left to the sender). Preconditions:
/// spec.Validate() is ok.
void ToControl(const FaultSpec& spec, rover_sys_FaultControl* out);
/// The spec an ADD message carries, validated; errors name "sys/fault_control" and the fault id.
Result<FaultSpec> FromControl(const rover_sys_FaultControl& msg);

rover_sys_FaultKind ToIdl(FaultKind kind);

}  // namespace rover::faults
