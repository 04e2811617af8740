#include "rover/recording/cdr.hpp"

#include <bit>
#include <cstdio>
#include <cstring>

namespace rover::recording {
namespace {

constexpr std::size_t kEncapsulationBytes = 4;
constexpr std::uint32_t kFrameIdBound = 31;  // string<31> in rover::Header

template <class T>
T Load(const std::uint8_t* p, bool little) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if (little != (std::endian::native == std::endian::little)) {
    std::uint8_t b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    for (std::size_t i = 0; i < sizeof v / 2; ++i) std::swap(b[i], b[sizeof v - 1 - i]);
    std::memcpy(&v, b, sizeof v);
  }
  return v;
}

}  // namespace

Result<CdrReader> CdrReader::Open(ByteSpan sample) {
  if (sample.size() < kEncapsulationBytes) {
    return InvalidArgument("serialised sample of " + std::to_string(sample.size()) +
                           " bytes is shorter than its 4-byte encapsulation header");
  }
  const unsigned id = (unsigned{sample[0]} << 8) | sample[1];
  bool little = false;
  int xcdr = 1;
  switch (id) {
    case 0x0000: little = false; xcdr = 1; break;
    case 0x0001: little = true; xcdr = 1; break;
    case 0x0006: little = false; xcdr = 2; break;
    case 0x0007: little = true; xcdr = 2; break;
    default: {
      char b[8];
      std::snprintf(b, sizeof b, "0x%04x", id);
      return InvalidArgument(std::string("serialised sample has encapsulation ") + b +
                             " (not plain CDR: the stack's types are @final)");
    }
  }
  return CdrReader(sample.subspan(kEncapsulationBytes), little, xcdr);
}

Result<ByteSpan> CdrReader::Take(std::size_t size, std::size_t align, const char* field) {
  if (xcdr_ == 2 && align > 4) align = 4;
  const std::size_t start = align > 1 ? (at_ + align - 1) / align * align : at_;
  if (start > p_.size() || p_.size() - start < size) {
    return InvalidArgument("serialised sample of " + std::to_string(p_.size() + 4) +
                           " bytes ends before its field '" + field + "' (at payload offset " +
                           std::to_string(start) + ")");
  }
  at_ = start + size;
  return p_.subspan(start, size);
}

Result<std::int64_t> CdrReader::Int64(const char* field) {
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(8, 8, field));
  return Load<std::int64_t>(b.data(), little_);
}

Result<std::uint32_t> CdrReader::Uint32(const char* field) {
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(4, 4, field));
  return Load<std::uint32_t>(b.data(), little_);
}

Result<std::uint16_t> CdrReader::Uint16(const char* field) {
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(2, 2, field));
  return Load<std::uint16_t>(b.data(), little_);
}

Result<ByteSpan> CdrReader::Octets(const char* field) {
  ROVER_ASSIGN_OR_RETURN(const std::uint32_t length, Uint32(field));
  return Take(length, 1, field);
}

Result<double> CdrReader::Double(const char* field) {
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(8, 8, field));
  return Load<double>(b.data(), little_);
}

Result<bool> CdrReader::Bool(const char* field) {
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(1, 1, field));
  if (b[0] > 1) {
    return InvalidArgument(std::string("field '") + field + "': boolean byte " +
                           std::to_string(b[0]) + " is neither 0 nor 1");
  }
  return b[0] == 1;
}

Result<std::string> CdrReader::String(const char* field, std::uint32_t bound) {
  ROVER_ASSIGN_OR_RETURN(const std::uint32_t length, Uint32(field));
  if (length == 0) {
    return InvalidArgument(std::string("field '") + field +
                           "': string length 0 (CDR strings count their NUL)");
  }
  if (bound > 0 && length - 1 > bound) {
    return InvalidArgument(std::string("field '") + field + "': string of " +
                           std::to_string(length - 1) + " characters exceeds its bound of " +
                           std::to_string(bound));
  }
  ROVER_ASSIGN_OR_RETURN(ByteSpan b, Take(length, 1, field));
  if (b[length - 1] != 0) {
    return InvalidArgument(std::string("field '") + field + "': string is not NUL-terminated");
  }
  return std::string(reinterpret_cast<const char*>(b.data()), length - 1);
}

CdrWriter::CdrWriter() : out_{0x00, 0x01, 0x00, 0x00} {}

void CdrWriter::Align(std::size_t n) {
  while ((out_.size() - kEncapsulationBytes) % n != 0) out_.push_back(0);
}

void CdrWriter::Raw(const void* data, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(data);
  out_.insert(out_.end(), b, b + n);
}

// This writer is little-endian only; the hosts this stack runs on are too.
static_assert(std::endian::native == std::endian::little, "CdrWriter assumes a little-endian host");

void CdrWriter::Int64(std::int64_t v) { Align(8); Raw(&v, 8); }
void CdrWriter::Uint32(std::uint32_t v) { Align(4); Raw(&v, 4); }
void CdrWriter::Double(double v) { Align(8); Raw(&v, 8); }
void CdrWriter::Bool(bool v) { out_.push_back(v ? 1 : 0); }
void CdrWriter::String(const std::string& v) {
  Uint32(static_cast<std::uint32_t>(v.size() + 1));
  Raw(v.data(), v.size());
  out_.push_back(0);
}

std::vector<std::uint8_t> CdrWriter::Finish() && {
  const std::size_t padding = (4 - out_.size() % 4) % 4;
  out_.insert(out_.end(), padding, 0);
  out_[3] = static_cast<std::uint8_t>(padding);
  return std::move(out_);
}

namespace {
Result<SampleHeader> ReadHeader(CdrReader& r) {
  SampleHeader h;
  ROVER_ASSIGN_OR_RETURN(h.stamp_ns, r.Int64("header.stamp_ns"));
  ROVER_ASSIGN_OR_RETURN(h.frame_id, r.String("header.frame_id", kFrameIdBound));
  ROVER_ASSIGN_OR_RETURN(h.seq, r.Uint32("header.seq"));
  return h;
}
}  // namespace

Result<SampleHeader> ReadSampleHeader(ByteSpan sample) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(sample));
  return ReadHeader(r);
}

Result<ClockSample> ReadClockSample(ByteSpan sample) {
  ROVER_ASSIGN_OR_RETURN(CdrReader r, CdrReader::Open(sample));
  ClockSample c;
  ROVER_ASSIGN_OR_RETURN(c.header, ReadHeader(r));
  ROVER_ASSIGN_OR_RETURN(c.sim_time_ns, r.Int64("sim_time_ns"));
  ROVER_ASSIGN_OR_RETURN(c.real_time_factor, r.Double("real_time_factor"));
  ROVER_ASSIGN_OR_RETURN(c.paused, r.Bool("paused"));
  return c;
}

std::vector<std::uint8_t> WriteClockSample(const ClockSample& clock) {
  CdrWriter w;
  w.Int64(clock.header.stamp_ns);
  w.String(clock.header.frame_id.substr(0, kFrameIdBound));
  w.Uint32(clock.header.seq);
  w.Int64(clock.sim_time_ns);
  w.Double(clock.real_time_factor);
  w.Bool(clock.paused);
  w.Uint32(0);  // written: an empty frontier (a replay is not in strict lock-step)
  return std::move(w).Finish();
}

}  // namespace rover::recording
