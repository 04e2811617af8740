#pragma once
/// @file
/// Reading and filling the idlc-generated C structs without DDS: sequences, bounded strings and
/// enum fields. Header-only; used by the conversions in core/msg and by the DDS wrappers in
/// core/runtime (rover::dds re-exports BorrowSequence, View and CopyString).

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace rover::idl {

/// Points a DDS sequence at memory the caller keeps alive until the sample is written.
template <class Seq, class V>
requires requires(Seq& s, V& c) { s._buffer = c.data(); }
void BorrowSequence(Seq& seq, V& container) {
  seq._buffer = container.data();
  seq._length = static_cast<std::uint32_t>(container.size());
  seq._maximum = static_cast<std::uint32_t>(container.size());
  seq._release = false;
}

/// Points a DDS sequence at read-only memory. DDS only reads a borrowed buffer while writing;
/// the C struct has no const member, hence the cast.
template <class Seq, class E>
void BorrowSequence(Seq& seq, std::span<const E> view) {
  using Element = std::remove_pointer_t<decltype(seq._buffer)>;
  static_assert(std::is_same_v<std::remove_cv_t<E>, Element>, "element types differ");
  seq._buffer = const_cast<Element*>(view.data());
  seq._length = static_cast<std::uint32_t>(view.size());
  seq._maximum = static_cast<std::uint32_t>(view.size());
  seq._release = false;
}

/// A read-only view of a received sequence.
template <class Seq>
auto View(const Seq& seq) {
  using E = std::remove_pointer_t<decltype(seq._buffer)>;
  return std::span<const E>(seq._buffer, seq._length);
}

/// Copies a std::string into a bounded IDL string (char[N]), truncating.
template <std::size_t N>
void CopyString(char (&dst)[N], std::string_view src) {
  const std::size_t n = std::min(src.size(), N - 1);
  std::memcpy(dst, src.data(), n);
  dst[n] = '\0';
}

/// The text of a bounded IDL string (stops at N characters if no terminator is there).
template <std::size_t N>
std::string ReadString(const char (&src)[N]) {
  return std::string(src, strnlen(src, N));
}

/// The integer stored in a C enum field, whatever its value on the wire (an out-of-range value
/// read through the enum type would be undefined behaviour).
template <class E>
std::int32_t RawEnum(const E& e) {
  static_assert(sizeof(E) == sizeof(std::int32_t), "IDL enums are 32 bit");
  std::int32_t v = 0;
  std::memcpy(&v, &e, sizeof v);
  return v;
}

/// Stores any integer in a C enum field (tests use it to play corrupt samples).
template <class E>
void SetRawEnum(E* e, std::int32_t value) {
  static_assert(sizeof(E) == sizeof(std::int32_t), "IDL enums are 32 bit");
  std::memcpy(e, &value, sizeof value);
}

}  // namespace rover::idl
