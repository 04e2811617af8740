// roverctl record / replay / info and x-rover.record with real processes (the smoke set) on
// loopback: what a recording of a set holds, and every bad input the commands must refuse
// (nothing half-written called complete, nothing published from a bad file, no replay onto a
// domain where others publish the same topics).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "rover/base/process.hpp"
#include "rover/mcap/info.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;
using testing::WaitFor;

class RecordingCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("recording-cli");
    setenv("CYCLONEDDS_URI", dds::LoopbackConfigUri(testing::SourceDir()).c_str(), 1);
  }
  void TearDown() override {
    for (auto& p : background_) p.Terminate(std::chrono::seconds(10));
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  Process Spawn(const std::vector<std::string>& argv, const std::string& log) {
    SpawnOptions o;
    o.argv = argv;
    o.env["ROVER_STATE_DIR"] = dir_ + "/state";
    o.stdout_path = log;
    o.stderr_path = log;
    auto p = Process::Spawn(o);
    EXPECT_TRUE(p.ok()) << p.status().message();
    return std::move(*p);
  }
  /// Runs `roverctl args...` to the end: (exit code, output).
  std::pair<int, std::string> Roverctl(const std::vector<std::string>& args) {
    const std::string log = dir_ + "/roverctl-" + std::to_string(++runs_) + ".log";
    std::vector<std::string> argv = {testing::BinDir() + "/roverctl"};
    argv.insert(argv.end(), args.begin(), args.end());
    Process p = Spawn(argv, log);
    auto e = p.WaitFor(std::chrono::seconds(120));
    if (!e) e = p.Terminate(std::chrono::seconds(5));
    return {e->code, testing::ReadFile(log)};
  }
  /// The smoke set's compose file, with `rover_extra` added to its x-rover map.
  std::string Compose(const std::string& tag, const std::string& rover_extra = "") {
    project_ = "rec" + std::to_string(getpid()) + "-" + tag;
    const std::string path = dir_ + "/" + tag + ".compose.yaml";
    std::ofstream(path) << "x-rover: {project: " << project_ << rover_extra << "}\n"
                        << "services:\n"
                           "  ddl-smoke: {command: ddl-smoke --set rate_hz=50}\n"
                           "  dl-smoke:\n"
                           "    command: dl-smoke\n"
                           "    depends_on: {ddl-smoke: {condition: service_healthy}}\n";
    return path;
  }
  /// Starts the set in the background; returns its domain.
  int Up(const std::string& compose) {
    auto [code, out] = Roverctl({"up", "-d", compose});
    EXPECT_EQ(code, 0) << out;
    std::ifstream in(dir_ + "/state/" + project_ + "/state.json");
    return nlohmann::json::parse(in)["domain"].get<int>();
  }
  void Down() { (void)Roverctl({"down", project_}); }

  static std::map<std::string, std::uint64_t> Counts(const std::string& path) {
    std::map<std::string, std::uint64_t> out;
    auto info = mcap::SummarizeFile(path);
    EXPECT_TRUE(info.ok()) << info.status().message();
    if (!info.ok()) return out;
    for (const auto& t : info->topics) out[t.topic] += t.message_count;
    return out;
  }

  std::string dir_, project_;
  std::vector<Process> background_;
  int runs_ = 0;
};

TEST_F(RecordingCli, ComposeKeyRecordsTheSetWhileItIsUp) {
  const std::string file = dir_ + "/smoke.mcap";
  const std::string compose =
      Compose("key", ", record: {path: " + file + ", exclude: [sys/health], compression: lz4}");
  auto [code, out] = Roverctl({"up", compose, "--for", "4"});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("recording to " + file), std::string::npos) << out;
  EXPECT_NE(out.find("recorded "), std::string::npos) << out;
  mcap::ReaderOptions ro;
  ro.verification = mcap::Verification::kFull;
  auto r = mcap::Reader::Open(file, ro);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const auto counts = Counts(file);
  EXPECT_GT(counts.count("ddl/imu") ? counts.at("ddl/imu") : 0, 50u);  // 50 Hz for ~3 s
  EXPECT_GT(counts.count("dl/pose") ? counts.at("dl/pose") : 0, 0u);
  EXPECT_EQ(counts.count("sys/health"), 0u) << "excluded";
  for (const auto& c : (*r)->chunk_indexes()) EXPECT_TRUE(c.compression == "lz4" || c.compression.empty());
  auto [icode, info] = Roverctl({"info", file});
  EXPECT_EQ(icode, 0);
  EXPECT_NE(info.find("ddl/imu"), std::string::npos) << info;
  EXPECT_NE(info.find("rover::ddl::Imu"), std::string::npos) << info;

  // A bad key is refused before anything starts.
  const std::string bad = Compose("badkey", ", record: {compression: gzip}");
  auto [bcode, bout] = Roverctl({"up", bad, "--for", "1"});
  EXPECT_EQ(bcode, 2) << bout;
  EXPECT_NE(bout.find("x-rover.record.compression: 'gzip' is not one of: zstd, lz4, none"),
            std::string::npos)
      << bout;
}

TEST_F(RecordingCli, RecordReplayAndTheirBadInputs) {
  const int domain = Up(Compose("cli"));
  const std::string file = dir_ + "/imu.mcap";
  auto [code, out] = Roverctl({"record", "-p", project_, "-o", file, "--topics", "ddl/*",
                               "--duration", "2"});
  ASSERT_EQ(code, 0) << out;
  const auto counts = Counts(file);
  ASSERT_EQ(counts.size(), 1u) << out;
  EXPECT_GT(counts.at("ddl/imu"), 20u);

  // Onto the running set: ddl-smoke publishes ddl/imu there already.
  auto [busy, busy_out] = Roverctl({"replay", file, "-p", project_});
  EXPECT_EQ(busy, 1) << busy_out;
  EXPECT_NE(busy_out.find("is in use"), std::string::npos) << busy_out;
  EXPECT_NE(busy_out.find("ddl/imu (published by"), std::string::npos) << busy_out;

  // Recording to a full disk fails, and says so.
  auto [full, full_out] = Roverctl({"record", "--domain", std::to_string(domain), "-o",
                                    "/dev/full", "--duration", "1", "--clock", "wall"});
  EXPECT_EQ(full, 1) << full_out;
  EXPECT_NE(full_out.find("No space left on device"), std::string::npos) << full_out;
  auto [nodir, nodir_out] = Roverctl({"record", "-p", project_, "-o", dir_ + "/no/such/x.mcap"});
  EXPECT_NE(nodir, 0);
  EXPECT_NE(nodir_out.find("cannot record to"), std::string::npos) << nodir_out;
  Down();

  // A fresh domain: the replay goes out, with a made-up sim/clock (the smoke set runs on wall
  // time, so the recording has none).
  dds::DomainLease fresh = testing::IsolatedDomain();
  const int d = fresh.domain();
  fresh = dds::DomainLease();  // the replay leases it itself
  auto p = dds::Participant::Create(d);
  ASSERT_TRUE(p.ok());
  auto imu = dds::Reader<rover_ddl_Imu>::Create(*p, "ddl/imu");
  auto clock = dds::Reader<rover_sim_Clock>::Create(*p, "sim/clock");
  ASSERT_TRUE(imu.ok() && clock.ok());
  std::size_t got = 0, ticks = 0;
  std::atomic<bool> reading{true};
  std::thread reader([&] {
    while (reading) {
      got += imu->Take().size();
      ticks += clock->Take().size();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  auto [rc, rout] = Roverctl({"replay", file, "--domain", std::to_string(d), "--rate", "4"});
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  reading = false;
  reader.join();
  EXPECT_EQ(rc, 0) << rout;
  EXPECT_NE(rout.find("sim/clock made up"), std::string::npos) << rout;
  EXPECT_GT(got, counts.at("ddl/imu") / 2) << rout;
  EXPECT_GT(ticks, 0u);

  // A truncated and a corrupted file: refused naming the offset, nothing published.
  const std::string cut = dir_ + "/cut.mcap", bad = dir_ + "/bad.mcap";
  fs::copy_file(file, cut);
  fs::resize_file(cut, fs::file_size(file) - 20);
  fs::copy_file(file, bad);
  {
    std::fstream f(bad, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(file) / 3));
    f.put('\x5a').put('\xa5');
  }
  got = 0;
  for (const std::string& f : {cut, bad}) {
    auto [bc, bo] = Roverctl({"replay", f, "--domain", std::to_string(d)});
    EXPECT_EQ(bc, 2) << bo;
    EXPECT_NE(bo.find("offset"), std::string::npos) << bo;
    EXPECT_NE(bo.find("nothing was published"), std::string::npos) << bo;
    auto [ic, io] = Roverctl({"info", f});
    if (f == cut) {
      EXPECT_EQ(ic, 2) << io;
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(imu->Take().size(), 0u);

  // Bad arguments.
  auto [nt, nt_out] = Roverctl({"replay", file, "--domain", std::to_string(d), "--topics", "apl/*"});
  EXPECT_EQ(nt, 2);
  EXPECT_NE(nt_out.find("selects no topic of the recording"), std::string::npos) << nt_out;
  auto [nd, nd_out] = Roverctl({"replay", file});
  EXPECT_EQ(nd, 2);
  EXPECT_NE(nd_out.find("give --domain D"), std::string::npos) << nd_out;
}

}  // namespace
}  // namespace rover
