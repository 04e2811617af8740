#include "rover/runtime/type_layout.hpp"

#include <dds/ddsc/dds_opcodes.h>
#include <dds/ddsi/ddsi_cdrstream.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>

#include "rover/base/check.hpp"
#include "rover/base/params.hpp"
#include "rover/runtime/type_object.hpp"

namespace rover::dds {

const char* FieldKindName(FieldKind kind) {
  switch (kind) {
    case FieldKind::kBool: return "boolean";
    case FieldKind::kInt: return "signed integer";
    case FieldKind::kUInt: return "unsigned integer";
    case FieldKind::kFloat: return "floating-point";
    case FieldKind::kEnum: return "enum";
    case FieldKind::kBitmask: return "bitmask";
    case FieldKind::kBoundedString: return "bounded string";
    case FieldKind::kString: return "string";
    case FieldKind::kStruct: return "struct";
    case FieldKind::kArray: return "array";
    case FieldKind::kSequence: return "sequence";
    case FieldKind::kUnion: return "union";
    case FieldKind::kExternal: return "optional or external member";
  }
  return "?";
}

std::string FieldKindPhrase(FieldKind kind) {
  const std::string name = FieldKindName(kind);
  const bool an = kind == FieldKind::kUInt || kind == FieldKind::kEnum ||
                  kind == FieldKind::kArray || kind == FieldKind::kExternal;
  return (an ? "an " : "a ") + name;
}

namespace {

constexpr int kMaxDepth = 32;

bool HasPointers(const FieldNode& n) {
  switch (n.kind) {
    case FieldKind::kString:
    case FieldKind::kSequence:
    case FieldKind::kUnion:
    case FieldKind::kExternal:
      return true;
    case FieldKind::kStruct:
      return std::any_of(n.members.begin(), n.members.end(), HasPointers);
    case FieldKind::kArray:
      return HasPointers(n.elem());
    default:
      return false;
  }
}

bool Copyable(const FieldNode& n) {
  switch (n.kind) {
    case FieldKind::kUnion:
    case FieldKind::kExternal:
      return false;
    case FieldKind::kStruct:
      return std::all_of(n.members.begin(), n.members.end(), Copyable);
    case FieldKind::kArray:
    case FieldKind::kSequence:
      return Copyable(n.elem());
    default:
      return true;
  }
}

bool IsSimple(std::uint32_t typecode) {
  switch (typecode) {
    case DDS_OP_VAL_1BY: case DDS_OP_VAL_2BY: case DDS_OP_VAL_4BY: case DDS_OP_VAL_8BY:
    case DDS_OP_VAL_BLN: case DDS_OP_VAL_ENU: case DDS_OP_VAL_BMK: case DDS_OP_VAL_STR:
    case DDS_OP_VAL_BST:
      return true;
    default:
      return false;
  }
}

std::uint32_t High16(std::uint32_t w) { return w >> 16; }
std::uint32_t Low16(std::uint32_t w) { return w & 0xffffu; }

// Walks the serialiser program of one descriptor alongside its COMPLETE TypeObjects.
class Builder {
 public:
  Builder(const dds_topic_descriptor_t* d, const XTypeTable& xt)
      // m_nops counts instructions; the bound is in words.
      : ops_(d->m_ops),
        nops_(dds_stream_countops(d->m_ops, d->m_nkeys, d->m_keys)),
        xt_(xt),
        type_(d->m_typename) {}

  Status Struct(std::uint32_t pc, const XType* xs, FieldNode* out, int depth) {
    if (depth > kMaxDepth) return Fail("types nested deeper than 32 levels");
    if (xs == nullptr || xs->kind != XType::Kind::kStruct) {
      return Fail("no COMPLETE struct TypeObject for the struct at ops[" + std::to_string(pc) + "]");
    }
    out->kind = FieldKind::kStruct;
    out->type_name = xs->name;
    std::size_t mi = 0;
    while (true) {
      ROVER_RETURN_IF_ERROR(Need(pc, 1));
      const std::uint32_t op = ops_[pc];
      const std::uint32_t code = DDS_OP(op);
      if (code == DDS_OP_RTS || code == DDS_OP_KOF) break;
      if (code == DDS_OP_DLC) {  // appendable: a DHEADER on the wire, same memory layout
        ++pc;
        continue;
      }
      if (code == DDS_OP_PLC || code == DDS_OP_PLM) return Fail("mutable types are not supported");
      if (code != DDS_OP_ADR) {
        return Fail("unexpected opcode " + std::to_string(code >> 24) + " at ops[" +
                    std::to_string(pc) + "]");
      }
      if (DDS_OP_TYPE(op) == DDS_OP_VAL_EXT && (DDS_OP_FLAGS(op) & DDS_OP_FLAG_BASE) != 0) {
        // The members of a base struct come first, inline.
        ROVER_RETURN_IF_ERROR(Need(pc, 3));
        FieldNode base;
        ROVER_RETURN_IF_ERROR(
            Struct(pc + Low16(ops_[pc + 2]), StructFor(xs->base), &base, depth + 1));
        for (auto& m : base.members) {
          m.offset += ops_[pc + 1];
          out->members.push_back(std::move(m));
        }
        pc += High16(ops_[pc + 2]);
        continue;
      }
      if (mi >= xs->members.size()) {
        return Fail(xs->name + ": the ops have more members than the TypeObject's " +
                    std::to_string(xs->members.size()));
      }
      const XMember& m = xs->members[mi++];
      FieldNode node;
      std::uint32_t next = 0;
      ROVER_RETURN_IF_ERROR(Member(pc, &m.type, &node, &next, depth));
      node.name = m.name;
      out->members.push_back(std::move(node));
      pc = next;
    }
    if (mi != xs->members.size()) {
      return Fail(xs->name + ": the TypeObject has " + std::to_string(xs->members.size()) +
                  " members, the ops " + std::to_string(mi));
    }
    return Status::Ok();
  }

 private:
  Status Fail(const std::string& what) const {
    return InvalidArgument("layout of " + type_ + ": " + what);
  }
  Status Need(std::uint32_t pc, std::uint32_t n) const {
    if (pc + n > nops_) return Fail("ops end inside the instruction at ops[" + std::to_string(pc) + "]");
    return Status::Ok();
  }

  const XType* StructFor(const XTypeId& id) const {
    const XTypeId& t = xt_.Unalias(id);
    if (t.kind != XTypeId::Kind::kHash) return nullptr;
    return xt_.Find(t.hash);
  }
  const XTypeId* ElementOf(const XTypeId* id) const {
    if (id == nullptr) return nullptr;
    const XTypeId& t = xt_.Unalias(*id);
    return t.element ? t.element.get() : nullptr;
  }

  // A scalar or string of typecode `code` whose flags come from `op`; `arg` is the word with
  // the enum max or the bounded string size, where applicable.
  static void Scalar(std::uint32_t code, std::uint32_t op, std::uint32_t arg, FieldNode* n) {
    const std::uint32_t flags = DDS_OP_FLAGS(op);
    switch (code) {
      case DDS_OP_VAL_1BY: case DDS_OP_VAL_2BY: case DDS_OP_VAL_4BY: case DDS_OP_VAL_8BY:
        n->size = 1u << (code - DDS_OP_VAL_1BY);
        n->kind = (flags & DDS_OP_FLAG_FP) ? FieldKind::kFloat
                  : (flags & DDS_OP_FLAG_SGN) ? FieldKind::kInt
                                              : FieldKind::kUInt;
        break;
      case DDS_OP_VAL_BLN:
        n->kind = FieldKind::kBool;
        n->size = 1;
        break;
      case DDS_OP_VAL_ENU:
        n->kind = FieldKind::kEnum;
        n->size = DDS_OP_TYPE_SZ(op);
        n->enum_max = arg;
        break;
      case DDS_OP_VAL_BMK:
        n->kind = FieldKind::kBitmask;
        n->size = DDS_OP_TYPE_SZ(op);
        break;
      case DDS_OP_VAL_STR:
        n->kind = FieldKind::kString;
        n->size = sizeof(char*);
        break;
      case DDS_OP_VAL_BST:
        n->kind = FieldKind::kBoundedString;
        n->capacity = arg;
        n->size = arg;
        break;
      default:
        break;
    }
  }

  // The element of a SEQ/BSQ/ARR instruction at `pc`. `args` is the index of its first word
  // after [offset] (and [sbound] / [alen]).
  Status Element(std::uint32_t pc, std::uint32_t args, bool array, const XTypeId* elem_id,
                 FieldNode* out, int depth) {
    const std::uint32_t op = ops_[pc];
    const std::uint32_t sub = DDS_OP_SUBTYPE(op);
    if (IsSimple(sub)) {
      std::uint32_t arg = 0;
      if (sub == DDS_OP_VAL_ENU) {
        ROVER_RETURN_IF_ERROR(Need(args, 1));
        arg = ops_[args];
      } else if (sub == DDS_OP_VAL_BST) {
        const std::uint32_t at = array ? args + 1 : args;  // ARR BST: [0] [max-size]
        ROVER_RETURN_IF_ERROR(Need(at, 1));
        arg = ops_[at];
      }
      Scalar(sub, op, arg, out);
      if (sub == DDS_OP_VAL_ENU && elem_id != nullptr) {
        const XTypeId& t = xt_.Unalias(*elem_id);
        if (t.kind == XTypeId::Kind::kHash) {
          if (const XType* e = xt_.Find(t.hash)) out->type_name = e->name;
        }
      }
      return Status::Ok();
    }
    // [elem-size] [next-insn, elem-insn] for sequences, the other way round for arrays.
    ROVER_RETURN_IF_ERROR(Need(args, 2));
    const std::uint32_t elem_size = array ? ops_[args + 1] : ops_[args];
    const std::uint32_t jump = array ? ops_[args] : ops_[args + 1];
    const std::uint32_t target = pc + Low16(jump);
    if (sub == DDS_OP_VAL_STU) {
      ROVER_RETURN_IF_ERROR(Struct(target, elem_id ? StructFor(*elem_id) : nullptr, out, depth + 1));
    } else if (sub == DDS_OP_VAL_UNI) {
      out->kind = FieldKind::kUnion;
    } else {
      std::uint32_t ignored = 0;
      ROVER_RETURN_IF_ERROR(Member(target, elem_id, out, &ignored, depth + 1));
      out->offset = 0;
    }
    out->size = elem_size;
    return Status::Ok();
  }

  // One ADR instruction at `pc` describing a member whose TypeIdentifier is `id` (may be null
  // for collection elements of unknown type).
  Status Member(std::uint32_t pc, const XTypeId* id, FieldNode* n, std::uint32_t* next, int depth) {
    if (depth > kMaxDepth) return Fail("types nested deeper than 32 levels");
    ROVER_RETURN_IF_ERROR(Need(pc, 2));
    const std::uint32_t op = ops_[pc];
    if (DDS_OP(op) != DDS_OP_ADR) return Fail("expected an ADR at ops[" + std::to_string(pc) + "]");
    const std::uint32_t code = DDS_OP_TYPE(op);
    n->offset = ops_[pc + 1];
    const bool external = (op & DDS_OP_FLAG_EXT) != 0;
    std::uint32_t len = 2;
    switch (code) {
      case DDS_OP_VAL_1BY: case DDS_OP_VAL_2BY: case DDS_OP_VAL_4BY: case DDS_OP_VAL_8BY:
      case DDS_OP_VAL_BLN: case DDS_OP_VAL_STR:
        Scalar(code, op, 0, n);
        break;
      case DDS_OP_VAL_ENU: case DDS_OP_VAL_BST:
        ROVER_RETURN_IF_ERROR(Need(pc, 3));
        Scalar(code, op, ops_[pc + 2], n);
        len = 3;
        if (code == DDS_OP_VAL_ENU && id != nullptr) {
          const XTypeId& t = xt_.Unalias(*id);
          if (t.kind == XTypeId::Kind::kHash) {
            if (const XType* e = xt_.Find(t.hash)) n->type_name = e->name;
          }
        }
        break;
      case DDS_OP_VAL_BMK:
        Scalar(code, op, 0, n);
        len = 4;
        break;
      case DDS_OP_VAL_SEQ:
      case DDS_OP_VAL_BSQ: {
        const bool bounded = code == DDS_OP_VAL_BSQ;
        const std::uint32_t args = pc + 2 + (bounded ? 1 : 0);
        ROVER_RETURN_IF_ERROR(Need(pc, args - pc));
        n->kind = FieldKind::kSequence;
        n->size = sizeof(dds_sequence_t);
        n->bound = bounded ? ops_[pc + 2] : 0;
        n->element.emplace_back();
        ROVER_RETURN_IF_ERROR(Element(pc, args, false, ElementOf(id), &n->element[0], depth));
        const std::uint32_t sub = DDS_OP_SUBTYPE(op);
        const std::uint32_t extra = sub == DDS_OP_VAL_ENU || sub == DDS_OP_VAL_BST ? 1
                                    : sub == DDS_OP_VAL_BMK                      ? 2
                                                                                 : 0;
        len = IsSimple(sub) ? (args - pc) + extra : High16(ops_[args + 1]);
        break;
      }
      case DDS_OP_VAL_ARR: {
        ROVER_RETURN_IF_ERROR(Need(pc, 3));
        n->kind = FieldKind::kArray;
        n->length = ops_[pc + 2];
        n->element.emplace_back();
        const XTypeId* elem_id = ElementOf(id);
        ROVER_RETURN_IF_ERROR(Element(pc, pc + 3, true, elem_id, &n->element[0], depth));
        n->size = n->length * n->elem().size;
        if (id != nullptr && xt_.Unalias(*id).kind == XTypeId::Kind::kArray) {
          n->dims = xt_.Unalias(*id).dims;
        }
        if (n->dims.empty()) n->dims = {n->length};
        const std::uint32_t sub = DDS_OP_SUBTYPE(op);
        len = sub == DDS_OP_VAL_ENU                               ? 4
              : sub == DDS_OP_VAL_BST || sub == DDS_OP_VAL_BMK   ? 5
              : IsSimple(sub)                                     ? 3
                                                                  : High16(ops_[pc + 3]);
        break;
      }
      case DDS_OP_VAL_UNI:
        ROVER_RETURN_IF_ERROR(Need(pc, 4));
        n->kind = FieldKind::kUnion;
        len = High16(ops_[pc + 3]);
        break;
      case DDS_OP_VAL_EXT: {
        ROVER_RETURN_IF_ERROR(Need(pc, 3));
        len = High16(ops_[pc + 2]);
        if (external) break;
        const std::uint32_t target = pc + Low16(ops_[pc + 2]);
        ROVER_RETURN_IF_ERROR(Need(target, 1));
        if (DDS_OP(ops_[target]) == DDS_OP_ADR && DDS_OP_TYPE(ops_[target]) == DDS_OP_VAL_UNI) {
          n->kind = FieldKind::kUnion;  // a named union type
          break;
        }
        const XType* xs = id != nullptr ? StructFor(*id) : nullptr;
        ROVER_RETURN_IF_ERROR(Struct(target, xs, n, depth + 1));
        break;
      }
      default:
        return Fail("unsupported member type code " + std::to_string(code) + " at ops[" +
                    std::to_string(pc) + "]");
    }
    if (external || (DDS_OP_FLAGS(op) & DDS_OP_FLAG_OPT) != 0) {
      if (n->kind != FieldKind::kString) {  // an optional string is a char* that may be null
        n->kind = FieldKind::kExternal;
        n->members.clear();
        n->element.clear();
        n->size = sizeof(void*);
      }
    }
    if (len == 0) return Fail("zero-length instruction at ops[" + std::to_string(pc) + "]");
    *next = pc + len;
    return Status::Ok();
  }

  const std::uint32_t* ops_;
  std::uint32_t nops_;
  const XTypeTable& xt_;
  std::string type_;
};

void CollectPaths(const FieldNode& n, const std::string& prefix, std::vector<std::string>* out) {
  if (n.kind == FieldKind::kStruct) {
    for (const auto& m : n.members) {
      const std::string p = prefix.empty() ? m.name : prefix + "." + m.name;
      out->push_back(p);
      CollectPaths(m, p, out);
    }
  } else if ((n.kind == FieldKind::kArray || n.kind == FieldKind::kSequence) &&
             n.elem().kind == FieldKind::kStruct) {
    CollectPaths(n.elem(), prefix + "[*]", out);
  }
}

void CopyPointers(const FieldNode& n, char* dst, const char* src);

void CopyElements(const FieldNode& elem, char* dst, const char* src, std::uint32_t count) {
  if (!HasPointers(elem)) return;
  for (std::uint32_t i = 0; i < count; ++i) {
    CopyPointers(elem, dst + std::size_t{i} * elem.size, src + std::size_t{i} * elem.size);
  }
}

// `dst` holds a memcpy of `src`; give it its own copies of everything pointed to.
void CopyPointers(const FieldNode& n, char* dst, const char* src) {
  switch (n.kind) {
    case FieldKind::kString: {
      const char* s = *reinterpret_cast<char* const*>(src);
      *reinterpret_cast<char**>(dst) = s != nullptr ? dds_string_dup(s) : nullptr;
      break;
    }
    case FieldKind::kStruct:
      for (const auto& m : n.members) CopyPointers(m, dst + m.offset, src + m.offset);
      break;
    case FieldKind::kArray:
      CopyElements(n.elem(), dst, src, n.length);
      break;
    case FieldKind::kSequence: {
      const auto* s = reinterpret_cast<const dds_sequence_t*>(src);
      auto* d = reinterpret_cast<dds_sequence_t*>(dst);
      const std::uint32_t len = s->_length;
      const std::size_t bytes = std::size_t{len} * n.elem().size;
      d->_length = len;
      d->_maximum = len;
      d->_release = true;
      d->_buffer = nullptr;
      if (len > 0 && s->_buffer != nullptr) {
        d->_buffer = static_cast<std::uint8_t*>(dds_alloc(bytes));
        std::memcpy(d->_buffer, s->_buffer, bytes);
        CopyElements(n.elem(), reinterpret_cast<char*>(d->_buffer),
                     reinterpret_cast<const char*>(s->_buffer), len);
      } else {
        d->_length = 0;
        d->_maximum = 0;
      }
      break;
    }
    default:
      break;
  }
}

void FreeContents(const FieldNode& n, char* p) {
  switch (n.kind) {
    case FieldKind::kString: {
      char** s = reinterpret_cast<char**>(p);
      dds_free(*s);
      *s = nullptr;
      break;
    }
    case FieldKind::kStruct:
      for (const auto& m : n.members) FreeContents(m, p + m.offset);
      break;
    case FieldKind::kArray:
      if (HasPointers(n.elem())) {
        for (std::uint32_t i = 0; i < n.length; ++i) FreeContents(n.elem(), p + std::size_t{i} * n.elem().size);
      }
      break;
    case FieldKind::kSequence: {
      auto* s = reinterpret_cast<dds_sequence_t*>(p);
      if (s->_buffer != nullptr && HasPointers(n.elem())) {
        for (std::uint32_t i = 0; i < s->_length; ++i) {
          FreeContents(n.elem(), reinterpret_cast<char*>(s->_buffer) + std::size_t{i} * n.elem().size);
        }
      }
      if (s->_release) dds_free(s->_buffer);
      s->_buffer = nullptr;
      s->_length = s->_maximum = 0;
      break;
    }
    default:
      break;
  }
}

}  // namespace

Result<TypeLayout> TypeLayout::Build(const dds_topic_descriptor_t* type) {
  if (type == nullptr) return InvalidArgument("no topic descriptor");
  if ((type->m_flagset & DDS_TOPIC_XTYPES_METADATA) == 0) {
    return InvalidArgument(std::string("layout of ") + type->m_typename +
                           ": the descriptor has no XTypes metadata (member names)");
  }
  auto table = XTypeTable::Decode(type->type_mapping.data, type->type_mapping.sz);
  if (!table.ok()) {
    return table.status().WithPrefix(std::string("layout of ") + type->m_typename);
  }
  TypeLayout layout;
  layout.descriptor_ = type;
  Builder b(type, *table);
  ROVER_RETURN_IF_ERROR(b.Struct(0, table->FindByName(type->m_typename), &layout.root_, 0));
  layout.root_.size = type->m_size;
  layout.copyable_ = Copyable(layout.root_);
  layout.flat_ = !HasPointers(layout.root_);
  return layout;
}

Result<std::shared_ptr<const TypeLayout>> TypeLayout::For(const dds_topic_descriptor_t* type) {
  static std::mutex mu;
  static std::map<const dds_topic_descriptor_t*, Result<std::shared_ptr<const TypeLayout>>> cache;
  std::lock_guard lock(mu);
  auto it = cache.find(type);
  if (it != cache.end()) return it->second;
  auto built = Build(type);
  Result<std::shared_ptr<const TypeLayout>> r =
      built.ok() ? Result<std::shared_ptr<const TypeLayout>>(
                       std::make_shared<const TypeLayout>(std::move(*built)))
                 : Result<std::shared_ptr<const TypeLayout>>(built.status());
  cache.emplace(type, r);
  return r;
}

std::vector<std::string> TypeLayout::MemberPaths() const {
  std::vector<std::string> out;
  CollectPaths(root_, "", &out);
  return out;
}

void TypeLayout::CopyInto(void* dst, const void* src) const {
  ROVER_DEMAND(copyable_);
  std::memcpy(dst, src, descriptor_->m_size);
  if (!flat_) CopyPointers(root_, static_cast<char*>(dst), static_cast<const char*>(src));
}

void* TypeLayout::Clone(const void* src) const {
  void* p = dds_alloc(descriptor_->m_size);
  CopyInto(p, src);
  return p;
}

void TypeLayout::Free(void* sample) const {
  if (sample == nullptr) return;
  if (!flat_) FreeContents(root_, static_cast<char*>(sample));
  dds_free(sample);
}

// ---- field paths -------------------------------------------------------------------------------

namespace {

struct PathToken {
  enum class Kind { kName, kIndex, kAll } kind;
  std::string name;
  std::uint32_t index = 0;
};

Result<std::vector<PathToken>> Tokenize(std::string_view path) {
  std::vector<PathToken> out;
  std::size_t i = 0;
  auto fail = [&](const std::string& what) {
    return InvalidArgument("field path '" + std::string(path) + "': " + what + " at character " +
                           std::to_string(i + 1));
  };
  auto name_char = [](char c, bool first) {
    return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (!first && c >= '0' && c <= '9');
  };
  if (path.empty()) return InvalidArgument("field path is empty");
  bool expect_name = true;
  while (i < path.size()) {
    if (expect_name) {
      if (!name_char(path[i], true)) return fail("expected a member name");
      const std::size_t start = i;
      while (i < path.size() && name_char(path[i], false)) ++i;
      out.push_back({PathToken::Kind::kName, std::string(path.substr(start, i - start))});
      expect_name = false;
    } else if (path[i] == '.') {
      ++i;
      expect_name = true;
      if (i == path.size()) return fail("expected a member name");
    } else if (path[i] == '[') {
      ++i;
      if (i < path.size() && path[i] == '*') {
        ++i;
        out.push_back({PathToken::Kind::kAll, ""});
      } else {
        const std::size_t start = i;
        std::uint64_t v = 0;
        while (i < path.size() && path[i] >= '0' && path[i] <= '9' && v < 0xffffffffull) {
          v = v * 10 + static_cast<std::uint64_t>(path[i] - '0');
          ++i;
        }
        if (i == start || v > 0xffffffffull) return fail("expected an index or '*'");
        out.push_back({PathToken::Kind::kIndex, "", static_cast<std::uint32_t>(v)});
      }
      if (i >= path.size() || path[i] != ']') return fail("expected ']'");
      ++i;
    } else {
      return fail("expected '.' or '['");
    }
  }
  return out;
}

std::string StripIndices(std::string_view path) {
  std::string out;
  int depth = 0;
  for (char c : path) {
    if (c == '[') ++depth;
    else if (c == ']') --depth;
    else if (depth == 0) out += c;
  }
  return out;
}

std::string Nearest(const TypeLayout& layout, std::string_view path) {
  const std::string key = StripIndices(path);
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& p : layout.MemberPaths()) scored.emplace_back(EditDistance(key, StripIndices(p)), p);
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string out;
  for (std::size_t i = 0; i < scored.size() && i < 3; ++i) {
    out += (i ? ", " : "") + scored[i].second;
  }
  return out;
}

void CollectLeaves(const FieldNode& n, std::vector<const FieldNode*>* out) {
  switch (n.kind) {
    case FieldKind::kStruct:
      for (const auto& m : n.members) CollectLeaves(m, out);
      break;
    case FieldKind::kArray:
    case FieldKind::kSequence:
      CollectLeaves(n.elem(), out);
      break;
    case FieldKind::kUnion:
    case FieldKind::kExternal:
      break;
    default:
      out->push_back(&n);
  }
}

}  // namespace

Result<FieldSelector> FieldSelector::Resolve(const TypeLayout& layout, std::string_view path) {
  auto tokens = Tokenize(path);
  if (!tokens.ok()) return tokens.status();
  FieldSelector sel;
  sel.path_ = std::string(path);
  sel.root_ = &layout.root();
  const FieldNode* cur = &layout.root();
  std::string walked;
  for (const PathToken& t : *tokens) {
    if (t.kind == PathToken::Kind::kName) {
      if (cur->kind != FieldKind::kStruct) {
        return InvalidArgument(layout.type_name() + ": '" + walked + "' is " +
                               FieldKindPhrase(cur->kind) + ", it has no member '" + t.name + "'");
      }
      auto it = std::find_if(cur->members.begin(), cur->members.end(),
                             [&](const FieldNode& m) { return m.name == t.name; });
      if (it == cur->members.end()) {
        return NotFound(layout.type_name() + " has no field '" + std::string(path) +
                        "' (nearest: " + Nearest(layout, path) + ")");
      }
      walked += (walked.empty() ? "" : ".") + t.name;
      cur = &*it;
      if (cur->kind == FieldKind::kUnion || cur->kind == FieldKind::kExternal) {
        return InvalidArgument(layout.type_name() + ": field '" + walked + "' is " +
                               FieldKindPhrase(cur->kind) + "; field paths cannot enter it");
      }
      sel.steps_.push_back({Step::Op::kMember, cur});
    } else {
      if (cur->kind != FieldKind::kArray && cur->kind != FieldKind::kSequence) {
        return InvalidArgument(layout.type_name() + ": '" + walked + "' is " +
                               FieldKindPhrase(cur->kind) + ", not an array or sequence; it takes no index");
      }
      if (t.kind == PathToken::Kind::kIndex) {
        if (cur->kind == FieldKind::kArray && t.index >= cur->length) {
          return OutOfRange(layout.type_name() + ": index " + std::to_string(t.index) + " of '" +
                            walked + "' is out of range; it has " + std::to_string(cur->length) +
                            " elements");
        }
        if (cur->kind == FieldKind::kSequence && cur->bound > 0 && t.index >= cur->bound) {
          return OutOfRange(layout.type_name() + ": index " + std::to_string(t.index) + " of '" +
                            walked + "' is beyond its bound " + std::to_string(cur->bound));
        }
      }
      walked += t.kind == PathToken::Kind::kAll ? "[*]" : "[" + std::to_string(t.index) + "]";
      const FieldNode* collection = cur;
      cur = &collection->elem();
      sel.steps_.push_back({t.kind == PathToken::Kind::kAll ? Step::Op::kAll : Step::Op::kIndex,
                            collection, t.index});
    }
  }
  CollectLeaves(*cur, &sel.leaves_);
  if (sel.leaves_.empty()) {
    return InvalidArgument(layout.type_name() + ": field '" + std::string(path) +
                           "' has no value a fault can change");
  }
  return sel;
}

void FieldSelector::WalkAll(char* base, const FieldNode& node,
                            const std::function<void(void*, const FieldNode&)>& fn) const {
  switch (node.kind) {
    case FieldKind::kStruct:
      for (const auto& m : node.members) WalkAll(base + m.offset, m, fn);
      break;
    case FieldKind::kArray:
      for (std::uint32_t i = 0; i < node.length; ++i) {
        WalkAll(base + std::size_t{i} * node.elem().size, node.elem(), fn);
      }
      break;
    case FieldKind::kSequence: {
      auto* s = reinterpret_cast<dds_sequence_t*>(base);
      if (s->_buffer == nullptr) break;
      for (std::uint32_t i = 0; i < s->_length; ++i) {
        WalkAll(reinterpret_cast<char*>(s->_buffer) + std::size_t{i} * node.elem().size, node.elem(), fn);
      }
      break;
    }
    case FieldKind::kUnion:
    case FieldKind::kExternal:
      break;
    default:
      fn(base, node);
  }
}

// `base` is the storage of the node entered by steps_[step - 1] (the root for step 0).
void FieldSelector::Walk(char* base, const FieldNode& node, std::size_t step,
                         const std::function<void(void*, const FieldNode&)>& fn) const {
  if (step == steps_.size()) {
    WalkAll(base, node, fn);
    return;
  }
  const Step& s = steps_[step];
  if (s.op == Step::Op::kMember) {
    Walk(base + s.node->offset, *s.node, step + 1, fn);
    return;
  }
  // s.node is the collection at `base`.
  const FieldNode& elem = s.node->elem();
  char* data = base;
  std::uint32_t count = s.node->length;
  if (s.node->kind == FieldKind::kSequence) {
    auto* seq = reinterpret_cast<dds_sequence_t*>(base);
    data = reinterpret_cast<char*>(seq->_buffer);
    count = data == nullptr ? 0 : seq->_length;
  }
  if (s.op == Step::Op::kIndex) {
    if (s.index < count) Walk(data + std::size_t{s.index} * elem.size, elem, step + 1, fn);
    return;
  }
  for (std::uint32_t i = 0; i < count; ++i) Walk(data + std::size_t{i} * elem.size, elem, step + 1, fn);
}

void FieldSelector::ForEachLeaf(void* sample,
                                const std::function<void(void*, const FieldNode&)>& fn) const {
  Walk(static_cast<char*>(sample), *root_, 0, fn);
}

}  // namespace rover::dds
