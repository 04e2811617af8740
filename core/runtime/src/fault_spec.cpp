#include "rover/runtime/fault_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "rover/base/format.hpp"
#include "rover/base/glob.hpp"
#include "rover/base/params.hpp"
#include "rover/base/range_check.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/fault_yaml.hpp"
#include "rover/runtime/topic_catalog.hpp"
#include "rover/runtime/type_layout.hpp"

namespace rover::faults {

namespace {

template <class E>
struct Named {
  E value;
  const char* name;
};

constexpr Named<FaultKind> kKinds[] = {
    {FaultKind::kDrop, "drop"},       {FaultKind::kDelay, "delay"},
    {FaultKind::kDuplicate, "duplicate"}, {FaultKind::kReorder, "reorder"},
    {FaultKind::kFreeze, "freeze"},   {FaultKind::kCorrupt, "corrupt"},
    {FaultKind::kNoise, "noise"},     {FaultKind::kBias, "bias"},
    {FaultKind::kPartition, "partition"},
};
constexpr Named<Side> kSides[] = {
    {Side::kWriter, "writer"}, {Side::kReader, "reader"}, {Side::kBoth, "both"}};
constexpr Named<Corruption> kCorruptions[] = {
    {Corruption::kNan, "nan"},       {Corruption::kPosInf, "inf"},
    {Corruption::kNegInf, "-inf"},   {Corruption::kValue, "value"},
    {Corruption::kOutOfRange, "out_of_range"}, {Corruption::kBitFlip, "bitflip"},
};
constexpr Named<DelayDistribution> kDistributions[] = {
    {DelayDistribution::kFixed, "fixed"},     {DelayDistribution::kUniform, "uniform"},
    {DelayDistribution::kNormal, "normal"},   {DelayDistribution::kExponential, "exponential"},
};

template <class E, std::size_t N>
const char* NameOf(const Named<E> (&table)[N], E v) {
  for (const auto& n : table) {
    if (n.value == v) return n.name;
  }
  return "?";
}

template <class E, std::size_t N>
std::string AllNames(const Named<E> (&table)[N]) {
  std::string out;
  for (const auto& n : table) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

template <class E, std::size_t N>
std::optional<E> Lookup(const Named<E> (&table)[N], std::string_view text) {
  for (const auto& n : table) {
    if (text == n.name) return n.value;
  }
  return std::nullopt;
}

template <class E, std::size_t N>
std::vector<std::string> NameList(const Named<E> (&table)[N]) {
  std::vector<std::string> out;
  for (const auto& n : table) out.emplace_back(n.name);
  return out;
}

// "<source>:<line>: key '<key>': " -- or "<source>: fault <id>: key '<key>': " without lines.
std::string Where(const FaultSpec& s, std::string_view key) {
  int line = s.line;
  if (!key.empty()) {
    auto it = s.key_lines.find(std::string(key));
    if (it != s.key_lines.end()) line = it->second;
  }
  std::string out = s.source.empty() ? std::string("fault") : s.source;
  if (line > 0) {
    out += ":" + std::to_string(line);
  } else {
    out += ": fault " + std::to_string(s.id);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + std::string(key) + "': ";
  return out;
}

Status KeyError(const FaultSpec& s, std::string_view key, const std::string& what) {
  return InvalidArgument(Where(s, key) + what);
}

// A range check in the one form of range_check.hpp, located at the key.
Status Located(const FaultSpec& s, std::string_view key, Status st) {
  if (st.ok()) return st;
  int line = s.line;
  auto it = s.key_lines.find(std::string(key));
  if (it != s.key_lines.end()) line = it->second;
  std::string where = s.source.empty() ? std::string("fault") : s.source;
  where += line > 0 ? ":" + std::to_string(line) : ": fault " + std::to_string(s.id);
  return InvalidArgument(where + ": " + st.message());
}

bool NeedsProbability(FaultKind k) { return k != FaultKind::kFreeze && k != FaultKind::kPartition; }
bool NeedsField(FaultKind k) {
  return k == FaultKind::kCorrupt || k == FaultKind::kNoise || k == FaultKind::kBias;
}
bool NeedsCopies(FaultKind k) {
  return k == FaultKind::kDelay || k == FaultKind::kReorder || k == FaultKind::kFreeze ||
         NeedsField(k);
}

std::string Percent(double p) { return FormatNumber(p * 100.0, 4) + "%"; }

std::string DelayText(const DelaySpec& d) {
  switch (d.distribution) {
    case DelayDistribution::kFixed: return FormatNumber(d.a_s) + " s";
    case DelayDistribution::kUniform:
      return FormatNumber(d.a_s) + "..." + FormatNumber(d.b_s) + " s (uniform)";
    case DelayDistribution::kNormal:
      return FormatNumber(d.a_s) + " s (normal, sigma " + FormatNumber(d.b_s) + " s)";
    case DelayDistribution::kExponential:
      return FormatNumber(d.a_s) + " s (exponential mean)";
  }
  return "?";
}

// Whether a corruption, noise or bias can act on `leaf`; an error text otherwise.
std::string LeafProblem(const FaultSpec& s, const dds::FieldNode& leaf) {
  using dds::FieldKind;
  const auto k = leaf.kind;
  const bool is_float = k == FieldKind::kFloat;
  const bool is_integer = k == FieldKind::kInt || k == FieldKind::kUInt;
  const std::string what = "member '" + leaf.name + "' is " + dds::FieldKindPhrase(k) +
                           (leaf.size ? " (" + std::to_string(leaf.size) + " bytes)" : "");
  if (s.kind == FaultKind::kNoise || s.kind == FaultKind::kBias) {
    if (!is_float && !is_integer) return what + "; " + FaultKindName(s.kind) + " needs numbers";
    return "";
  }
  if (k == FieldKind::kEnum && s.side != Side::kReader &&
      (s.corruption == Corruption::kOutOfRange || s.corruption == Corruption::kBitFlip ||
       (s.corruption == Corruption::kValue && (s.value < 0 || s.value > leaf.enum_max)))) {
    return what + " with literals 0.." + std::to_string(leaf.enum_max) +
           "; DDS refuses to send an enum value outside them, so corrupt it with side: reader";
  }
  switch (s.corruption) {
    case Corruption::kNan:
    case Corruption::kPosInf:
    case Corruption::kNegInf:
      if (!is_float) return what + "; " + CorruptionName(s.corruption) + " needs floating-point fields";
      return "";
    case Corruption::kValue: {
      if (is_float) return "";
      if (k == FieldKind::kBool) {
        return s.value == 0.0 || s.value == 1.0 ? "" : what + "; value must be 0 or 1";
      }
      if (!is_integer && k != FieldKind::kEnum) return what + "; value needs numbers or enums";
      if (s.value != std::floor(s.value)) return what + "; value " + FormatNumber(s.value) + " is not an integer";
      const int bits = static_cast<int>(leaf.size) * 8;
      double lo = 0, hi = 0;
      if (k == FieldKind::kUInt) {
        hi = std::ldexp(1.0, bits) - 1;
      } else {
        lo = -std::ldexp(1.0, bits - 1);
        hi = std::ldexp(1.0, bits - 1) - 1;
      }
      if (s.value < lo || s.value > hi) {
        return what + "; value " + FormatNumber(s.value, 17) + " does not fit [" +
               FormatNumber(lo, 17) + ", " + FormatNumber(hi, 17) + "]";
      }
      return "";
    }
    case Corruption::kOutOfRange:
      if (!is_float && !is_integer && k != FieldKind::kEnum) return what + "; out_of_range needs numbers or enums";
      return "";
    case Corruption::kBitFlip:
      return "";
  }
  return "";
}

Status CheckDelay(const FaultSpec& s) {
  const DelaySpec& d = s.delay;
  ROVER_RETURN_IF_ERROR(Located(s, "delay", CheckNonNegative("delay", d.a_s, "s")));
  switch (d.distribution) {
    case DelayDistribution::kFixed:
      break;
    case DelayDistribution::kUniform:
      ROVER_RETURN_IF_ERROR(Located(s, "delay", CheckRange("delay.max", d.b_s, Bounds::AtLeast(d.a_s), "s")));
      break;
    case DelayDistribution::kNormal:
      ROVER_RETURN_IF_ERROR(Located(s, "delay", CheckNonNegative("delay.sigma", d.b_s, "s")));
      break;
    case DelayDistribution::kExponential:
      ROVER_RETURN_IF_ERROR(Located(s, "delay", CheckPositive("delay.mean", d.a_s, "s")));
      break;
  }
  return Status::Ok();
}

std::vector<std::string> SplitPatterns(std::string_view patterns) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : patterns) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

std::string NearestTopics(std::string_view patterns) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::string key(patterns);
  for (const auto& t : dds::TopicCatalog()) {
    if (IsFaultInfrastructure(t.name)) continue;
    scored.emplace_back(EditDistance(key, std::string(t.name)), std::string(t.name));
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string out;
  for (std::size_t i = 0; i < scored.size() && i < 3; ++i) out += (i ? ", " : "") + scored[i].second;
  return out;
}

}  // namespace

const char* FaultKindName(FaultKind kind) { return NameOf(kKinds, kind); }
const char* SideName(Side side) { return NameOf(kSides, side); }
const char* CorruptionName(Corruption c) { return NameOf(kCorruptions, c); }
const char* DelayDistributionName(DelayDistribution d) { return NameOf(kDistributions, d); }

// One glob algorithm for the project (rover/base/glob.hpp); this name stays for the fault API.
bool GlobMatch(std::string_view glob, std::string_view text) {
  return rover::GlobMatch(glob, text);
}

bool TopicMatches(std::string_view patterns, std::string_view topic) {
  bool included = false;
  for (const auto& p : SplitPatterns(patterns)) {
    if (p.empty()) continue;
    if (p[0] == '!') {
      if (GlobMatch(std::string_view(p).substr(1), topic)) return false;
    } else if (GlobMatch(p, topic)) {
      included = true;
    }
  }
  return included;
}

bool IsFaultInfrastructure(std::string_view topic) {
  return topic == "sys/fault_control" || topic == "sys/fault_event";
}

std::vector<std::string> MatchingCatalogTopics(std::string_view patterns) {
  std::vector<std::string> out;
  for (const auto& t : dds::TopicCatalog()) {
    if (!IsFaultInfrastructure(t.name) && TopicMatches(patterns, t.name)) out.emplace_back(t.name);
  }
  return out;
}

Status FaultSpec::Validate() const {
  const FaultSpec& s = *this;
  if (name.size() > 63) return KeyError(s, "name", "longer than 63 characters");
  if (topic.empty()) return KeyError(s, "topic", "is required (a glob over topic names)");
  if (topic.size() > 127) return KeyError(s, "topic", "longer than 127 characters");
  for (const auto& p : SplitPatterns(topic)) {
    if (p.empty() || p == "!") return KeyError(s, "topic", "'" + topic + "' has an empty pattern");
  }
  const auto topics = MatchingCatalogTopics(topic);
  if (topics.empty()) {
    return KeyError(s, "topic", "'" + topic + "' matches no catalog topic (nearest: " +
                                    NearestTopics(topic) + ")");
  }
  if (service.empty()) return KeyError(s, "service", "is empty (use '*' for every service)");
  if (service.size() > 63) return KeyError(s, "service", "longer than 63 characters");
  if (kind == FaultKind::kPartition && service == "*") {
    return KeyError(s, "service", "partition needs the service to cut off");
  }
  ROVER_RETURN_IF_ERROR(Located(s, "probability", CheckRange("probability", probability, 0.0, 1.0)));
  ROVER_RETURN_IF_ERROR(Located(s, "start_s", CheckNonNegative("start_s", start_s, "s")));
  ROVER_RETURN_IF_ERROR(Located(s, "duration_s", CheckNonNegative("duration_s", duration_s, "s")));
  if (!NeedsProbability(kind) && probability != 1.0) {
    return KeyError(s, "probability", std::string("does not apply to ") + FaultKindName(kind));
  }
  if (kind == FaultKind::kDelay && !delay.given) {
    return KeyError(s, "delay", "is required for kind delay (seconds, or a distribution)");
  }
  if (kind == FaultKind::kDelay || kind == FaultKind::kReorder) ROVER_RETURN_IF_ERROR(CheckDelay(s));
  if (kind == FaultKind::kDuplicate) {
    ROVER_RETURN_IF_ERROR(Located(s, "copies", CheckIntRange("copies", copies, 1, 100)));
  }
  if (kind == FaultKind::kCorrupt && corruption == Corruption::kBitFlip) {
    ROVER_RETURN_IF_ERROR(Located(s, "bits", CheckIntRange("bits", bits, 1, 64)));
  }
  if (kind == FaultKind::kNoise) ROVER_RETURN_IF_ERROR(Located(s, "sigma", CheckPositive("sigma", sigma)));
  if (kind == FaultKind::kBias || (kind == FaultKind::kCorrupt && corruption == Corruption::kValue)) {
    ROVER_RETURN_IF_ERROR(Located(s, "value", CheckFinite("value", value)));
  }
  if (NeedsField(kind) && field.empty()) {
    return KeyError(s, "field", std::string("is required for kind ") + FaultKindName(kind));
  }
  if (!NeedsField(kind) && !field.empty()) {
    return KeyError(s, "field", "applies to corrupt, noise and bias only");
  }
  if (field.size() > 127) return KeyError(s, "field", "longer than 127 characters");
  // The types of the matched topics.
  for (const auto& t : topics) {
    const auto info = dds::FindTopic(t);
    const dds_topic_descriptor_t* desc = dds::DescriptorForType(info->type_name);
    if (desc == nullptr) {
      return KeyError(s, "topic", "topic " + t + ": no descriptor for type " + std::string(info->type_name));
    }
    if (!NeedsField(kind) && !NeedsCopies(kind)) continue;
    auto layout = dds::TypeLayout::For(desc);
    if (!layout.ok()) return KeyError(s, "topic", "topic " + t + ": " + layout.status().message());
    if (NeedsCopies(kind) && !(*layout)->copyable()) {
      return KeyError(s, "kind", std::string(FaultKindName(kind)) + " copies samples, and " +
                                     (*layout)->type_name() + " (topic " + t +
                                     ") has unions or optional members");
    }
    if (!NeedsField(kind)) continue;
    auto sel = dds::FieldSelector::Resolve(**layout, field);
    if (!sel.ok()) return KeyError(s, "field", sel.status().message() + " (topic " + t + ")");
    for (const dds::FieldNode* leaf : sel->leaf_nodes()) {
      const std::string problem = LeafProblem(s, *leaf);
      if (!problem.empty()) {
        return KeyError(s, kind == FaultKind::kCorrupt ? "mode" : "field",
                        (*layout)->type_name() + " '" + field + "': " + problem);
      }
    }
  }
  return Status::Ok();
}

std::string FaultSpec::Describe() const {
  std::string what;
  const std::string p = probability < 1.0 ? Percent(probability) + " of " : "";
  switch (kind) {
    case FaultKind::kDrop: what = "drop " + (p.empty() ? std::string("every sample of ") : p); break;
    case FaultKind::kDelay: what = "delay " + p + "samples by " + DelayText(delay) + " on "; break;
    case FaultKind::kDuplicate:
      what = "duplicate (x" + std::to_string(copies + 1) + ") " + (p.empty() ? "every sample of " : p);
      break;
    case FaultKind::kReorder: what = "reorder " + (p.empty() ? std::string("every sample of ") : p); break;
    case FaultKind::kFreeze: what = "freeze "; break;
    case FaultKind::kCorrupt:
      what = "corrupt " + field + " (" + CorruptionName(corruption) +
             (corruption == Corruption::kValue ? " " + FormatNumber(value) : "") +
             (corruption == Corruption::kBitFlip ? " " + std::to_string(bits) : "") + ") in " + p;
      break;
    case FaultKind::kNoise: what = "add noise (sigma " + FormatNumber(sigma) + ") to " + field + " in " + p; break;
    case FaultKind::kBias: what = "add " + FormatNumber(value) + " to " + field + " in " + p; break;
    case FaultKind::kPartition: what = "cut " + service + " off "; break;
  }
  std::string out = "fault " + std::to_string(id) + (name.empty() ? "" : " '" + name + "'") + ": " +
                    what + topic;
  if (kind != FaultKind::kPartition) {
    out += std::string(" at the ") +
           (side == Side::kWriter ? "writers" : side == Side::kReader ? "readers" : "writers and readers") +
           " of " + (service == "*" ? std::string("every service") : service);
  }
  out += ", from " + FormatNumber(start_s) + " s" +
         (start_mode == StartMode::kOnReceipt ? " after receipt" : "") +
         (duration_s > 0 ? " for " + FormatNumber(duration_s) + " s" : " until removed") +
         ", seed " + std::to_string(seed);
  return out;
}

// ---- YAML -------------------------------------------------------------------------------------

namespace {

const std::vector<std::string>& KnownKeys() {
  static const std::vector<std::string> keys = {
      "id", "name", "kind", "topic", "service", "side", "field", "mode", "value", "sigma",
      "bits", "copies", "probability", "delay", "start_s", "duration_s", "seed"};
  return keys;
}

// Which kinds a key applies to (empty = every kind).
bool KeyApplies(const std::string& key, FaultKind k, Corruption c) {
  if (key == "field") return NeedsField(k);
  if (key == "mode") return k == FaultKind::kCorrupt;
  if (key == "value") return k == FaultKind::kBias || (k == FaultKind::kCorrupt && c == Corruption::kValue);
  if (key == "sigma") return k == FaultKind::kNoise;
  if (key == "bits") return k == FaultKind::kCorrupt && c == Corruption::kBitFlip;
  if (key == "copies") return k == FaultKind::kDuplicate;
  if (key == "probability") return NeedsProbability(k);
  if (key == "delay") return k == FaultKind::kDelay || k == FaultKind::kReorder;
  return true;
}

class FaultReader {
 public:
  explicit FaultReader(FaultSpec& s) : s_(s) {}

  Status Text(const YAML::Node& n, const std::string& key, std::string* out) {
    if (!n.IsScalar()) return KeyError(s_, key, "expected text");
    *out = n.Scalar();
    return Status::Ok();
  }
  Status Number(const YAML::Node& n, const std::string& key, double* out) {
    if (!n.IsScalar()) return KeyError(s_, key, "expected a number");
    try {
      *out = n.as<double>();
    } catch (const YAML::Exception&) {
      return KeyError(s_, key, "'" + n.Scalar() + "' is not a number");
    }
    return Status::Ok();
  }
  Status Integer(const YAML::Node& n, const std::string& key, std::uint64_t max, std::uint64_t* out) {
    if (!n.IsScalar()) return KeyError(s_, key, "expected a whole number");
    const std::string& t = n.Scalar();
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos) {
      return KeyError(s_, key, "'" + t + "' is not a whole number >= 0");
    }
    try {
      const unsigned long long v = std::stoull(t);
      if (v > max) return KeyError(s_, key, t + " is larger than " + std::to_string(max));
      *out = v;
    } catch (const std::exception&) {
      return KeyError(s_, key, "'" + t + "' is not a whole number >= 0");
    }
    return Status::Ok();
  }
  template <class E, std::size_t N>
  Status Enum(const YAML::Node& n, const std::string& key, const Named<E> (&table)[N],
              const char* what, E* out) {
    std::string t;
    ROVER_RETURN_IF_ERROR(Text(n, key, &t));
    auto v = Lookup(table, t);
    if (!v) {
      return KeyError(s_, key, "'" + t + "' is not a " + what + DidYouMean(t, NameList(table)) +
                                   "; one of: " + AllNames(table));
    }
    *out = *v;
    return Status::Ok();
  }

  Status Delay(const YAML::Node& n) {
    DelaySpec& d = s_.delay;
    d.given = true;
    if (n.IsScalar()) {
      d.distribution = DelayDistribution::kFixed;
      return Number(n, "delay", &d.a_s);
    }
    if (!n.IsMap()) return KeyError(s_, "delay", "expected seconds or a map with 'distribution'");
    std::map<std::string, YAML::Node> keys;
    for (const auto& kv : n) keys[kv.first.Scalar()] = kv.second;
    if (keys.count("distribution")) {
      ROVER_RETURN_IF_ERROR(Enum(keys["distribution"], "delay", kDistributions, "delay distribution",
                                 &d.distribution));
    }
    std::vector<std::string> allowed;
    switch (d.distribution) {
      case DelayDistribution::kFixed: allowed = {"distribution", "mean"}; break;
      case DelayDistribution::kUniform: allowed = {"distribution", "min", "max"}; break;
      case DelayDistribution::kNormal: allowed = {"distribution", "mean", "sigma"}; break;
      case DelayDistribution::kExponential: allowed = {"distribution", "mean"}; break;
    }
    for (const auto& [k, v] : keys) {
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        return KeyError(s_, "delay", "'" + k + "' does not apply to a " +
                                         DelayDistributionName(d.distribution) +
                                         " delay; keys: " + list);
      }
    }
    const char* a_key = d.distribution == DelayDistribution::kUniform ? "min" : "mean";
    const char* b_key = d.distribution == DelayDistribution::kUniform ? "max" : "sigma";
    if (!keys.count(a_key)) return KeyError(s_, "delay", std::string("'") + a_key + "' is required");
    ROVER_RETURN_IF_ERROR(Number(keys[a_key], "delay", &d.a_s));
    if (d.distribution == DelayDistribution::kUniform || d.distribution == DelayDistribution::kNormal) {
      if (!keys.count(b_key)) return KeyError(s_, "delay", std::string("'") + b_key + "' is required");
      ROVER_RETURN_IF_ERROR(Number(keys[b_key], "delay", &d.b_s));
    }
    return Status::Ok();
  }

 private:
  FaultSpec& s_;
};

Result<FaultSpec> ParseOne(const YAML::Node& node, std::string_view source, std::size_t index) {
  FaultSpec s;
  s.source = std::string(source);
  s.line = node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
  if (!node.IsMap()) {
    return InvalidArgument(Where(s, "") + "fault " + std::to_string(index + 1) +
                           ": expected a map with kind, topic, ...");
  }
  std::map<std::string, YAML::Node> keys;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    s.key_lines[key] = kv.first.Mark().line + 1;
    if (std::find(KnownKeys().begin(), KnownKeys().end(), key) == KnownKeys().end()) {
      return KeyError(s, key, "unknown key" + DidYouMean(key, KnownKeys()));
    }
    keys[key] = kv.second;
  }
  FaultReader r(s);
  if (!keys.count("kind")) {
    return InvalidArgument(Where(s, "") + "missing key 'kind' (one of: " + AllNames(kKinds) + ")");
  }
  ROVER_RETURN_IF_ERROR(r.Enum(keys["kind"], "kind", kKinds, "fault kind", &s.kind));
  if (keys.count("mode")) {
    ROVER_RETURN_IF_ERROR(r.Enum(keys["mode"], "mode", kCorruptions, "corruption mode", &s.corruption));
  } else if (s.kind == FaultKind::kCorrupt) {
    return InvalidArgument(Where(s, "") + "missing key 'mode' (one of: " + AllNames(kCorruptions) + ")");
  }
  for (const auto& [key, value] : keys) {
    if (!KeyApplies(key, s.kind, s.corruption)) {
      return KeyError(s, key, std::string("does not apply to ") + FaultKindName(s.kind) +
                                  (s.kind == FaultKind::kCorrupt ? std::string(" with mode ") +
                                                                       CorruptionName(s.corruption)
                                                                 : std::string()));
    }
  }
  if (s.kind == FaultKind::kPartition) {
    s.topic = "*,!sim/*";
    s.side = Side::kBoth;
  }
  std::uint64_t u = 0;
  if (keys.count("id")) {
    ROVER_RETURN_IF_ERROR(r.Integer(keys["id"], "id", 0xffffffffu, &u));
    if (u == 0) return KeyError(s, "id", "must be > 0");
    s.id = static_cast<std::uint32_t>(u);
  }
  if (keys.count("name")) ROVER_RETURN_IF_ERROR(r.Text(keys["name"], "name", &s.name));
  if (keys.count("topic")) {
    const YAML::Node& t = keys["topic"];
    if (t.IsSequence()) {
      s.topic.clear();
      for (const auto& item : t) {
        if (!item.IsScalar()) return KeyError(s, "topic", "expected globs");
        s.topic += (s.topic.empty() ? "" : ",") + item.Scalar();
      }
    } else {
      ROVER_RETURN_IF_ERROR(r.Text(t, "topic", &s.topic));
    }
  }
  if (keys.count("service")) ROVER_RETURN_IF_ERROR(r.Text(keys["service"], "service", &s.service));
  if (keys.count("side")) ROVER_RETURN_IF_ERROR(r.Enum(keys["side"], "side", kSides, "side", &s.side));
  if (keys.count("field")) ROVER_RETURN_IF_ERROR(r.Text(keys["field"], "field", &s.field));
  if (keys.count("value")) ROVER_RETURN_IF_ERROR(r.Number(keys["value"], "value", &s.value));
  if (keys.count("sigma")) ROVER_RETURN_IF_ERROR(r.Number(keys["sigma"], "sigma", &s.sigma));
  if (keys.count("bits")) {
    ROVER_RETURN_IF_ERROR(r.Integer(keys["bits"], "bits", 1000, &u));
    s.bits = static_cast<std::uint32_t>(u);
  }
  if (keys.count("copies")) {
    ROVER_RETURN_IF_ERROR(r.Integer(keys["copies"], "copies", 1000, &u));
    s.copies = static_cast<std::uint32_t>(u);
  }
  if (keys.count("probability")) {
    ROVER_RETURN_IF_ERROR(r.Number(keys["probability"], "probability", &s.probability));
  }
  if (keys.count("delay")) ROVER_RETURN_IF_ERROR(r.Delay(keys["delay"]));
  if (keys.count("start_s")) ROVER_RETURN_IF_ERROR(r.Number(keys["start_s"], "start_s", &s.start_s));
  if (keys.count("duration_s")) {
    ROVER_RETURN_IF_ERROR(r.Number(keys["duration_s"], "duration_s", &s.duration_s));
  }
  if (keys.count("seed")) {
    ROVER_RETURN_IF_ERROR(r.Integer(keys["seed"], "seed", std::numeric_limits<std::uint64_t>::max(), &s.seed));
  }
  if (s.kind == FaultKind::kReorder && !s.delay.given) {
    s.delay.a_s = 1.0;  // longest hold of a sample waiting for the one to swap with
  }
  return s;
}

Result<YAML::Node> Load(std::string_view text, std::string_view source) {
  try {
    return YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    return InvalidArgument(std::string(source) + ":" + std::to_string(e.mark.line + 1) +
                           ": malformed YAML: " + e.msg);
  }
}

}  // namespace

Result<std::vector<FaultSpec>> ParseFaults(const YAML::Node& root, std::string_view source) {
  YAML::Node list = root;
  if (root.IsMap()) {
    for (const auto& kv : root) {
      if (kv.first.Scalar() != "faults") {
        return InvalidArgument(std::string(source) + ":" + std::to_string(kv.first.Mark().line + 1) +
                               ": key '" + kv.first.Scalar() + "': unknown key (expected 'faults')");
      }
    }
    list = root["faults"];
  }
  std::vector<FaultSpec> out;
  if (!list || list.IsNull()) return out;
  if (!list.IsSequence()) {
    return InvalidArgument(std::string(source) + ":" + std::to_string(list.Mark().line + 1) +
                           ": expected a list of faults");
  }
  std::set<std::uint32_t> ids;
  for (std::size_t i = 0; i < list.size(); ++i) {
    auto s = ParseOne(list[i], source, i);
    if (!s.ok()) return s.status();
    if (s->id == 0) {
      std::uint32_t id = static_cast<std::uint32_t>(i + 1);
      while (ids.count(id)) ++id;
      s->id = id;
    }
    if (!ids.insert(s->id).second) {
      return KeyError(*s, "id", "fault id " + std::to_string(s->id) + " is used twice");
    }
    ROVER_RETURN_IF_ERROR(s->Validate());
    out.push_back(std::move(*s));
  }
  return out;
}

Result<std::vector<FaultSpec>> ParseFaults(std::string_view yaml_text, std::string_view source) {
  auto root = Load(yaml_text, source);
  if (!root.ok()) return root.status();
  return ParseFaults(*root, source);
}

Result<FaultSpec> ParseFault(std::string_view yaml_text, std::string_view source) {
  auto root = Load(yaml_text, source);
  if (!root.ok()) return root.status();
  auto s = ParseOne(*root, source, 0);
  if (!s.ok()) return s.status();
  ROVER_RETURN_IF_ERROR(s->Validate());
  return s;
}

Result<std::vector<FaultSpec>> LoadFaultsFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound("faults file '" + path + "' cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseFaults(ss.str(), path);
}

// ---- control messages --------------------------------------------------------------------------

rover_sys_FaultKind ToIdl(FaultKind kind) {
  switch (kind) {
    case FaultKind::kDrop: return rover_sys_FAULT_DROP;
    case FaultKind::kDelay: return rover_sys_FAULT_DELAY;
    case FaultKind::kDuplicate: return rover_sys_FAULT_DUPLICATE;
    case FaultKind::kReorder: return rover_sys_FAULT_REORDER;
    case FaultKind::kFreeze: return rover_sys_FAULT_FREEZE;
    case FaultKind::kCorrupt: return rover_sys_FAULT_CORRUPT;
    case FaultKind::kNoise: return rover_sys_FAULT_NOISE;
    case FaultKind::kBias: return rover_sys_FAULT_BIAS;
    case FaultKind::kPartition: return rover_sys_FAULT_PARTITION;
  }
  return rover_sys_FAULT_DROP;
}

void ToControl(const FaultSpec& s, rover_sys_FaultControl* m) {
  m->fault_id = s.id;
  m->action = rover_sys_FAULT_ACTION_ADD;
  m->kind = ToIdl(s.kind);
  dds::CopyString(m->name, s.name);
  dds::CopyString(m->topic_pattern, s.topic);
  dds::CopyString(m->service_pattern, s.service);
  m->side = static_cast<rover_sys_FaultSide>(s.side);
  dds::CopyString(m->field, s.field);
  m->corruption = static_cast<rover_sys_FaultCorruption>(s.corruption);
  m->value = s.value;
  m->sigma = s.sigma;
  m->bits = s.bits;
  m->copies = s.copies;
  m->probability = s.probability;
  m->delay_distribution = static_cast<rover_sys_FaultDelay>(s.delay.distribution);
  m->delay_a_s = s.delay.given ? s.delay.a_s : -1.0;  // < 0: not given
  m->delay_b_s = s.delay.b_s;
  m->start_mode = s.start_mode == StartMode::kOnReceipt ? rover_sys_FAULT_START_ON_RECEIPT
                                                        : rover_sys_FAULT_START_RUN_EPOCH;
  m->start_ns = static_cast<int64_t>(std::llround(s.start_s * 1e9));
  m->duration_ns = static_cast<int64_t>(std::llround(s.duration_s * 1e9));
  m->seed = s.seed;
}

Result<FaultSpec> FromControl(const rover_sys_FaultControl& m) {
  FaultSpec s;
  s.source = "sys/fault_control";
  s.id = m.fault_id;
  auto bad_enum = [&](const char* key, int v) {
    return KeyError(s, key, "value " + std::to_string(v) + " is not a valid enumerator");
  };
  if (m.fault_id == 0) return KeyError(s, "id", "an added fault needs a fault_id > 0");
  if (m.kind < rover_sys_FAULT_DROP || m.kind > rover_sys_FAULT_PARTITION) return bad_enum("kind", m.kind);
  if (m.side < rover_sys_FAULT_SIDE_WRITER || m.side > rover_sys_FAULT_SIDE_BOTH) return bad_enum("side", m.side);
  if (m.corruption < rover_sys_CORRUPT_NAN || m.corruption > rover_sys_CORRUPT_BITFLIP) {
    return bad_enum("mode", m.corruption);
  }
  if (m.delay_distribution < rover_sys_DELAY_FIXED || m.delay_distribution > rover_sys_DELAY_EXPONENTIAL) {
    return bad_enum("delay", m.delay_distribution);
  }
  s.kind = static_cast<FaultKind>(m.kind);
  s.name = m.name;
  s.topic = m.topic_pattern;
  s.service = m.service_pattern[0] == '\0' ? std::string("*") : std::string(m.service_pattern);
  s.side = static_cast<Side>(m.side);
  s.field = m.field;
  s.corruption = static_cast<Corruption>(m.corruption);
  s.value = m.value;
  s.sigma = m.sigma;
  s.bits = m.bits;
  s.copies = m.copies;
  s.probability = m.probability;
  s.delay.distribution = static_cast<DelayDistribution>(m.delay_distribution);
  s.delay.given = m.delay_a_s >= 0.0;
  s.delay.a_s = s.delay.given ? m.delay_a_s : (s.kind == FaultKind::kReorder ? 1.0 : 0.0);
  s.delay.b_s = m.delay_b_s;
  s.start_mode = m.start_mode == rover_sys_FAULT_START_ON_RECEIPT ? StartMode::kOnReceipt
                                                                  : StartMode::kRunEpoch;
  s.start_s = static_cast<double>(m.start_ns) * 1e-9;
  s.duration_s = static_cast<double>(m.duration_ns) * 1e-9;
  s.seed = m.seed;
  ROVER_RETURN_IF_ERROR(s.Validate());
  return s;
}

}  // namespace rover::faults
