#include "rover/runtime/type_object.hpp"

#include <string>

namespace rover::dds {
namespace {

// XTypes 1.3 constants (Annex B).
constexpr std::uint8_t kEkMinimal = 0xF1;
constexpr std::uint8_t kEkComplete = 0xF2;
constexpr std::uint8_t kTkAlias = 0x30;
constexpr std::uint8_t kTkEnum = 0x40;
constexpr std::uint8_t kTkStructure = 0x51;
constexpr std::uint8_t kTkUnion = 0x52;
constexpr std::uint8_t kTiString8Small = 0x70;
constexpr std::uint8_t kTiString8Large = 0x71;
constexpr std::uint8_t kTiString16Small = 0x72;
constexpr std::uint8_t kTiString16Large = 0x73;
constexpr std::uint8_t kTiSeqSmall = 0x80;
constexpr std::uint8_t kTiSeqLarge = 0x81;
constexpr std::uint8_t kTiArraySmall = 0x90;
constexpr std::uint8_t kTiArrayLarge = 0x91;
constexpr std::uint8_t kTiMapSmall = 0xA0;
constexpr std::uint8_t kTiMapLarge = 0xA1;
constexpr std::uint8_t kTiScc = 0xB0;
// Primitive type kinds occupy 0x00..0x1F (TK_NONE ... TK_CHAR16, TK_INT8/UINT8 of 1.3).
constexpr std::uint8_t kLastPrimitive = 0x1F;

// Reads little-endian XCDR2. Alignment is relative to the start of the buffer and capped at 4
// (XCDR2 aligns 8-byte values to 4). Every read checks bounds; the first failure sticks.
class Cdr {
 public:
  Cdr(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  std::size_t pos() const { return pos_; }

  void Align(std::size_t n) {
    if (n > 4) n = 4;
    const std::size_t r = pos_ % n;
    if (r != 0) Skip(n - r);
  }
  void Skip(std::size_t n) {
    if (!ok()) return;
    if (n > size_ - pos_) return Fail("truncated");
    pos_ += n;
  }
  void Seek(std::size_t to) {
    if (!ok()) return;
    if (to < pos_ || to > size_) return Fail("bad length field");
    pos_ = to;
  }
  std::uint8_t U8() {
    if (!ok()) return 0;
    if (pos_ >= size_) {
      Fail("truncated");
      return 0;
    }
    return data_[pos_++];
  }
  std::uint16_t U16() {
    Align(2);
    const std::uint16_t lo = U8();
    const std::uint16_t hi = U8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  std::uint32_t U32() {
    Align(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(U8()) << (8 * i);
    return v;
  }
  /// A DHEADER: returns the position where the delimited object ends.
  std::size_t Delimited() {
    const std::uint32_t n = U32();
    if (ok() && n > size_ - pos_) Fail("DHEADER runs past the end");
    return ok() ? pos_ + n : pos_;
  }
  std::string String() {
    const std::uint32_t n = U32();
    if (!ok()) return {};
    if (n == 0 || n > size_ - pos_) {
      Fail("bad string length");
      return {};
    }
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n - 1);  // drop the NUL
    pos_ += n;
    return s;
  }
  void Fail(const std::string& what) {
    if (ok()) error_ = what + " at byte " + std::to_string(pos_);
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::string error_;
};

XTypeId ReadTypeId(Cdr& in, int depth);

// PlainCollectionHeader: octet equiv_kind, uint16 element_flags.
void SkipCollectionHeader(Cdr& in) {
  (void)in.U8();
  (void)in.U16();
}

std::shared_ptr<const XTypeId> ReadElement(Cdr& in, int depth) {
  return std::make_shared<const XTypeId>(ReadTypeId(in, depth + 1));
}

XTypeId ReadTypeId(Cdr& in, int depth) {
  XTypeId id;
  if (depth > 32) {
    in.Fail("type identifiers nested too deeply");
    return id;
  }
  id.discriminator = in.U8();
  const std::uint8_t d = id.discriminator;
  if (d <= kLastPrimitive) {
    id.kind = XTypeId::Kind::kPrimitive;
  } else if (d == kTiString8Small || d == kTiString16Small) {
    id.kind = XTypeId::Kind::kString;
    id.bound = in.U8();
  } else if (d == kTiString8Large || d == kTiString16Large) {
    id.kind = XTypeId::Kind::kString;
    id.bound = in.U32();
  } else if (d == kTiSeqSmall || d == kTiSeqLarge) {
    id.kind = XTypeId::Kind::kSequence;
    SkipCollectionHeader(in);
    id.bound = d == kTiSeqSmall ? in.U8() : in.U32();
    id.element = ReadElement(in, depth);
  } else if (d == kTiArraySmall || d == kTiArrayLarge) {
    id.kind = XTypeId::Kind::kArray;
    SkipCollectionHeader(in);
    const std::uint32_t n = in.U32();
    for (std::uint32_t i = 0; i < n && in.ok(); ++i) {
      id.dims.push_back(d == kTiArraySmall ? in.U8() : in.U32());
    }
    id.element = ReadElement(in, depth);
  } else if (d == kTiMapSmall || d == kTiMapLarge) {
    id.kind = XTypeId::Kind::kMap;
    SkipCollectionHeader(in);
    id.bound = d == kTiMapSmall ? in.U8() : in.U32();
    id.element = ReadElement(in, depth);
    (void)in.U16();               // key flags
    (void)ReadTypeId(in, depth + 1);  // key type
  } else if (d == kTiScc) {
    // StronglyConnectedComponentId is appendable: skip it whole. Recursive types only.
    in.Seek(in.Delimited());
  } else if (d == kEkComplete || d == kEkMinimal) {
    id.kind = XTypeId::Kind::kHash;
    for (auto& b : id.hash) b = in.U8();
  } else {
    in.Fail("unknown TypeIdentifier discriminator " + std::to_string(d));
  }
  return id;
}

// @optional members of final and appendable structs carry an is-present octet; an optional
// appendable struct or a sequence of appendable structs then starts with a DHEADER.
void SkipOptionalDelimited(Cdr& in) {
  if (in.U8() != 0) in.Seek(in.Delimited());
}

// CompleteTypeDetail: @optional ann_builtin, @optional ann_custom, QualifiedTypeName.
std::string ReadTypeDetail(Cdr& in) {
  SkipOptionalDelimited(in);
  SkipOptionalDelimited(in);
  return in.String();
}

void ReadStruct(Cdr& in, XType& t) {
  t.kind = XType::Kind::kStruct;
  (void)in.U16();  // struct flags
  const std::size_t header_end = in.Delimited();
  t.base = ReadTypeId(in, 0);
  t.name = ReadTypeDetail(in);
  in.Seek(header_end);
  const std::size_t seq_end = in.Delimited();
  const std::uint32_t n = in.U32();
  for (std::uint32_t i = 0; i < n && in.ok(); ++i) {
    const std::size_t member_end = in.Delimited();
    XMember m;
    m.id = in.U32();
    (void)in.U16();  // member flags
    m.type = ReadTypeId(in, 0);
    m.name = in.String();  // CompleteMemberDetail.name; annotations follow, skipped
    in.Seek(member_end);
    t.members.push_back(std::move(m));
  }
  in.Seek(seq_end);
}

void ReadAlias(Cdr& in, XType& t) {
  t.kind = XType::Kind::kAlias;
  (void)in.U16();  // alias flags
  const std::size_t header_end = in.Delimited();
  t.name = ReadTypeDetail(in);
  in.Seek(header_end);
  const std::size_t body_end = in.Delimited();
  (void)in.U16();  // related flags
  t.aliased = ReadTypeId(in, 0);
  in.Seek(body_end);
}

void ReadEnum(Cdr& in, XType& t) {
  t.kind = XType::Kind::kEnum;
  (void)in.U16();  // enum flags
  const std::size_t header_end = in.Delimited();
  (void)in.U16();  // bit bound
  t.name = ReadTypeDetail(in);
  in.Seek(header_end);
  const std::size_t seq_end = in.Delimited();
  const std::uint32_t n = in.U32();
  for (std::uint32_t i = 0; i < n && in.ok(); ++i) {
    const std::size_t literal_end = in.Delimited();
    const std::size_t common_end = in.Delimited();  // CommonEnumeratedLiteral is appendable
    XMember m;
    m.value = static_cast<std::int32_t>(in.U32());
    in.Seek(common_end);
    m.name = in.String();
    in.Seek(literal_end);
    t.members.push_back(std::move(m));
  }
  in.Seek(seq_end);
}

// One TypeIdentifierTypeObjectPair of the complete sequence.
void ReadPair(Cdr& in, std::map<XTypeId::Hash, XType>& out) {
  const XTypeId id = ReadTypeId(in, 0);
  const std::size_t object_end = in.Delimited();
  const std::uint8_t ek = in.U8();
  if (!in.ok()) return;
  if (ek != kEkComplete || id.kind != XTypeId::Kind::kHash) {
    in.Seek(object_end);
    return;
  }
  XType t;
  t.type_kind = in.U8();
  switch (t.type_kind) {
    case kTkStructure: ReadStruct(in, t); break;
    case kTkAlias: ReadAlias(in, t); break;
    case kTkEnum: ReadEnum(in, t); break;
    case kTkUnion: t.kind = XType::Kind::kUnion; break;
    default: break;
  }
  in.Seek(object_end);
  if (in.ok()) out[id.hash] = std::move(t);
}

void SkipDelimitedSequence(Cdr& in) { in.Seek(in.Delimited()); }

}  // namespace

Result<XTypeTable> XTypeTable::Decode(const std::uint8_t* data, std::size_t size) {
  if (data == nullptr || size == 0) return InvalidArgument("the descriptor has no XTypes type mapping");
  Cdr in(data, size);
  XTypeTable table;
  SkipDelimitedSequence(in);  // minimal pairs: no names
  const std::size_t end = in.Delimited();
  const std::uint32_t n = in.U32();
  for (std::uint32_t i = 0; i < n && in.ok(); ++i) ReadPair(in, table.types_);
  in.Seek(end);
  if (!in.ok()) return InvalidArgument("XTypes type mapping: " + in.error());
  return table;
}

const XType* XTypeTable::Find(const XTypeId::Hash& hash) const {
  auto it = types_.find(hash);
  return it == types_.end() ? nullptr : &it->second;
}

const XType* XTypeTable::FindByName(const std::string& name) const {
  for (const auto& [hash, t] : types_) {
    if (t.name == name && t.kind != XType::Kind::kAlias) return &t;
  }
  return nullptr;
}

const XTypeId& XTypeTable::Unalias(const XTypeId& id) const {
  const XTypeId* cur = &id;
  for (int i = 0; i < 16 && cur->kind == XTypeId::Kind::kHash; ++i) {
    const XType* t = Find(cur->hash);
    if (t == nullptr || t->kind != XType::Kind::kAlias) break;
    cur = &t->aliased;
  }
  return *cur;
}

}  // namespace rover::dds
