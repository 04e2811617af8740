#include "rover/apl/sequencer/condition.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"

namespace rover::apl::sequencer {
namespace {

struct QuantityRow {
  Quantity q;
  const char* name;
  std::string_view unit;  // "" for enumerated ones
};

constexpr std::array<QuantityRow, 7> kQuantities{{
    {Quantity::kLastTermination, "last.termination", ""},
    {Quantity::kLastFault, "last.fault", ""},
    {Quantity::kLastClass, "last.class", ""},
    {Quantity::kDistanceTo, "distance_to", "m"},
    {Quantity::kVisodomFailures, "visodom.failures", "count"},
    {Quantity::kTilt, "tilt", "deg"},
    {Quantity::kElapsed, "elapsed", "s"},
}};

const QuantityRow& RowOf(Quantity q) {
  for (const auto& r : kQuantities) {
    if (r.q == q) return r;
  }
  ROVER_UNREACHABLE();
}

template <class T>
bool Compare(Relation r, T a, T b) {
  switch (r) {
    case Relation::kEq: return a == b;
    case Relation::kNe: return a != b;
    case Relation::kLt: return a < b;
    case Relation::kLe: return a <= b;
    case Relation::kGt: return a > b;
    case Relation::kGe: return a >= b;
  }
  ROVER_UNREACHABLE();
}

std::optional<bool> EvaluateComparison(const Comparison& c, const ConditionInputs& in) {
  const Outcome& last = in.last;
  switch (c.quantity) {
    case Quantity::kLastTermination:
      return Compare(c.relation, static_cast<int>(last.termination), c.enum_value);
    case Quantity::kLastFault:
      return Compare(c.relation, last.fault.Index(), c.enum_value);
    case Quantity::kLastClass: {
      const msg::FaultClass k = last.fault_class == msg::FaultClass::kNone
                                    ? last.fault.DefaultClass()
                                    : last.fault_class;
      return Compare(c.relation, static_cast<int>(k), c.enum_value);
    }
    case Quantity::kDistanceTo:
      if (in.pose == nullptr) return std::nullopt;
      return Compare(c.relation, DistanceTo(*in.pose, c.point), c.number);
    case Quantity::kVisodomFailures:
      return Compare(c.relation, static_cast<double>(in.visodom_failures), c.number);
    case Quantity::kTilt:
      if (in.pose == nullptr) return std::nullopt;
      return Compare(c.relation, TiltOf(*in.pose) * 180.0 / std::numbers::pi, c.number);
    case Quantity::kElapsed: return Compare(c.relation, in.elapsed_s, c.number);
  }
  ROVER_UNREACHABLE();
}

}  // namespace

const char* QuantityName(Quantity q) { return RowOf(q).name; }

std::vector<std::string> QuantityNames() {
  std::vector<std::string> out;
  for (const auto& r : kQuantities) out.emplace_back(r.name);
  return out;
}

std::optional<Quantity> FindQuantity(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  for (const auto& r : kQuantities) {
    if (lower == r.name) return r.q;
  }
  return std::nullopt;
}

bool IsEnumerated(Quantity q) { return RowOf(q).unit.empty(); }

std::string_view QuantityUnit(Quantity q) { return RowOf(q).unit; }

const std::vector<std::string>& QuantityValueNames(Quantity q) {
  switch (q) {
    case Quantity::kLastTermination: return TerminationNames();
    case Quantity::kLastFault: return FaultNames();
    case Quantity::kLastClass: return FaultClassNames();
    default: break;
  }
  ROVER_DEMAND_MSG(false, "QuantityValueNames of a numeric quantity");
  ROVER_UNREACHABLE();
}

const char* RelationName(Relation r) {
  switch (r) {
    case Relation::kEq: return "==";
    case Relation::kNe: return "!=";
    case Relation::kLt: return "<";
    case Relation::kLe: return "<=";
    case Relation::kGt: return ">";
    case Relation::kGe: return ">=";
  }
  ROVER_UNREACHABLE();
}

bool NeedsPose(const Condition& c) {
  if (c.op == Condition::Op::kCompare) {
    return c.compare.quantity == Quantity::kDistanceTo || c.compare.quantity == Quantity::kTilt;
  }
  return std::any_of(c.operands.begin(), c.operands.end(),
                     [](const Condition& o) { return NeedsPose(o); });
}

std::optional<bool> Evaluate(const Condition& c, const ConditionInputs& inputs) {
  switch (c.op) {
    case Condition::Op::kCompare: return EvaluateComparison(c.compare, inputs);
    case Condition::Op::kNot: {
      ROVER_DEMAND(c.operands.size() == 1);
      const auto v = Evaluate(c.operands[0], inputs);
      if (!v) return std::nullopt;
      return !*v;
    }
    case Condition::Op::kAnd:
    case Condition::Op::kOr: {
      ROVER_DEMAND(c.operands.size() >= 2);
      // Every operand is evaluated, so a missing pose is noticed whichever way the others go.
      bool unknown = false;
      bool value = c.op == Condition::Op::kAnd;
      for (const Condition& o : c.operands) {
        const auto v = Evaluate(o, inputs);
        if (!v) {
          unknown = true;
        } else if (c.op == Condition::Op::kAnd) {
          value = value && *v;
        } else {
          value = value || *v;
        }
      }
      if (unknown) return std::nullopt;
      return value;
    }
  }
  ROVER_UNREACHABLE();
}

}  // namespace rover::apl::sequencer
