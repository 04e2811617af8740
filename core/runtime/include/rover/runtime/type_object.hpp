#pragma once
/// @file
/// Member names of a topic type, read from the XTypes metadata idlc puts into every topic
/// descriptor (`dds_topic_descriptor_t::type_mapping`).
///
/// The TypeMapping is XCDR2 (little endian) and holds, for every type the topic uses, a MINIMAL
/// and a COMPLETE TypeObject (OMG DDS-XTypes 1.3, 7.3.4). Only COMPLETE TypeObjects carry member
/// names; this decoder reads those of structures, aliases and enumerations and records the kind
/// of every other one. Member *layout* (offsets, sizes) does not come from here: the descriptor's
/// serialiser program has it (type_layout.hpp). Wire layout decoded (XCDR2):
///
///   TypeMapping (final)       = seq<pair> minimal, seq<pair> complete, seq<id pair>
///   pair (final)              = TypeIdentifier, TypeObject
///   TypeObject (appendable)   = DHEADER, octet EK_COMPLETE|EK_MINIMAL, union by TypeKind
///   CompleteStructType        = uint16 flags, header (appendable: base TypeIdentifier, detail
///                               with optional annotations and the qualified name), member seq
///   CompleteStructMember      = DHEADER, uint32 id, uint16 flags, TypeIdentifier, name, ...
///
/// A sequence of non-primitive elements starts with a DHEADER, so anything this decoder does
/// not need is skipped by length, not parsed.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::dds {

/// A decoded XTypes TypeIdentifier: a primitive, a string, a plain collection, or a hash that
/// names a TypeObject of the same mapping.
struct XTypeId {
  enum class Kind { kPrimitive, kString, kSequence, kArray, kMap, kHash, kOther };
  using Hash = std::array<std::uint8_t, 14>;

  Kind kind = Kind::kOther;
  std::uint8_t discriminator = 0;      ///< the TypeIdentifier's octet (TK_* or TI_* or EK_*)
  Hash hash{};                         ///< kHash
  std::uint32_t bound = 0;             ///< kString, kSequence: 0 = unbounded
  std::vector<std::uint32_t> dims;     ///< kArray: dimensions, outermost first
  std::shared_ptr<const XTypeId> element;  ///< kSequence, kArray, kMap
};

/// One member of a structure, or one literal of an enumeration (then `value` is set).
struct XMember {
  std::string name;
  std::uint32_t id = 0;
  XTypeId type;
  std::int32_t value = 0;
};

/// A COMPLETE TypeObject.
struct XType {
  enum class Kind { kStruct, kAlias, kEnum, kUnion, kOther };
  Kind kind = Kind::kOther;
  std::uint8_t type_kind = 0;  ///< TK_* octet
  std::string name;            ///< qualified IDL name, e.g. "rover::dl::PoseEstimate"
  XTypeId base;                ///< kStruct: base type (kPrimitive TK_NONE when none)
  std::vector<XMember> members;  ///< kStruct: members in declaration order; kEnum: literals
  XTypeId aliased;             ///< kAlias: the related type
};

/// The COMPLETE TypeObjects of one topic descriptor, by hash and by name.
class XTypeTable {
 public:
  /// Decodes an XCDR2 TypeMapping. Malformed data is InvalidArgument naming the byte offset.
  static Result<XTypeTable> Decode(const std::uint8_t* data, std::size_t size);

  const XType* Find(const XTypeId::Hash& hash) const;
  /// By qualified name ("rover::dl::PoseEstimate").
  const XType* FindByName(const std::string& name) const;
  /// Follows aliases until a non-alias type identifier (at most 16 levels).
  const XTypeId& Unalias(const XTypeId& id) const;
  std::size_t size() const { return types_.size(); }

 private:
  std::map<XTypeId::Hash, XType> types_;
};

}  // namespace rover::dds
