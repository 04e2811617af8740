#pragma once
/// @file
/// Readers and writers of serialised samples, for code that moves samples without knowing their
/// type at compile time: the recorder takes each sample as the bytes Cyclone received (the
/// 4-byte CDR encapsulation header and the payload, exactly what a typed reader would have
/// deserialised), and replay publishes recorded bytes as they are.
///
/// Both create the topic with the type's idlc descriptor (dds::DescriptorForType in
/// rover/runtime/topic_catalog.hpp finds it by C type name), so they match typed endpoints of the same topic on type name and type
/// information alike. The writer hands Cyclone the bytes through dds_writecdr: Cyclone checks
/// them against the type as it would a sample from the network (a malformed sample is refused
/// with an error, nothing is published). Neither passes through the fault seam: they carry
/// recordings, not the stack's own traffic.

#include <dds/dds.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/qos.hpp"

namespace rover::dds {

struct RawReaderOptions {
  /// Keep every sample until taken (history keep-all), whatever the profile's history depth: a
  /// recorder must not lose samples while it writes. Reliability and durability stay the
  /// profile's, so the reader matches the topic's writers and a latched topic's last sample
  /// reaches it.
  bool keep_all = true;
};

class RawReader {
 public:
  RawReader() = default;
  /// A reader of `topic` (type `descriptor`) with `profile`'s QoS (see RawReaderOptions).
  static Result<RawReader> Create(const Participant& p, const std::string& topic,
                                  const dds_topic_descriptor_t* descriptor, QosProfile profile,
                                  const RawReaderOptions& options = {});

  /// Calls `fn(bytes, info)` for every sample with valid data that has arrived, oldest first;
  /// `bytes` (encapsulation header included) is valid only during the call. Returns the number
  /// delivered.
  std::size_t TakeEach(
      const std::function<void(std::span<const std::uint8_t>, const dds_sample_info_t&)>& fn);

  /// Samples the transport reports lost since the reader was created (DDS SAMPLE_LOST, and
  /// SAMPLE_REJECTED for lack of resources).
  std::uint64_t LostSamples() const;
  int MatchedWriters() const;
  const std::string& topic_name() const { return name_; }
  dds_entity_t handle() const { return reader_.handle(); }
  bool valid() const { return reader_.valid(); }

 private:
  Entity reader_;
  Entity topic_;
  std::string name_;
  std::vector<std::uint8_t> scratch_;
};

class RawWriter {
 public:
  RawWriter() = default;
  static Result<RawWriter> Create(const Participant& p, const std::string& topic,
                                  const dds_topic_descriptor_t* descriptor, QosProfile profile);

  /// Publishes one serialised sample (encapsulation header included). InvalidArgument when
  /// Cyclone cannot read it as the topic's type; Unavailable when the write fails.
  Status Write(std::span<const std::uint8_t> sample);

  int MatchedReaders() const;
  const std::string& topic_name() const { return name_; }
  dds_entity_t handle() const { return writer_.handle(); }
  bool valid() const { return writer_.valid(); }

 private:
  Entity writer_;
  Entity topic_;
  std::string name_;
};

}  // namespace rover::dds
