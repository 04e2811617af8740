#pragma once
/// @file
/// Just enough CDR to read what the recorder and replay need from a serialised sample without
/// its type: the `rover::Header` every topic sample starts with (stamp, frame, sequence), the
/// time of a sim/clock sample, and writing a sim/clock sample for replays of recordings that
/// have none.
///
/// A serialised sample is the 4-byte encapsulation header (identifier, big-endian, then 2 option
/// bytes) and the payload. This stack's types are @final, so Cyclone writes plain CDR: XCDR1
/// (CDR_BE 0x0000, CDR_LE 0x0001: primitives aligned to their size) or XCDR2 (CDR2_BE 0x0006,
/// CDR2_LE 0x0007: at most 4-byte alignment). Alignment counts from the first payload byte.
/// Strings: uint32 length including the terminating NUL, then the bytes.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::recording {

using ByteSpan = std::span<const std::uint8_t>;

/// Reads primitives from one serialised sample in order.
class CdrReader {
 public:
  /// Checks the encapsulation header; InvalidArgument for a sample shorter than 4 bytes or an
  /// encapsulation other than the four above ("encapsulation 0x0003 (not plain CDR)").
  static Result<CdrReader> Open(ByteSpan sample);

  Result<std::int64_t> Int64(const char* field);
  Result<std::uint32_t> Uint32(const char* field);
  Result<std::uint16_t> Uint16(const char* field);
  Result<double> Double(const char* field);
  Result<bool> Bool(const char* field);
  /// A string of at most `bound` characters (0 = unbounded), NUL terminated.
  Result<std::string> String(const char* field, std::uint32_t bound = 0);
  /// A sequence<octet>: its uint32 length, then the bytes (a view into the sample).
  Result<ByteSpan> Octets(const char* field);

  bool little_endian() const { return little_; }
  int xcdr_version() const { return xcdr_; }

 private:
  CdrReader(ByteSpan payload, bool little, int xcdr) : p_(payload), little_(little), xcdr_(xcdr) {}
  Result<ByteSpan> Take(std::size_t size, std::size_t align, const char* field);

  ByteSpan p_;
  std::size_t at_ = 0;
  bool little_ = true;
  int xcdr_ = 1;
};

/// Writes an XCDR1 little-endian sample (the encapsulation header first).
class CdrWriter {
 public:
  CdrWriter();
  void Int64(std::int64_t v);
  void Uint32(std::uint32_t v);
  void Double(double v);
  void Bool(bool v);
  void String(const std::string& v);
  /// The sample: header, payload, padded to a multiple of 4 bytes (the option bytes say how
  /// many were added, as the DDS-XTypes specification asks).
  std::vector<std::uint8_t> Finish() &&;

 private:
  void Align(std::size_t n);
  void Raw(const void* data, std::size_t n);
  std::vector<std::uint8_t> out_;
};

/// The header every sample of this stack starts with (idl/rover_common.idl).
struct SampleHeader {
  std::int64_t stamp_ns = 0;  ///< [ns] run clock
  std::string frame_id;
  std::uint32_t seq = 0;
};

/// Reads the leading rover::Header of a serialised sample.
Result<SampleHeader> ReadSampleHeader(ByteSpan sample);

/// A sim/clock sample (rover::sim::Clock).
struct ClockSample {
  SampleHeader header;
  std::int64_t sim_time_ns = 0;
  double real_time_factor = 0;
  bool paused = false;
};

Result<ClockSample> ReadClockSample(ByteSpan sample);
/// Serialises a sim/clock sample (XCDR1, little-endian), as Cyclone would.
std::vector<std::uint8_t> WriteClockSample(const ClockSample& clock);

}  // namespace rover::recording
