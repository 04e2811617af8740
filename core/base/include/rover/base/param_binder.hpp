#pragma once
/// @file
/// Parameters declared once, next to the options struct they fill.
///
/// An options struct lists its parameters in one static function; the declaration (key, type,
/// default, unit, range, help) and the read-back into the struct both come from that list, so a
/// key can never be declared in one place and read under another name in a second:
///
///   struct DriveOptions {
///     double check_rate_hz = 8.0;
///     double max_tilt = 30.0 * kDegree;   // [rad]
///     int tilt_cycles = 3;
///     Status Validate() const;         // cross-field rules; messages start with the field
///     static void BindParams(ParamBinder<DriveOptions>& b) {
///       b.Bind("check_rate_hz", &DriveOptions::check_rate_hz, "Hz", "check cycle").Range(1, 50);
///       b.BindDegrees("max_tilt_deg", &DriveOptions::max_tilt, "tilt limit").Range(0, 45);
///       b.Bind("tilt_cycles", &DriveOptions::tilt_cycles, "", "cycles over the limit").Min(1);
///     }
///   };
///
///   DeclareParams<DriveOptions>(params, "drive.");              // in DeclareParameters
///   ROVER_ASSIGN_OR_RETURN(options_, ReadParams<DriveOptions>(params, "drive."));
///
/// Units: the key carries the parameter's unit (documented as "[unit] help"); BindScaled and
/// BindDegrees convert to the member's unit (member = value * scale), and ranges are in the
/// parameter's unit. ReadParams calls Options::Validate() when the struct has one and reports a
/// failure against the key whose field the message starts with, in ParamSet's form:
///   "drive.yaml:7: key 'drive.max_tilt_deg': max_tilt = 1.2 rad is outside (0, 0.785]"

#include <array>
#include <concepts>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/params.hpp"
#include "rover/base/status.hpp"

namespace rover {

namespace internal {

/// One parameter of an options struct, type-erased over the struct.
struct BoundParam {
  std::string key;  ///< relative to the prefix given at declaration
  ParamType type = ParamType::kDouble;
  std::string unit;
  std::string doc;
  std::vector<std::string> fields;  ///< names Validate() messages use for this member
  std::optional<double> min, max;
  std::vector<std::string> one_of;
  std::optional<std::size_t> size;
  std::function<ParamValue(const void* options)> get;
  std::function<void(void* options, const ParamValue& value)> set;
};

void DeclareBound(ParamSet& params, const std::string& prefix, const BoundParam& b,
                  const void* defaults);
void ReadBound(const ParamSet& params, const std::string& prefix, const BoundParam& b,
               void* options);
/// Maps a Validate() failure to the key of the field its message starts with.
Status AttributeToKey(const ParamSet& params, const std::string& prefix,
                      const std::deque<BoundParam>& bound, const Status& failure);
std::vector<std::string> DefaultFields(const std::string& key);

}  // namespace internal

template <class Options>
class ParamBinder {
 public:
  /// Constraints of one bound parameter, in the parameter's unit.
  class Binding {
   public:
    explicit Binding(internal::BoundParam& p) : p_(&p) {}
    Binding& Range(double lo, double hi) {
      ROVER_DEMAND(lo <= hi);
      p_->min = lo;
      p_->max = hi;
      return *this;
    }
    Binding& Min(double lo) {
      p_->min = lo;
      return *this;
    }
    Binding& Max(double hi) {
      p_->max = hi;
      return *this;
    }
    Binding& OneOf(std::vector<std::string> values) {
      ROVER_DEMAND(p_->type == ParamType::kString);
      p_->one_of = std::move(values);
      return *this;
    }
    Binding& Size(std::size_t n) {
      ROVER_DEMAND(p_->type == ParamType::kDoubleList);
      p_->size = n;
      return *this;
    }
    /// Another name Validate() messages use for this member (the key, and the key without a
    /// unit suffix such as _deg or _s, are known already).
    Binding& Field(std::string name) {
      p_->fields.push_back(std::move(name));
      return *this;
    }

   private:
    internal::BoundParam* p_;
  };

  /// A number in the member's own unit.
  Binding Bind(std::string key, double Options::*m, std::string unit, std::string doc) {
    return BindScaled(std::move(key), m, 1.0, std::move(unit), std::move(doc));
  }
  /// A number whose member holds value * scale (e.g. a key in mm for a member in m: 1e-3).
  Binding BindScaled(std::string key, double Options::*m, double scale, std::string unit,
                     std::string doc) {
    ROVER_DEMAND(scale != 0.0);
    return Add(std::move(key), ParamType::kDouble, std::move(unit), std::move(doc),
               [m, scale](const Options& o) -> ParamValue { return o.*m / scale; },
               [m, scale](Options& o, const ParamValue& v) { o.*m = std::get<double>(v) * scale; });
  }
  /// An angle given in degrees for a member in radians.
  Binding BindDegrees(std::string key, double Options::*m, std::string doc) {
    return BindScaled(std::move(key), m, 3.14159265358979323846 / 180.0, "deg", std::move(doc));
  }
  /// Any integer member (ranges are checked before the cast: declare one that fits).
  template <std::integral I>
    requires(!std::same_as<I, bool>)
  Binding Bind(std::string key, I Options::*m, std::string unit, std::string doc) {
    return Add(std::move(key), ParamType::kInt, std::move(unit), std::move(doc),
               [m](const Options& o) -> ParamValue { return static_cast<std::int64_t>(o.*m); },
               [m](Options& o, const ParamValue& v) {
                 o.*m = static_cast<I>(std::get<std::int64_t>(v));
               });
  }
  Binding Bind(std::string key, bool Options::*m, std::string doc) {
    return Add(std::move(key), ParamType::kBool, "", std::move(doc),
               [m](const Options& o) -> ParamValue { return o.*m; },
               [m](Options& o, const ParamValue& v) { o.*m = std::get<bool>(v); });
  }
  Binding Bind(std::string key, std::string Options::*m, std::string doc) {
    return Add(std::move(key), ParamType::kString, "", std::move(doc),
               [m](const Options& o) -> ParamValue { return o.*m; },
               [m](Options& o, const ParamValue& v) { o.*m = std::get<std::string>(v); });
  }
  Binding Bind(std::string key, std::vector<double> Options::*m, std::string unit,
               std::string doc) {
    return Add(std::move(key), ParamType::kDoubleList, std::move(unit), std::move(doc),
               [m](const Options& o) -> ParamValue { return o.*m; },
               [m](Options& o, const ParamValue& v) { o.*m = std::get<std::vector<double>>(v); });
  }
  /// A fixed-size list (its size is declared).
  template <std::size_t N>
  Binding Bind(std::string key, std::array<double, N> Options::*m, std::string unit,
               std::string doc) {
    Binding b = Add(std::move(key), ParamType::kDoubleList, std::move(unit), std::move(doc),
                    [m](const Options& o) -> ParamValue {
                      return std::vector<double>((o.*m).begin(), (o.*m).end());
                    },
                    [m](Options& o, const ParamValue& v) {
                      const auto& l = std::get<std::vector<double>>(v);
                      for (std::size_t i = 0; i < N && i < l.size(); ++i) (o.*m)[i] = l[i];
                    });
    b.Size(N);
    return b;
  }
  /// An enumeration given by name; the names are the allowed values.
  template <class E>
    requires std::is_enum_v<E>
  Binding BindEnum(std::string key, E Options::*m, std::vector<std::pair<std::string, E>> names,
                   std::string doc) {
    std::vector<std::string> allowed;
    for (const auto& [n, _] : names) allowed.push_back(n);
    Binding b = Add(std::move(key), ParamType::kString, "", std::move(doc),
                    [m, names](const Options& o) -> ParamValue {
                      for (const auto& [n, e] : names) {
                        if (e == o.*m) return n;
                      }
                      ROVER_UNREACHABLE();  // a default that has no name
                    },
                    [m, names](Options& o, const ParamValue& v) {
                      for (const auto& [n, e] : names) {
                        if (n == std::get<std::string>(v)) o.*m = e;
                      }
                    });
    b.OneOf(std::move(allowed));
    return b;
  }
  /// Anything else: `get` gives the parameter value of a struct, `set` stores one into it.
  Binding BindCustom(std::string key, ParamType type, std::string unit, std::string doc,
                     std::function<ParamValue(const Options&)> get,
                     std::function<void(Options&, const ParamValue&)> set) {
    return Add(std::move(key), type, std::move(unit), std::move(doc), std::move(get),
               std::move(set));
  }
  /// The parameters of a member struct (with its own BindParams), under `prefix` ("prior.").
  template <class Sub>
  void Nest(const std::string& prefix, Sub Options::*m) {
    ParamBinder<Sub> sub;
    Sub::BindParams(sub);
    for (const internal::BoundParam& p : sub.params()) {
      internal::BoundParam q = p;
      q.key = prefix + p.key;
      q.get = [m, g = p.get](const void* o) {
        return g(&(static_cast<const Options*>(o)->*m));
      };
      q.set = [m, s = p.set](void* o, const ParamValue& v) {
        s(&(static_cast<Options*>(o)->*m), v);
      };
      params_.push_back(std::move(q));
    }
  }

  const std::deque<internal::BoundParam>& params() const { return params_; }

 private:
  Binding Add(std::string key, ParamType type, std::string unit, std::string doc,
              std::function<ParamValue(const Options&)> get,
              std::function<void(Options&, const ParamValue&)> set) {
    for (const auto& p : params_) ROVER_DEMAND_MSG(p.key != key, "parameter bound twice");
    internal::BoundParam p;
    p.fields = internal::DefaultFields(key);
    p.key = std::move(key);
    p.type = type;
    p.unit = std::move(unit);
    p.doc = std::move(doc);
    p.get = [g = std::move(get)](const void* o) { return g(*static_cast<const Options*>(o)); };
    p.set = [s = std::move(set)](void* o, const ParamValue& v) { s(*static_cast<Options*>(o), v); };
    params_.push_back(std::move(p));
    return Binding(params_.back());
  }

  std::deque<internal::BoundParam> params_;
};

/// An options struct that lists its parameters.
template <class Options>
concept BindsParams = requires(ParamBinder<Options>& b) { Options::BindParams(b); };

/// The parameters of `Options` as a list (for documentation tools and tests).
template <BindsParams Options>
std::deque<internal::BoundParam> BoundParams() {
  ParamBinder<Options> b;
  Options::BindParams(b);
  return b.params();
}

/// Declares every parameter of `Options` under `prefix`, with `defaults`' values as defaults.
template <BindsParams Options>
void DeclareParams(ParamSet& params, const std::string& prefix,
                   const Options& defaults = Options{}) {
  for (const auto& p : BoundParams<Options>()) internal::DeclareBound(params, prefix, p, &defaults);
}

/// Reads `Options` from (validated) parameters declared by DeclareParams, starting from `base`
/// for members that are not bound, then runs Options::Validate() if it has one. Errors name
/// the file, line and key.
template <BindsParams Options>
Result<Options> ReadParams(const ParamSet& params, const std::string& prefix,
                           Options base = Options{}) {
  ROVER_RETURN_IF_ERROR(params.Validate());
  const auto bound = BoundParams<Options>();
  for (const auto& p : bound) internal::ReadBound(params, prefix, p, &base);
  if constexpr (requires(const Options& o) {
                  { o.Validate() } -> std::same_as<Status>;
                }) {
    const Status s = base.Validate();
    if (!s.ok()) return internal::AttributeToKey(params, prefix, bound, s);
  }
  return base;
}

}  // namespace rover
