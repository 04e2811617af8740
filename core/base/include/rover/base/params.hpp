#pragma once
/// @file
/// Declared, validated service parameters loaded from YAML files and `key=value` overrides.
///
/// A service declares every parameter it reads, with a type, a default (or Required()), a range
/// or a set of allowed values and a one-line doc. Loading rejects unknown keys, wrong types and
/// malformed YAML; Validate() rejects out-of-range and missing values. Every error names the
/// source (file and line, or the command-line override) and the key, e.g.
///   params/drive.yaml:12: key 'max_tilt_deg': 95 is out of range [0, 45]
///
/// YAML layout: a map; nested maps flatten to dotted keys (`ekf: {gyro_noise: 1e-4}` sets
/// `ekf.gyro_noise`). A top-level key equal to the service name may wrap the whole map, so one
/// file can hold the parameters of several services.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rover/base/status.hpp"

namespace rover {

using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

enum class ParamType { kBool, kInt, kDouble, kString, kDoubleList };
const char* ParamTypeName(ParamType t);

/// Where a parameter's value came from.
struct ParamOrigin {
  std::string source = "default";  ///< file path, "--set", or "default"
  int line = 0;                    ///< 1-based line in `source`, 0 if not a file

  /// "file:12" or "--set" or "default".
  std::string ToString() const;
};

class ParamSet {
 public:
  /// Builder returned by Declare() to add constraints.
  class Spec {
   public:
    /// Closed interval for numbers (applies to every element of a list).
    Spec& Range(double lo, double hi);
    Spec& Min(double lo);
    Spec& Max(double hi);
    /// Allowed values of a string parameter.
    Spec& OneOf(std::vector<std::string> values);
    /// Exact length of a list parameter.
    Spec& Size(std::size_t n);
    /// No default: the value must come from a file or an override.
    Spec& Required();

    const std::string& name() const { return name_; }
    ParamType type() const { return type_; }
    const std::string& doc() const { return doc_; }

   private:
    friend class ParamSet;
    std::string name_;
    ParamType type_ = ParamType::kDouble;
    std::string doc_;
    std::optional<double> min_, max_;
    std::vector<std::string> one_of_;
    std::optional<std::size_t> size_;
    bool required_ = false;
  };

  explicit ParamSet(std::string owner = "") : owner_(std::move(owner)) {}

  /// Declares a parameter. Declaring the same name twice is a programming error (aborts).
  Spec& Declare(const std::string& name, bool default_value, std::string doc);
  Spec& Declare(const std::string& name, int default_value, std::string doc);
  Spec& Declare(const std::string& name, std::int64_t default_value, std::string doc);
  Spec& Declare(const std::string& name, double default_value, std::string doc);
  Spec& Declare(const std::string& name, const char* default_value, std::string doc);
  Spec& Declare(const std::string& name, std::string default_value, std::string doc);
  Spec& Declare(const std::string& name, std::vector<double> default_value, std::string doc);
  /// Declares with a run-time type; `default_value` must hold that type (param_binder.hpp).
  Spec& DeclareVariant(const std::string& name, ParamType type, ParamValue default_value,
                       std::string doc);

  /// Loads values from a YAML file. Unknown keys, wrong types and malformed YAML are errors.
  Status LoadYamlFile(const std::string& path);
  /// Same, from text; `source_name` is used in error messages.
  Status LoadYamlString(const std::string& text, const std::string& source_name);
  /// Loads only the named top-level sections of a YAML file (e.g. a scenario's `terrain` and
  /// `lander`); other top-level keys are left alone. Keys inside the sections are checked as
  /// usual and errors carry the file's own line numbers.
  Status LoadYamlSections(const std::string& text, const std::string& source_name,
                          const std::vector<std::string>& sections);
  /// Applies one `key=value` override (value in YAML syntax, e.g. `gains=[1,2,3]`).
  Status SetFromString(const std::string& assignment, const std::string& source = "--set");
  /// Checks ranges, allowed values, list sizes and required parameters.
  Status Validate() const;

  bool Has(const std::string& name) const { return specs_.count(name) != 0; }
  /// Typed read. Reading an undeclared name or with the wrong type is a programming error.
  bool GetBool(const std::string& name) const;
  std::int64_t GetInt(const std::string& name) const;
  double GetDouble(const std::string& name) const;
  const std::string& GetString(const std::string& name) const;
  const std::vector<double>& GetDoubleList(const std::string& name) const;
  /// The value whatever its type. Reading an undeclared name is a programming error.
  const ParamValue& Value(const std::string& name) const;

  const ParamOrigin& Origin(const std::string& name) const;
  /// Names in declaration order.
  const std::vector<std::string>& names() const { return order_; }
  const Spec& spec(const std::string& name) const;
  /// The effective values as YAML (for logs and `--print-params`).
  std::string DumpYaml() const;
  /// A table of every parameter with type, default, constraint and doc (for `--help-params`).
  std::string DescribeAll() const;

 private:
  struct Entry {
    ParamValue value;
    ParamValue default_value;
    ParamOrigin origin;
    bool set = false;
  };
  Spec& DeclareValue(const std::string& name, ParamType type, ParamValue v, std::string doc);
  // `yaml_node` is a const YAML::Node*; kept opaque so this header does not include yaml-cpp.
  Status Assign(const std::string& key, const ParamOrigin& origin, const void* yaml_node);
  Status AssignTree(const std::string& prefix, const std::string& source, const void* yaml_node);
  std::string Suggest(const std::string& key) const;

  std::string owner_;
  std::map<std::string, Spec> specs_;
  std::map<std::string, Entry> entries_;
  std::vector<std::string> order_;
};

/// Levenshtein distance, for "did you mean" hints.
std::size_t EditDistance(const std::string& a, const std::string& b);
/// " (did you mean 'x'?)" for the entry of `known` within edit distance 2 of `key`, else "".
std::string DidYouMean(const std::string& key, const std::vector<std::string>& known);

/// " (did you mean 'k'?)" naming the entry of `known` closest to `key` (edit distance at most 2;
/// the first of equals), or "" when none is that close. The one form of the hint in messages
/// about unknown keys, names and choices.
std::string DidYouMean(const std::string& key, const std::vector<std::string>& known);

/// A validation failure ("field: why", as Validate() functions write them) restated against the
/// parameter it concerns, in ParamSet's form: "<file>:<line>: key '<key>': why" (the origin is
/// "parameters" when `key` is not declared). Ok stays Ok.
Status AtParamKey(const ParamSet& params, const std::string& key, const Status& status);

}  // namespace rover
