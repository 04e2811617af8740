#pragma once
// Shared helpers of the rover_mcap tests: a deterministic sample recording, reading everything
// back, and a builder of hand-made files (records laid out by the test itself).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "rover/mcap/crc32.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/mcap/records.hpp"
#include "rover/mcap/writer.hpp"

namespace rover::mcap::testing {

inline std::string MakeTempDir(const std::string& prefix) {
  std::string templ = ::testing::TempDir() + "/" + prefix + "-XXXXXX";
  const char* dir = mkdtemp(templ.data());
  EXPECT_NE(dir, nullptr);
  return templ;
}

/// One message as written or read, owning its data.
struct Msg {
  std::string topic;
  std::uint32_t sequence = 0;
  Timestamp log_time = 0;
  Timestamp publish_time = 0;
  Bytes data;
  bool operator==(const Msg&) const = default;
};

inline std::ostream& operator<<(std::ostream& os, const Msg& m) {
  return os << m.topic << "#" << m.sequence << "@" << m.log_time << "(" << m.data.size() << "B)";
}

/// The IDL of a sample type, as the recorder will store it.
inline std::string SampleIdl(const std::string& module, const std::string& type) {
  return "module rover {\n  module " + module + " {\n    struct " + type +
         " {\n      double x;\n      sequence<octet> payload;\n    };\n  };\n};\n";
}

struct SampleSpec {
  int messages = 300;
  /// Log times jitter by up to this much around i * 1 ms, so that chunks overlap in time.
  Timestamp jitter_ns = 0;
  std::size_t max_data_bytes = 200;
  bool compressible = true;  ///< data from a small alphabet (else uniform random bytes)
  std::uint32_t seed = 7;
  bool metadata = true;
  bool attachment = true;
};

struct Sample {
  std::vector<Msg> written;  ///< in write order
  std::vector<Channel> channels;
  std::vector<Schema> schemas;
};

/// Writes a recording on three topics (two schemas, one topic without schema) through `w`.
inline Sample WriteSample(Writer& w, const SampleSpec& spec) {
  Sample s;
  std::mt19937 rng(spec.seed);
  const std::string pose_idl = SampleIdl("dl", "PoseEstimate");
  const std::string range_idl = SampleIdl("dl", "RangeImage");
  auto pose = w.AddSchema("rover::dl::PoseEstimate", kSchemaEncodingOmgIdl, AsBytes(pose_idl));
  auto range = w.AddSchema("rover::dl::RangeImage", kSchemaEncodingOmgIdl, AsBytes(range_idl));
  EXPECT_TRUE(pose.ok() && range.ok());
  const std::vector<std::tuple<std::string, std::uint16_t, StringMap>> topics = {
      {"dl/pose", pose.value(), {{"qos", "state"}}},
      {"dl/range_image", range.value(), {}},
      {"sys/event", 0, {{"note", "no schema"}}}};
  std::vector<std::uint16_t> ids;
  for (const auto& [topic, schema, meta] : topics) {
    auto id = w.AddChannel(topic, kMessageEncodingCdr, schema, meta);
    EXPECT_TRUE(id.ok()) << id.status().ToString();
    ids.push_back(id.value());
  }
  if (spec.metadata) {
    EXPECT_TRUE(w.WriteMetadata({"run", {{"seed", "7"}, {"scenario", "drive_flat"}}}).ok());
  }
  std::vector<std::uint32_t> seq(ids.size(), 0);
  for (int i = 0; i < spec.messages; ++i) {
    const std::size_t c = rng() % ids.size();
    Msg m;
    m.topic = std::get<0>(topics[c]);
    m.sequence = seq[c]++;
    const std::int64_t base = 1'000'000'000 + static_cast<std::int64_t>(i) * 1'000'000;
    const std::int64_t jitter = spec.jitter_ns == 0
                                    ? 0
                                    : static_cast<std::int64_t>(rng() % (2 * spec.jitter_ns + 1)) -
                                          static_cast<std::int64_t>(spec.jitter_ns);
    m.log_time = static_cast<Timestamp>(base + jitter);
    m.publish_time = m.log_time - 1000;
    m.data.resize(rng() % (spec.max_data_bytes + 1));
    for (auto& b : m.data) {
      b = spec.compressible ? static_cast<std::uint8_t>('a' + rng() % 4)
                            : static_cast<std::uint8_t>(rng());
    }
    EXPECT_TRUE(w.WriteMessage({ids[c], m.sequence, m.log_time, m.publish_time, m.data}).ok());
    s.written.push_back(std::move(m));
    if (spec.attachment && i == spec.messages / 2) {
      Attachment a{2'000'000'000, 1'500'000'000, "calibration.yaml", "application/x-yaml",
                   Bytes{'k', ':', ' ', '1', '\n'}};
      EXPECT_TRUE(w.WriteAttachment(a).ok());
    }
  }
  return s;
}

/// Writes a sample recording into memory.
inline Bytes SampleFile(const WriterOptions& options, const SampleSpec& spec,
                        Sample* out = nullptr) {
  Bytes bytes;
  auto w = Writer::Create(std::make_unique<BufferSink>(&bytes), options);
  EXPECT_TRUE(w.ok()) << w.status().ToString();
  Sample s = WriteSample(**w, spec);
  const Status closed = (*w)->Close();
  EXPECT_TRUE(closed.ok()) << closed.ToString();
  if (out != nullptr) *out = std::move(s);
  return bytes;
}

/// The expected read order: a stable sort of the written messages by log time.
inline std::vector<Msg> InLogTimeOrder(std::vector<Msg> v) {
  std::stable_sort(v.begin(), v.end(),
                   [](const Msg& a, const Msg& b) { return a.log_time < b.log_time; });
  return v;
}

/// Every message a reader yields for `filter`, or the error.
inline Result<std::vector<Msg>> ReadAll(const Reader& r, const MessageFilter& filter = {}) {
  std::vector<Msg> out;
  Status s = r.ForEachMessage(filter, [&](const MessageEvent& e) {
    out.push_back({e.channel->topic, e.message.sequence, e.message.log_time, e.message.publish_time,
                   Bytes(e.message.data.begin(), e.message.data.end())});
    return Status::Ok();
  });
  if (!s.ok()) return s;
  return out;
}

inline Result<std::unique_ptr<Reader>> OpenBytes(Bytes bytes,
                                                 Verification v = Verification::kDataSection,
                                                 std::string name = "test.mcap") {
  ReaderOptions o;
  o.verification = v;
  return Reader::Open(std::make_unique<BufferSource>(std::move(bytes), std::move(name)), o);
}

/// Lays out a file record by record: magic, Header, the data records the test appends, DataEnd
/// with the data CRC, an optional summary (records the test appends), Footer, magic.
class FileBuilder {
 public:
  explicit FileBuilder(Header header = {"", "test"}) {
    bytes_.assign(kMagic.begin(), kMagic.end());
    AppendRecord(bytes_, header);
  }
  /// The offset the next record will have.
  std::uint64_t offset() const { return bytes_.size(); }
  template <class R>
  std::uint64_t Data(const R& record) {
    const std::uint64_t at = bytes_.size();
    AppendRecord(bytes_, record);
    return at;
  }
  void Raw(const Bytes& b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
  /// Ends the data section; records appended after this are the summary.
  void EndData(bool with_crc = true) {
    AppendRecord(bytes_, DataEnd{with_crc ? ComputeCrc32(bytes_) : 0u});
    summary_start_ = bytes_.size();
  }
  /// Footer and magic; `summary` false writes a footer of zeros.
  Bytes Finish(bool summary, bool with_crc = true) {
    Footer f;
    if (summary) {
      f.summary_start = summary_start_;
      f.summary_offset_start = 0;
      Bytes prefix;
      AppendRecord(prefix, f);
      if (with_crc) {
        Crc32 crc;
        crc.Update(ByteSpan(bytes_).subspan(summary_start_));
        crc.Update(ByteSpan(prefix).first(kFooterRecordBytes - 4));
        f.summary_crc = crc.Value();
      }
    }
    AppendRecord(bytes_, f);
    bytes_.insert(bytes_.end(), kMagic.begin(), kMagic.end());
    return bytes_;
  }

 private:
  Bytes bytes_;
  std::uint64_t summary_start_ = 0;
};

/// A whole uncompressed Chunk record holding `records` (already laid out).
inline Bytes ChunkOf(const Bytes& records, Timestamp start, Timestamp end) {
  Bytes out;
  AppendRecord(out, ChunkView{start, end, records.size(), ComputeCrc32(records), "", records});
  return out;
}

}  // namespace rover::mcap::testing
