#pragma once
/// @file
/// Checks for hand-written YAML files (compose files, scenarios, and the sequence and fault files
/// to come): the one form of their error messages, each naming the file, the line and the key.
///
///   "deploy/x.yaml:12: services.loco: unknown key 'comand' (did you mean 'command'?) (known: ...)"
///   "s.yaml:4: criteria.max_tilt_deg: 95 is out of range [0.1, 89.9]"
///   "s.yaml:3: task.steps[].primitive: 'fly' is not one of: straight, arc (did you mean ...)"
///
/// `where` / `key` arguments are dotted paths as the user would write them ("task.steps[]",
/// "criteria.target"); an empty `where` means the top level of the file. Lines are 1-based.
/// Library `rover_yaml` (links yaml-cpp publicly; rover_base itself stays YAML-free in its API).

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/range_check.hpp"
#include "rover/base/status.hpp"

namespace rover::yaml {

/// The 1-based line of `n` in its file.
int Line(const YAML::Node& n);

/// Makes the errors of one file: "<file>:<line>: <what>", InvalidArgument.
class FileErrors {
 public:
  explicit FileErrors(std::string file) : file_(std::move(file)) {}
  Status At(const YAML::Node& n, std::string_view what) const { return At(Line(n), what); }
  Status At(int line, std::string_view what) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// Parses `text`; a syntax error is "<file>:<line>: malformed YAML: <yaml-cpp's reason>".
Result<YAML::Node> Load(const std::string& text, const FileErrors& err);

struct KeyRules {
  bool require_map = true;        ///< a node that is not a map is "<where>: expected a map"
  bool allow_extensions = false;  ///< "x-..." keys are always accepted (Compose extensions)
};

/// Every key of `map` is one of `known` and appears once. Errors, at the key's line:
/// "<where>: unknown key 'k' (did you mean 'kk'?) (known: a, b, c)",
/// "<where>: duplicate key 'k'".
Status CheckKeys(const YAML::Node& map, std::string_view where,
                 const std::vector<std::string>& known, const FileErrors& err, KeyRules rules = {});

/// `map` has `key`; else "<where>: missing 'key'" at the map's line.
Status RequireKey(const YAML::Node& map, std::string_view where, const std::string& key,
                  const FileErrors& err);

/// The text of a scalar, "" for anything else.
std::string ScalarText(const YAML::Node& n);

/// A finite number; else "<key>: expected a finite number, got '<text>'" at its line.
Result<double> Number(const YAML::Node& n, std::string_view key, const FileErrors& err);

/// Reads `parent[name]` into *out when present (else leaves *out alone), checking it is a finite
/// number inside `bounds`: "<where>.<name>: 95 is out of range [0.1, 89.9]". `present`, when
/// given, says whether the key was there.
Status OptionalNumber(const YAML::Node& parent, const std::string& name, std::string_view where,
                      const Bounds& bounds, const FileErrors& err, double* out,
                      bool* present = nullptr);
/// The same with a closed range [lo, hi].
inline Status OptionalNumber(const YAML::Node& parent, const std::string& name,
                             std::string_view where, double lo, double hi, const FileErrors& err,
                             double* out, bool* present = nullptr) {
  return OptionalNumber(parent, name, where, Bounds::Closed(lo, hi), err, out, present);
}

/// `n` is a scalar equal to one of `choices`; else
/// "<key>: 'v' is not one of: a, b, c (did you mean 'b'?)" at its line.
Result<std::string> OneOf(const YAML::Node& n, std::string_view key,
                          const std::vector<std::string>& choices, const FileErrors& err);

/// Flattens nested maps into dotted keys ("ekf.gyro_noise" -> "0.001"), prefixed by `prefix`.
/// Scalars keep their text, null is "~", and sequences are written in flow style ("[1, 2]") so
/// that each value is one line of YAML.
void Flatten(const YAML::Node& n, const std::string& prefix,
             std::map<std::string, std::string>* out);

/// "a, b, c".
std::string JoinNames(const std::vector<std::string>& names, std::string_view separator = ", ");

}  // namespace rover::yaml
