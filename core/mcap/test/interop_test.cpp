// Interop with the reference implementation: @mcap/core (TypeScript, on Node.js) reads every
// record of files this library writes, and this library reads files @mcap/core writes.
// scripts/setup.sh installs the tool (tests/tools/mcap-node, npm ci); without Node.js or the
// tool the tests skip, saying so.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mcap_test_util.hpp"
#include "rover/base/process.hpp"
#include "rover/mcap/crc32.hpp"
#include "rover/mcap/info.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/mcap/writer.hpp"

namespace rover::mcap {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kToolDir = std::string(ROVER_SOURCE_DIR) + "/tests/tools/mcap-node";

/// Why the reference tool cannot run here, or "" when it can.
std::string MissingTool() {
  const char* path = std::getenv("PATH");
  if (FindInPath("node", path != nullptr ? path : "").empty()) {
    return "Node.js (node) is not in PATH; scripts/setup.sh installs it";
  }
  if (!fs::exists(kToolDir + "/node_modules/@mcap/core/package.json")) {
    return "@mcap/core is not installed in " + kToolDir +
           "/node_modules; run scripts/setup.sh (npm ci there)";
  }
  return "";
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `node <script> <args>` in the tool folder; returns its stdout as JSON.
json RunNode(const std::string& dir, const std::string& script, std::vector<std::string> args) {
  static int run = 0;
  const std::string out = dir + "/node-" + std::to_string(++run) + ".out";
  const std::string err = dir + "/node-" + std::to_string(run) + ".err";
  SpawnOptions o;
  o.argv = {"node", kToolDir + "/" + script};
  o.argv.insert(o.argv.end(), args.begin(), args.end());
  o.stdout_path = out;
  o.stderr_path = err;
  o.working_dir = kToolDir;
  auto p = Process::Spawn(o);
  EXPECT_TRUE(p.ok()) << p.status().ToString();
  if (!p.ok()) return json();
  const auto exit = p->WaitFor(Seconds(120));
  if (!exit) {
    p->Terminate(Seconds(2));
    ADD_FAILURE() << script << " did not finish";
    return json();
  }
  EXPECT_TRUE(exit->success()) << script << ": " << exit->ToString() << "\n" << Slurp(err);
  if (!exit->success()) return json();
  return json::parse(Slurp(out));
}

struct OurLayout {
  const char* name;
  Compression compression;
  bool chunked;
  bool summary;
};

// ---- our files, the reference reader ------------------------------------------------------------

TEST(Interop, TheReferenceReaderReadsEveryRecordOfOurFiles) {
  if (const std::string why = MissingTool(); !why.empty()) GTEST_SKIP() << why;
  const std::string dir = testing::MakeTempDir("mcap-interop");
  const std::vector<OurLayout> layouts = {{"zstd", Compression::kZstd, true, true},
                                          {"lz4", Compression::kLz4, true, true},
                                          {"none", Compression::kNone, true, true},
                                          {"unchunked", Compression::kNone, false, true},
                                          {"no-summary", Compression::kZstd, true, false}};
  for (const OurLayout& l : layouts) {
    SCOPED_TRACE(l.name);
    const std::string path = dir + "/ours-" + l.name + ".mcap";
    WriterOptions o;
    o.compression = l.compression;
    o.chunked = l.chunked;
    o.summary = l.summary;
    o.chunk_bytes = 2048;
    testing::SampleSpec spec;
    spec.jitter_ns = 3'000'000;  // overlapping chunks
    testing::Sample sample;
    {
      auto w = Writer::Create(path, o);
      ASSERT_TRUE(w.ok()) << w.status().ToString();
      sample = testing::WriteSample(**w, spec);
      ASSERT_TRUE((*w)->Close().ok());
    }
    std::set<Timestamp> times;
    for (const auto& m : sample.written) times.insert(m.log_time);
    ASSERT_EQ(times.size(), sample.written.size()) << "the comparison needs distinct log times";

    // What our reader sees, to compare with.
    auto ours = Reader::Open(path, {Verification::kFull});
    ASSERT_TRUE(ours.ok()) << ours.status().ToString();
    Crc32 ordered;
    std::uint32_t sum_of_crcs = 0;
    std::map<std::string, int> per_topic;
    ASSERT_TRUE((*ours)
                    ->ForEachMessage({},
                                     [&](const MessageEvent& e) {
                                       ordered.Update(e.message.data);
                                       sum_of_crcs += ComputeCrc32(e.message.data);
                                       ++per_topic[e.channel->topic];
                                       return Status::Ok();
                                     })
                    .ok());
    const std::size_t chunks = (*ours)->chunk_indexes().size();

    const json got = RunNode(dir, "read.mjs", {path});
    ASSERT_FALSE(got.is_null());
    const json& stream = got["stream"];
    EXPECT_TRUE(stream["done"].get<bool>());
    EXPECT_EQ(stream["messages"].get<int>(), 300);
    EXPECT_EQ(stream["sumOfDataCrcs"].get<std::uint32_t>(), sum_of_crcs);
    EXPECT_TRUE(stream["dataSectionCrcOk"].get<bool>());
    const json& records = stream["records"];
    EXPECT_EQ(records["Header"].get<int>(), 1);
    EXPECT_EQ(records["Footer"].get<int>(), 1);
    EXPECT_EQ(records["DataEnd"].get<int>(), 1);
    EXPECT_EQ(records["Message"].get<int>(), 300);
    EXPECT_EQ(records["Metadata"].get<int>(), 1);
    EXPECT_EQ(records["Attachment"].get<int>(), 1);
    EXPECT_EQ(records.value("Chunk", 0), static_cast<int>(chunks));
    EXPECT_EQ(records.value("MessageIndex", 0) > 0, l.chunked);
    const int copies = l.summary ? 2 : 1;  // the data section, and the summary's copy
    EXPECT_EQ(records["Schema"].get<int>(), 2 * copies);
    EXPECT_EQ(records["Channel"].get<int>(), 3 * copies);
    EXPECT_EQ(records.value("Statistics", 0), l.summary ? 1 : 0);
    std::cout << "[ interop ] ours-" << l.name << " -> @mcap/core stream reader: " << records.dump()
              << "\n";

    const json& indexed = got["indexed"];
    ASSERT_EQ(indexed["indexed"].get<bool>(), l.summary);
    if (!l.summary) continue;
    EXPECT_EQ(indexed["profile"], "");
    EXPECT_EQ(indexed["library"], "rover_mcap 1");
    EXPECT_TRUE(indexed["dataSectionCrcOk"].get<bool>());
    EXPECT_EQ(indexed["chunkIndexes"].get<std::size_t>(), chunks);
    if (l.chunked) {
      EXPECT_EQ(indexed["messages"].get<int>(), 300);
      EXPECT_TRUE(indexed["inOrder"].get<bool>());
      EXPECT_EQ(indexed["orderedDataCrc"].get<std::uint32_t>(), ordered.Value());
      for (const auto& [topic, n] : per_topic) {
        EXPECT_EQ(indexed["perTopic"].value(topic, -1), n) << topic;
      }
    } else {
      // Messages outside chunks are not indexed: the indexed reader yields none (as the
      // specification says), the stream reader above found all of them.
      EXPECT_EQ(indexed["messages"].get<int>(), 0);
    }
    EXPECT_EQ(indexed["statistics"]["messageCount"], "300");
    ASSERT_EQ(indexed["schemas"].size(), 2u);
    for (const json& s : indexed["schemas"]) {
      const Schema& mine = (*ours)->schemas().at(s["id"].get<std::uint16_t>());
      EXPECT_EQ(s["name"], mine.name);
      EXPECT_EQ(s["encoding"], "omgidl");
      EXPECT_EQ(s["dataCrc"].get<std::uint32_t>(), ComputeCrc32(mine.data));
    }
    ASSERT_EQ(indexed["channels"].size(), 3u);
    for (const json& c : indexed["channels"]) {
      const Channel& mine = (*ours)->channels().at(c["id"].get<std::uint16_t>());
      EXPECT_EQ(c["topic"], mine.topic);
      EXPECT_EQ(c["schemaId"].get<std::uint16_t>(), mine.schema_id);
      EXPECT_EQ(c["messageEncoding"], "cdr");
      EXPECT_EQ(c["metadata"].get<StringMap>(), mine.metadata);
      EXPECT_TRUE(c["schemaFound"].get<bool>()) << "the reference reader finds every schema";
    }
    std::set<int> groups;
    for (const json& g : indexed["summaryOffsets"]) groups.insert(g.get<int>());
    EXPECT_TRUE(groups.contains(0x03) && groups.contains(0x04) && groups.contains(0x0B) &&
                groups.contains(0x0A) && groups.contains(0x0D));
    EXPECT_EQ(groups.contains(0x08), l.chunked);
    ASSERT_EQ(indexed["attachments"].size(), 1u);
    EXPECT_EQ(indexed["attachments"][0]["name"], "calibration.yaml");
    EXPECT_EQ(indexed["attachments"][0]["size"].get<int>(), 5);
    ASSERT_EQ(indexed["metadata"].size(), 1u);
    EXPECT_EQ(indexed["metadata"][0]["name"], "run");
    EXPECT_EQ(indexed["metadata"][0]["metadata"]["scenario"], "drive_flat");
    std::cout << "[ interop ] ours-" << l.name
              << " -> @mcap/core indexed reader: " << indexed["messages"] << " messages from "
              << indexed["chunkIndexes"] << " chunks, summary groups "
              << indexed["summaryOffsets"].dump() << "\n";
  }
}

// ---- the reference writer, our reader -----------------------------------------------------------

Timestamp LogTimeOf(int i) {
  return 1'000'000'000ull + static_cast<Timestamp>((i * 7919) % 500) * 1'000'000ull;
}
Bytes DataOf(int i) {
  Bytes d(static_cast<std::size_t>((i * 37) % 200));
  for (std::size_t k = 0; k < d.size(); ++k)
    d[k] = static_cast<std::uint8_t>((i * 31 + static_cast<int>(k) * 17) & 0xff);
  return d;
}

TEST(Interop, OurReaderReadsTheReferenceWritersFiles) {
  if (const std::string why = MissingTool(); !why.empty()) GTEST_SKIP() << why;
  const std::string dir = testing::MakeTempDir("mcap-interop");
  for (const std::string compression : {"none", "zstd", "lz4"}) {
    for (const bool chunks : {true, false}) {
      if (!chunks && compression != "none") continue;  // compression needs chunks
      const std::string name = compression + (chunks ? "" : "-unchunked");
      SCOPED_TRACE(name);
      const std::string path = dir + "/reference-" + name + ".mcap";
      std::vector<std::string> args = {path, "--compression", compression};
      if (!chunks) args.push_back("--no-chunks");
      const json wrote = RunNode(dir, "write.mjs", args);
      ASSERT_FALSE(wrote.is_null());

      for (Verification v :
           {Verification::kFull, Verification::kDataSection, Verification::kSummary}) {
        auto r = Reader::Open(path, {v});
        ASSERT_TRUE(r.ok()) << r.status().ToString();
        EXPECT_TRUE((*r)->has_summary());
        EXPECT_EQ((*r)->header().library, "@mcap/core interop writer");
        ASSERT_EQ((*r)->channels().size(), 3u);
        EXPECT_EQ((*r)->channels().at(0).topic, "interop/points") << "channel ids start at 0";
        EXPECT_EQ((*r)->channels().at(0).metadata, (StringMap{{"k", "v"}}));
        EXPECT_EQ((*r)->channels().at(2).schema_id, 0);
        ASSERT_EQ((*r)->schemas().size(), 2u);
        EXPECT_EQ((*r)->schemas().at(1).name, "interop::Point");
        EXPECT_EQ((*r)->schemas().at(2).encoding, "omgidl");
        for (const ChunkIndex& c : (*r)->chunk_indexes()) {
          EXPECT_EQ(c.compression, compression == "none" ? "" : compression);
        }
        EXPECT_EQ((*r)->chunk_indexes().empty(), !chunks);

        int n = 0;
        Timestamp last = 0;
        std::uint32_t sum_of_crcs = 0;
        const Status s = (*r)->ForEachMessage({}, [&](const MessageEvent& e) {
          const int i = static_cast<int>(e.message.sequence);
          EXPECT_EQ(e.message.log_time, LogTimeOf(i));
          EXPECT_EQ(e.message.publish_time, LogTimeOf(i) + 1);
          EXPECT_EQ(e.message.channel_id, i % 3);
          EXPECT_EQ(Bytes(e.message.data.begin(), e.message.data.end()), DataOf(i)) << i;
          EXPECT_GE(e.message.log_time, last);
          last = e.message.log_time;
          sum_of_crcs += ComputeCrc32(e.message.data);
          ++n;
          return Status::Ok();
        });
        ASSERT_TRUE(s.ok()) << s.ToString();
        EXPECT_EQ(n, 500);
        EXPECT_EQ(sum_of_crcs, wrote["sumOfDataCrcs"].get<std::uint32_t>());
        ASSERT_EQ((*r)->ReadAllMetadata().value().size(), 1u);
        EXPECT_EQ((*r)->ReadAllMetadata().value()[0],
                  (Metadata{"interop", {{"writer", "@mcap/core"}}}));
        ASSERT_EQ((*r)->attachment_indexes().size(), 1u);
        const Attachment a = (*r)->ReadAttachment((*r)->attachment_indexes()[0]).value();
        EXPECT_EQ(a.name, "notes.txt");
        EXPECT_EQ(a.data, (Bytes{'h', 'e', 'l', 'l', 'o'}));
        const RecordingInfo info = Summarize(**r).value();
        EXPECT_EQ(info.message_count, 500u);
        ASSERT_EQ(info.topics.size(), 3u);
        EXPECT_EQ(info.topics[0].topic, "interop/labels");
        EXPECT_EQ(info.topics[0].message_count, 167u);
      }
      std::cout << "[ interop ] @mcap/core " << name << " (" << wrote["size"]
                << " bytes) -> rover_mcap reader: 500 messages, 3 channels, 2 schemas, metadata "
                   "and attachment\n";
    }
  }
}

}  // namespace
}  // namespace rover::mcap
