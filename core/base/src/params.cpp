#include "rover/base/params.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "rover/base/check.hpp"

namespace rover {
namespace {

std::string Where(const ParamOrigin& o) { return o.ToString(); }

std::string Quote(const std::string& s) { return "'" + s + "'"; }

std::string FormatDouble(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string ValueText(const ParamValue& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>) {
          return x ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          return std::to_string(x);
        } else if constexpr (std::is_same_v<T, double>) {
          return FormatDouble(x);
        } else if constexpr (std::is_same_v<T, std::string>) {
          return "\"" + x + "\"";
        } else {
          std::string s = "[";
          for (std::size_t i = 0; i < x.size(); ++i) s += (i ? ", " : "") + FormatDouble(x[i]);
          return s + "]";
        }
      },
      v);
}

std::string NodeText(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  std::ostringstream os;
  os << YAML::Dump(n);
  std::string s = os.str();
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

bool ParseDouble(const YAML::Node& n, double* out) {
  if (!n.IsScalar()) return false;
  try {
    *out = n.as<double>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

}  // namespace

const char* ParamTypeName(ParamType t) {
  switch (t) {
    case ParamType::kBool: return "a boolean";
    case ParamType::kInt: return "an integer";
    case ParamType::kDouble: return "a number";
    case ParamType::kString: return "a string";
    case ParamType::kDoubleList: return "a list of numbers";
  }
  return "?";
}

std::string ParamOrigin::ToString() const {
  if (line > 0) return source + ":" + std::to_string(line);
  return source;
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string DidYouMean(const std::string& key, const std::vector<std::string>& known) {
  const std::string* best = nullptr;
  std::size_t best_d = 3;  // suggest only close matches
  for (const auto& k : known) {
    const std::size_t d = EditDistance(key, k);
    if (d < best_d) {
      best_d = d;
      best = &k;
    }
  }
  return best ? " (did you mean '" + *best + "'?)" : "";
}

// ---- Spec --------------------------------------------------------------------------------------

ParamSet::Spec& ParamSet::Spec::Range(double lo, double hi) {
  ROVER_DEMAND(lo <= hi);
  min_ = lo;
  max_ = hi;
  return *this;
}
ParamSet::Spec& ParamSet::Spec::Min(double lo) {
  min_ = lo;
  return *this;
}
ParamSet::Spec& ParamSet::Spec::Max(double hi) {
  max_ = hi;
  return *this;
}
ParamSet::Spec& ParamSet::Spec::OneOf(std::vector<std::string> values) {
  ROVER_DEMAND(type_ == ParamType::kString);
  one_of_ = std::move(values);
  return *this;
}
ParamSet::Spec& ParamSet::Spec::Size(std::size_t n) {
  ROVER_DEMAND(type_ == ParamType::kDoubleList);
  size_ = n;
  return *this;
}
ParamSet::Spec& ParamSet::Spec::Required() {
  required_ = true;
  return *this;
}

// ---- declaration -------------------------------------------------------------------------------

ParamSet::Spec& ParamSet::DeclareValue(const std::string& name, ParamType type, ParamValue v,
                                       std::string doc) {
  ROVER_DEMAND_MSG(!name.empty(), "parameter name is empty");
  ROVER_DEMAND_MSG(specs_.count(name) == 0, name.c_str());
  Spec& s = specs_[name];
  s.name_ = name;
  s.type_ = type;
  s.doc_ = std::move(doc);
  entries_[name] = Entry{v, v, ParamOrigin{}, false};
  order_.push_back(name);
  return s;
}

ParamSet::Spec& ParamSet::DeclareVariant(const std::string& n, ParamType type, ParamValue v,
                                         std::string d) {
  const bool matches = (type == ParamType::kBool && std::holds_alternative<bool>(v)) ||
                       (type == ParamType::kInt && std::holds_alternative<std::int64_t>(v)) ||
                       (type == ParamType::kDouble && std::holds_alternative<double>(v)) ||
                       (type == ParamType::kString && std::holds_alternative<std::string>(v)) ||
                       (type == ParamType::kDoubleList &&
                        std::holds_alternative<std::vector<double>>(v));
  ROVER_DEMAND_MSG(matches, n.c_str());
  return DeclareValue(n, type, std::move(v), std::move(d));
}

ParamSet::Spec& ParamSet::Declare(const std::string& n, bool v, std::string d) {
  return DeclareValue(n, ParamType::kBool, v, std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, int v, std::string d) {
  return DeclareValue(n, ParamType::kInt, static_cast<std::int64_t>(v), std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, std::int64_t v, std::string d) {
  return DeclareValue(n, ParamType::kInt, v, std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, double v, std::string d) {
  return DeclareValue(n, ParamType::kDouble, v, std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, const char* v, std::string d) {
  return DeclareValue(n, ParamType::kString, std::string(v), std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, std::string v, std::string d) {
  return DeclareValue(n, ParamType::kString, std::move(v), std::move(d));
}
ParamSet::Spec& ParamSet::Declare(const std::string& n, std::vector<double> v, std::string d) {
  return DeclareValue(n, ParamType::kDoubleList, std::move(v), std::move(d));
}

// ---- loading -----------------------------------------------------------------------------------

std::string ParamSet::Suggest(const std::string& key) const { return DidYouMean(key, order_); }

Status ParamSet::Assign(const std::string& key, const ParamOrigin& origin, const void* yaml_node) {
  const YAML::Node& node = *static_cast<const YAML::Node*>(yaml_node);
  const std::string where = Where(origin) + ": key " + Quote(key);
  auto it = specs_.find(key);
  if (it == specs_.end()) {
    std::string known;
    if (Suggest(key).empty()) {
      // List the keys of the same section (e.g. "terrain.rocks."), at most a dozen.
      const std::string section = key.substr(0, key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
      std::vector<std::string> same;
      for (const auto& n : order_) {
        if (n.rfind(section, 0) == 0) same.push_back(n);
      }
      if (same.empty()) same = order_;
      known = " (known keys" + (section.empty() ? std::string() : " under '" + section + "'") + ":";
      for (std::size_t i = 0; i < same.size() && i < 12; ++i) known += " " + same[i];
      if (same.size() > 12) known += " ... (" + std::to_string(same.size()) + " in all; --help-params lists them)";
      known += ")";
    }
    return InvalidArgument(where + ": unknown parameter" + Suggest(key) + known);
  }
  const Spec& spec = it->second;
  Entry& e = entries_[key];
  auto type_error = [&]() {
    return InvalidArgument(where + ": expected " + ParamTypeName(spec.type_) + ", got '" +
                           NodeText(node) + "'");
  };
  switch (spec.type_) {
    case ParamType::kBool: {
      if (!node.IsScalar()) return type_error();
      const std::string& s = node.Scalar();
      if (s == "true" || s == "True" || s == "TRUE" || s == "yes" || s == "on") {
        e.value = true;
      } else if (s == "false" || s == "False" || s == "FALSE" || s == "no" || s == "off") {
        e.value = false;
      } else {
        return type_error();
      }
      break;
    }
    case ParamType::kInt: {
      double d = 0;
      if (!ParseDouble(node, &d) || std::floor(d) != d || std::abs(d) > 9.0e15) return type_error();
      e.value = static_cast<std::int64_t>(d);
      break;
    }
    case ParamType::kDouble: {
      double d = 0;
      if (!ParseDouble(node, &d)) return type_error();
      e.value = d;
      break;
    }
    case ParamType::kString: {
      if (!node.IsScalar()) return type_error();
      e.value = node.Scalar();
      break;
    }
    case ParamType::kDoubleList: {
      if (!node.IsSequence()) return type_error();
      std::vector<double> v;
      for (const auto& item : node) {
        double d = 0;
        if (!ParseDouble(item, &d)) return type_error();
        v.push_back(d);
      }
      e.value = std::move(v);
      break;
    }
  }
  e.origin = origin;
  e.set = true;
  return Status::Ok();
}

Status ParamSet::AssignTree(const std::string& prefix, const std::string& source,
                            const void* yaml_node) {
  const YAML::Node& map = *static_cast<const YAML::Node*>(yaml_node);
  for (const auto& kv : map) {
    const std::string key = prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar();
    const ParamOrigin origin{source, kv.first.Mark().line + 1};
    if (kv.second.IsMap() && specs_.count(key) == 0) {
      ROVER_RETURN_IF_ERROR(AssignTree(key, source, &kv.second));
      continue;
    }
    ROVER_RETURN_IF_ERROR(Assign(key, origin, &kv.second));
  }
  return Status::Ok();
}

Status ParamSet::LoadYamlString(const std::string& text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    return InvalidArgument(source_name + ":" + std::to_string(e.mark.line + 1) +
                           ": malformed YAML: " + e.msg);
  }
  if (root.IsNull()) return Status::Ok();
  if (!root.IsMap()) {
    return InvalidArgument(source_name + ":" + std::to_string(root.Mark().line + 1) +
                           ": expected a map of parameters, got a " +
                           (root.IsSequence() ? "list" : "scalar"));
  }
  // One file may hold several services' parameters, each under its service name.
  if (!owner_.empty() && root[owner_] && root[owner_].IsMap() && specs_.count(owner_) == 0) {
    YAML::Node sub = root[owner_];
    return AssignTree("", source_name, &sub);
  }
  return AssignTree("", source_name, &root);
}

Status ParamSet::LoadYamlSections(const std::string& text, const std::string& source_name,
                                  const std::vector<std::string>& sections) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    return InvalidArgument(source_name + ":" + std::to_string(e.mark.line + 1) +
                           ": malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) return Status::Ok();
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (std::find(sections.begin(), sections.end(), key) == sections.end()) continue;
    if (kv.second.IsMap() && specs_.count(key) == 0) {
      ROVER_RETURN_IF_ERROR(AssignTree(key, source_name, &kv.second));
    } else {
      ROVER_RETURN_IF_ERROR(Assign(key, ParamOrigin{source_name, kv.first.Mark().line + 1}, &kv.second));
    }
  }
  return Status::Ok();
}

Status ParamSet::LoadYamlFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot open parameter file");
  std::stringstream ss;
  ss << in.rdbuf();
  return LoadYamlString(ss.str(), path);
}

Status ParamSet::SetFromString(const std::string& assignment, const std::string& source) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    return InvalidArgument(source + ": '" + assignment + "' is not of the form key=value");
  }
  const std::string key = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  YAML::Node node;
  try {
    node = YAML::Load(value);
  } catch (const YAML::ParserException& e) {
    return InvalidArgument(source + ": key '" + key + "': malformed value '" + value + "': " + e.msg);
  }
  if (node.IsNull()) node = YAML::Node(value);
  return Assign(key, ParamOrigin{source + " " + assignment, 0}, &node);
}

Status ParamSet::Validate() const {
  for (const auto& name : order_) {
    const Spec& s = specs_.at(name);
    const Entry& e = entries_.at(name);
    const std::string where = Where(e.origin) + ": key " + Quote(name);
    if (s.required_ && !e.set) {
      return InvalidArgument((owner_.empty() ? std::string("parameters") : owner_) +
                             ": required parameter '" + name + "' is not set (" + s.doc_ + ")");
    }
    auto check_number = [&](double v) -> Status {
      if (!std::isfinite(v)) {
        return OutOfRange(where + ": " + FormatDouble(v) + " is not a finite number");
      }
      if ((s.min_ && v < *s.min_) || (s.max_ && v > *s.max_)) {
        std::string range = "[" + (s.min_ ? FormatDouble(*s.min_) : std::string("-inf")) + ", " +
                            (s.max_ ? FormatDouble(*s.max_) : std::string("inf")) + "]";
        return OutOfRange(where + ": " + FormatDouble(v) + " is out of range " + range);
      }
      return Status::Ok();
    };
    switch (s.type_) {
      case ParamType::kInt:
        ROVER_RETURN_IF_ERROR(check_number(static_cast<double>(std::get<std::int64_t>(e.value))));
        break;
      case ParamType::kDouble:
        ROVER_RETURN_IF_ERROR(check_number(std::get<double>(e.value)));
        break;
      case ParamType::kDoubleList: {
        const auto& v = std::get<std::vector<double>>(e.value);
        if (s.size_ && v.size() != *s.size_) {
          return InvalidArgument(where + ": expected " + std::to_string(*s.size_) +
                                 " numbers, got " + std::to_string(v.size()));
        }
        for (double x : v) ROVER_RETURN_IF_ERROR(check_number(x));
        break;
      }
      case ParamType::kString: {
        const auto& v = std::get<std::string>(e.value);
        if (!s.one_of_.empty() &&
            std::find(s.one_of_.begin(), s.one_of_.end(), v) == s.one_of_.end()) {
          std::string allowed;
          for (const auto& a : s.one_of_) allowed += (allowed.empty() ? "" : ", ") + a;
          return InvalidArgument(where + ": '" + v + "' is not one of: " + allowed);
        }
        break;
      }
      case ParamType::kBool:
        break;
    }
  }
  return Status::Ok();
}

// ---- access ------------------------------------------------------------------------------------

#define ROVER_PARAM_GET(Fn, T, Type)                                               \
  T ParamSet::Fn(const std::string& name) const {                                  \
    auto it = entries_.find(name);                                                 \
    ROVER_DEMAND_MSG(it != entries_.end(), ("undeclared parameter " + name).c_str()); \
    ROVER_DEMAND_MSG(specs_.at(name).type_ == Type, ("wrong type for " + name).c_str()); \
    return std::get<std::decay_t<T>>(it->second.value);                            \
  }
ROVER_PARAM_GET(GetBool, bool, ParamType::kBool)
ROVER_PARAM_GET(GetInt, std::int64_t, ParamType::kInt)
ROVER_PARAM_GET(GetDouble, double, ParamType::kDouble)
ROVER_PARAM_GET(GetString, const std::string&, ParamType::kString)
ROVER_PARAM_GET(GetDoubleList, const std::vector<double>&, ParamType::kDoubleList)
#undef ROVER_PARAM_GET

const ParamValue& ParamSet::Value(const std::string& name) const {
  auto it = entries_.find(name);
  ROVER_DEMAND_MSG(it != entries_.end(), ("undeclared parameter " + name).c_str());
  return it->second.value;
}

const ParamOrigin& ParamSet::Origin(const std::string& name) const {
  auto it = entries_.find(name);
  ROVER_DEMAND_MSG(it != entries_.end(), ("undeclared parameter " + name).c_str());
  return it->second.origin;
}

const ParamSet::Spec& ParamSet::spec(const std::string& name) const {
  auto it = specs_.find(name);
  ROVER_DEMAND_MSG(it != specs_.end(), ("undeclared parameter " + name).c_str());
  return it->second;
}

std::string ParamSet::DumpYaml() const {
  std::string out;
  for (const auto& name : order_) {
    const Entry& e = entries_.at(name);
    out += name + ": " + ValueText(e.value) + "  # " + e.origin.ToString() + "\n";
  }
  return out;
}

std::string ParamSet::DescribeAll() const {
  std::string out;
  for (const auto& name : order_) {
    const Spec& s = specs_.at(name);
    const Entry& e = entries_.at(name);
    out += "  " + name + " (" + ParamTypeName(s.type_) + ")";
    out += s.required_ ? ", required" : ", default " + ValueText(e.default_value);
    if (s.min_ || s.max_) {
      out += ", range [" + (s.min_ ? FormatDouble(*s.min_) : std::string("-inf")) + ", " +
             (s.max_ ? FormatDouble(*s.max_) : std::string("inf")) + "]";
    }
    if (!s.one_of_.empty()) {
      out += ", one of";
      for (const auto& a : s.one_of_) out += " " + a;
    }
    out += "\n      " + s.doc_ + "\n";
  }
  return out;
}

Status AtParamKey(const ParamSet& params, const std::string& key, const Status& status) {
  if (status.ok()) return status;
  std::string why = status.message();
  if (const std::size_t colon = why.find(": "); colon != std::string::npos) {
    why = why.substr(colon + 2);
  }
  const std::string where =
      params.Has(key) ? params.Origin(key).ToString() : std::string("parameters");
  return Status(status.code(), where + ": key '" + key + "': " + why);
}

}  // namespace rover
