#pragma once
// Private to rover_msg_idl: reading a C enum field into a library enum with a check, and the
// small conversions several message families share.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "rover/base/status.hpp"
#include "rover/idl/access.hpp"
#include "rover/idl/types.hpp"

namespace rover::msg::internal {

/// The library enum of a C enum field whose IDL has `count` enumerators 0 .. count-1 (same
/// ordinals as E). InvalidArgument "<field> = 7 is not a <type> (0..3)" otherwise.
template <class E, class C>
Result<E> EnumFromIdl(const C& field_value, int count, std::string_view field,
                      std::string_view type) {
  const std::int32_t v = idl::RawEnum(field_value);
  if (v < 0 || v >= count) {
    return InvalidArgument(std::string(field) + " = " + std::to_string(v) + " is not a " +
                           std::string(type) + " (0.." + std::to_string(count - 1) + ")");
  }
  return static_cast<E>(v);
}

/// The library enum of a command's C enum field, value kept as it is (the consumer rejects an
/// unknown one with its typed reason).
template <class E, class C>
E RawEnumFromIdl(const C& field_value) {
  return static_cast<E>(idl::RawEnum(field_value));
}

/// The C enum of a library enum (same ordinals).
template <class C, class E>
C EnumToIdl(E value) {
  return static_cast<C>(static_cast<std::int32_t>(value));
}

/// A size or count clamped into an IDL uint16 field.
inline std::uint16_t ClampSize(int v) {
  return static_cast<std::uint16_t>(std::clamp(v, 0, 65535));
}

inline rover_Vector3 Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d Vec(const rover_Vector3& v) { return {v.x, v.y, v.z}; }

}  // namespace rover::msg::internal
