#include "rover/base/param_binder.hpp"

#include <cctype>

namespace rover::internal {
namespace {

// Unit suffixes a key may carry that its member's name does not.
constexpr const char* kUnitSuffixes[] = {"_deg", "_deg_s", "_s", "_hz", "_m", "_mm", "_ms",
                                         "_us", "_pct", "_px"};

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Whether `message` starts with `field` as a whole word (optionally after "Type.").
bool StartsWithField(const std::string& message, const std::string& field) {
  std::size_t start = 0;
  const std::size_t dot = message.find('.');
  const std::size_t space = message.find(' ');
  if (dot != std::string::npos && dot < space && dot > 0 &&
      std::isupper(static_cast<unsigned char>(message[0]))) {
    start = dot + 1;  // "RoverGeometry.min_turn_radius ..."
  }
  if (message.compare(start, field.size(), field) != 0) return false;
  const std::size_t end = start + field.size();
  if (end == message.size()) return true;
  const char c = message[end];
  return c == ' ' || c == ':' || c == '=' || c == '[' || c == ',';
}

}  // namespace

std::vector<std::string> DefaultFields(const std::string& key) {
  std::vector<std::string> out{key};
  for (const char* s : kUnitSuffixes) {
    if (EndsWith(key, s)) out.push_back(key.substr(0, key.size() - std::string(s).size()));
  }
  return out;
}

void DeclareBound(ParamSet& params, const std::string& prefix, const BoundParam& b,
                  const void* defaults) {
  const std::string doc = b.unit.empty() ? b.doc : "[" + b.unit + "] " + b.doc;
  ParamSet::Spec& spec = params.DeclareVariant(prefix + b.key, b.type, b.get(defaults), doc);
  if (b.min) spec.Min(*b.min);
  if (b.max) spec.Max(*b.max);
  if (!b.one_of.empty()) spec.OneOf(b.one_of);
  if (b.size) spec.Size(*b.size);
}

void ReadBound(const ParamSet& params, const std::string& prefix, const BoundParam& b,
               void* options) {
  b.set(options, params.Value(prefix + b.key));
}

Status AttributeToKey(const ParamSet& params, const std::string& prefix,
                      const std::deque<BoundParam>& bound, const Status& failure) {
  // The longest matching field wins ("max_tilt_rate" before "max_tilt").
  const BoundParam* best = nullptr;
  std::size_t best_len = 0;
  for (const BoundParam& b : bound) {
    for (const std::string& f : b.fields) {
      if (f.size() > best_len && StartsWithField(failure.message(), f)) {
        best = &b;
        best_len = f.size();
      }
    }
  }
  if (best == nullptr) {
    return prefix.empty() ? failure : failure.WithPrefix("parameters " + prefix + "*");
  }
  const std::string key = prefix + best->key;
  return Status(failure.code(), params.Origin(key).ToString() + ": key '" + key + "': " +
                                    failure.message());
}

}  // namespace rover::internal
