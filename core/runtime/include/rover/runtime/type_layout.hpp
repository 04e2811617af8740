#pragma once
/// @file
/// The in-memory layout of any idlc-generated topic type, with member names, and field paths
/// resolved against it, so that the fault seam can change a named field of any catalog type.
///
/// Layout (offsets, sizes, arrays, sequences, strings, enums, nested structs) comes from the
/// descriptor's serialiser program (`m_ops`, dds_opcodes.h): one ADR instruction per member, in
/// declaration order. Names come from the descriptor's COMPLETE XTypes TypeObjects
/// (type_object.hpp), matched to the ADR instructions by position. A type whose ops and
/// TypeObjects disagree (member counts, nested kinds) is an error, never a guess.
///
/// Memory model of idlc's C mapping (what Copy/Free rely on): a struct is a C struct; an array
/// is inline; a sequence is dds_sequence_t {uint32 _maximum, uint32 _length, T* _buffer,
/// bool _release}; a bounded string is char[bound + 1] inline; an unbounded string is char*.
/// Unions and @optional/@external members are recorded but not addressable or copyable.
///
/// Field paths: member names joined by '.', with an index or '*' per array/sequence level:
///   pose.position.x   header.stamp_ns   covariance[3]   wheel_angle[*]   waypoints[*].x
/// A path that ends at a struct or a collection selects every leaf below it.

#include <dds/dds.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::dds {

enum class FieldKind {
  kBool,
  kInt,            ///< signed integer of `size` bytes
  kUInt,           ///< unsigned integer (and char, octet) of `size` bytes
  kFloat,          ///< float (4) or double (8)
  kEnum,           ///< enumeration stored in `size` bytes, literals 0..enum_max
  kBitmask,
  kBoundedString,  ///< char[capacity] inline
  kString,         ///< char* (unbounded)
  kStruct,
  kArray,          ///< `length` elements of `element` inline
  kSequence,       ///< dds_sequence_t of `element`
  kUnion,          ///< not addressable
  kExternal,       ///< @optional / @external member (a pointer): not addressable
};
const char* FieldKindName(FieldKind kind);
/// The kind with its article: "an enum", "a struct".
std::string FieldKindPhrase(FieldKind kind);

/// One node of a type's layout tree.
struct FieldNode {
  std::string name;             ///< member name; "" for the root and collection elements
  FieldKind kind = FieldKind::kStruct;
  std::uint32_t offset = 0;     ///< bytes from the start of the enclosing struct or element
  std::uint32_t size = 0;       ///< bytes the value occupies in its parent (element stride)
  std::uint32_t enum_max = 0;   ///< kEnum: largest literal value
  std::uint32_t capacity = 0;   ///< kBoundedString: bytes including the terminating NUL
  std::uint32_t length = 0;     ///< kArray: elements (all dimensions)
  std::vector<std::uint32_t> dims;  ///< kArray: dimensions, outermost first
  std::uint32_t bound = 0;      ///< kSequence: 0 = unbounded
  std::string type_name;        ///< kStruct, kEnum: qualified IDL name when known
  std::vector<FieldNode> members;   ///< kStruct
  std::vector<FieldNode> element;   ///< kArray, kSequence: exactly one node

  bool numeric() const {
    return kind == FieldKind::kInt || kind == FieldKind::kUInt || kind == FieldKind::kFloat;
  }
  const FieldNode& elem() const { return element.front(); }
};

/// The layout of one topic type.
class TypeLayout {
 public:
  /// The layout of `type`, built once per descriptor and cached (thread-safe).
  static Result<std::shared_ptr<const TypeLayout>> For(const dds_topic_descriptor_t* type);
  /// Builds without the cache (tests).
  static Result<TypeLayout> Build(const dds_topic_descriptor_t* type);

  const FieldNode& root() const { return root_; }
  /// Qualified IDL name, e.g. "rover::dl::PoseEstimate".
  const std::string& type_name() const { return root_.type_name; }
  const dds_topic_descriptor_t* descriptor() const { return descriptor_; }
  /// Whether Copy/Free can handle every member (no unions, no optional/external members).
  bool copyable() const { return copyable_; }
  /// True when the type has no pointers (no sequences, no unbounded strings): a copy is memcpy.
  bool flat() const { return flat_; }
  /// Every path down to every member, e.g. "pose", "pose.position", "pose.position.x",
  /// "covariance" (collections without index). For suggestions and docs.
  std::vector<std::string> MemberPaths() const;

  /// Allocates (dds_alloc) a deep copy of `src`: sequences get their own buffers
  /// (_release = true), unbounded strings are duplicated. Free it with Free(). Precondition:
  /// copyable().
  void* Clone(const void* src) const;
  /// Deep-copies `src` into `dst`, whose contents must be empty (zeroed); the copy owns its
  /// buffers like Clone's, so dds_sample_free(dst, ..., DDS_FREE_CONTENTS) frees it too.
  void CopyInto(void* dst, const void* src) const;
  /// Frees a Clone() (its buffers and itself).
  void Free(void* sample) const;

 private:
  FieldNode root_;
  const dds_topic_descriptor_t* descriptor_ = nullptr;
  bool copyable_ = true;
  bool flat_ = true;
};

/// A field path resolved against a layout: a walk from the root to a set of leaves.
class FieldSelector {
 public:
  /// Parses and resolves `path`. An unknown member is NotFound naming the type and the nearest
  /// member paths; a bad index is OutOfRange naming the array's length.
  static Result<FieldSelector> Resolve(const TypeLayout& layout, std::string_view path);

  /// Calls `fn(address, node)` for every selected leaf of `sample` (sequence indices beyond
  /// the sample's length are skipped). Leaves are scalars and strings.
  void ForEachLeaf(void* sample, const std::function<void(void*, const FieldNode&)>& fn) const;
  /// The leaf kinds this selection can reach (for validating a fault against the type).
  const std::vector<const FieldNode*>& leaf_nodes() const { return leaves_; }
  const std::string& path() const { return path_; }

 private:
  struct Step {
    enum class Op { kMember, kIndex, kAll } op;
    const FieldNode* node;  // the node this step enters
    std::uint32_t index = 0;
  };
  void Walk(char* base, const FieldNode& node, std::size_t step,
            const std::function<void(void*, const FieldNode&)>& fn) const;
  void WalkAll(char* base, const FieldNode& node,
               const std::function<void(void*, const FieldNode&)>& fn) const;

  std::string path_;
  const FieldNode* root_ = nullptr;
  std::vector<Step> steps_;
  std::vector<const FieldNode*> leaves_;
};

}  // namespace rover::dds
