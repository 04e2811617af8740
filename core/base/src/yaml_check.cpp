#include "rover/base/yaml_check.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "rover/base/format.hpp"
#include "rover/base/params.hpp"  // DidYouMean

namespace rover::yaml {
namespace {

std::string Prefixed(std::string_view where, const std::string& what) {
  return where.empty() ? what : std::string(where) + ": " + what;
}

}  // namespace

int Line(const YAML::Node& n) { return n.Mark().line + 1; }

Status FileErrors::At(int line, std::string_view what) const {
  return InvalidArgument(file_ + ":" + std::to_string(line) + ": " + std::string(what));
}

Result<YAML::Node> Load(const std::string& text, const FileErrors& err) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    return err.At(e.mark.line + 1, "malformed YAML: " + e.msg);
  }
}

std::string JoinNames(const std::vector<std::string>& names, std::string_view separator) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += separator;
    out += n;
  }
  return out;
}

Status CheckKeys(const YAML::Node& map, std::string_view where,
                 const std::vector<std::string>& known, const FileErrors& err, KeyRules rules) {
  if (!map.IsMap()) {
    if (rules.require_map) return err.At(map, Prefixed(where, "expected a map"));
    return Status::Ok();
  }
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string key = kv.first.Scalar();
    if (!seen.insert(key).second)
      return err.At(kv.first, Prefixed(where, "duplicate key '" + key + "'"));
    if (rules.allow_extensions && key.rfind("x-", 0) == 0) continue;
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      return err.At(kv.first, Prefixed(where, "unknown key '" + key + "'" + DidYouMean(key, known) +
                                                  " (known: " + JoinNames(known) + ")"));
    }
  }
  return Status::Ok();
}

Status RequireKey(const YAML::Node& map, std::string_view where, const std::string& key,
                  const FileErrors& err) {
  if (map.IsMap() && map[key]) return Status::Ok();
  return err.At(map, Prefixed(where, "missing '" + key + "'"));
}

std::string ScalarText(const YAML::Node& n) { return n.IsScalar() ? n.Scalar() : ""; }

Result<double> Number(const YAML::Node& n, std::string_view key, const FileErrors& err) {
  if (n.IsScalar()) {
    try {
      const double v = n.as<double>();
      if (std::isfinite(v)) return v;
    } catch (const YAML::Exception&) {
    }
  }
  return err.At(n, std::string(key) + ": expected a finite number, got '" +
                       (n.IsScalar() ? n.Scalar() : "?") + "'");
}

Status OptionalNumber(const YAML::Node& parent, const std::string& name, std::string_view where,
                      const Bounds& bounds, const FileErrors& err, double* out, bool* present) {
  const YAML::Node n = parent[name];
  if (present) *present = static_cast<bool>(n);
  if (!n) return Status::Ok();
  const std::string key = where.empty() ? name : std::string(where) + "." + name;
  ROVER_ASSIGN_OR_RETURN(const double v, Number(n, key, err));
  if (!bounds.Contains(v)) {
    return err.At(n, key + ": " + FormatNumber(v) + " is out of range " + bounds.ToString());
  }
  *out = v;
  return Status::Ok();
}

Result<std::string> OneOf(const YAML::Node& n, std::string_view key,
                          const std::vector<std::string>& choices, const FileErrors& err) {
  const std::string v = ScalarText(n);
  if (n.IsScalar() && std::find(choices.begin(), choices.end(), v) != choices.end()) return v;
  return err.At(n, std::string(key) + ": '" + v + "' is not one of: " + JoinNames(choices) +
                       (v.empty() ? "" : DidYouMean(v, choices)));
}

void Flatten(const YAML::Node& n, const std::string& prefix,
             std::map<std::string, std::string>* out) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      Flatten(kv.second, prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar(),
              out);
    }
  } else if (n.IsScalar()) {
    (*out)[prefix] = n.Scalar();
  } else {
    YAML::Emitter e;
    e << YAML::Flow << n;
    (*out)[prefix] = e.c_str();
  }
}

}  // namespace rover::yaml
