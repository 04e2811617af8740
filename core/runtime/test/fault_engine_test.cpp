#include "rover/runtime/fault_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <set>
#include <thread>

#include "rover/runtime/dds.hpp"
#include "rover/runtime/executor.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::faults {
namespace {

using dds::Reader;
using dds::Writer;
using Cmd = rover_dl_DriveCommand;

constexpr std::uint32_t kSentinel = 999999;

class FaultEngineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = rover::testing::IsolatedDomain();
    auto p = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok()) << p.status().message();
    participant_ = std::move(*p);
    engine_ = MakeEngine("svc");
  }
  void TearDown() override { engine_.reset(); }

  std::unique_ptr<FaultEngine> MakeEngine(const std::string& service) {
    auto e = std::make_unique<FaultEngine>(
        FaultEngine::Options{service, &clock_, Time{0}, std::chrono::seconds(1)});
    e->SetRecordSink([this](const FaultRecord& r) {
      std::lock_guard lock(mu_);
      records_.push_back(r);
    });
    e->Install();
    return e;
  }

  static FaultSpec Spec(const std::string& yaml, std::uint32_t id = 1) {
    auto s = ParseFault(yaml, "test");
    EXPECT_TRUE(s.ok()) << s.status().message();
    FaultSpec out = s.ok() ? *s : FaultSpec{};
    out.id = id;
    return out;
  }
  void Add(const std::string& yaml, std::uint32_t id = 1) {
    const Status s = engine_->Add(Spec(yaml, id));
    ASSERT_TRUE(s.ok()) << s.message();
  }

  template <class T>
  Writer<T> MakeWriter(const std::string& topic) {
    auto w = Writer<T>::Create(participant_, topic);
    EXPECT_TRUE(w.ok()) << w.status().message();
    return std::move(*w);
  }
  template <class T>
  Reader<T> MakeReader(const std::string& topic) {
    auto r = Reader<T>::Create(participant_, topic);
    EXPECT_TRUE(r.ok()) << r.status().message();
    return std::move(*r);
  }

  struct Commands {
    Writer<Cmd> w;
    Reader<Cmd> r;
  };
  // A writer and a reader of dl/drive_command (reliable, keep-all) in this process.
  Commands OpenCommands() {
    return {MakeWriter<Cmd>("dl/drive_command"), MakeReader<Cmd>("dl/drive_command")};
  }

  static Cmd Command(std::uint32_t id) {
    Cmd c{};
    c.command_id = id;
    c.header.seq = id;
    c.curvature = 0.25;
    c.distance = 1.0 + id;
    dds::CopyString(c.header.frame_id, "rover");
    return c;
  }
  static void Send(Writer<Cmd>& w, std::uint32_t first, std::uint32_t last) {
    for (std::uint32_t i = first; i <= last; ++i) ASSERT_TRUE(w.Write(Command(i)).ok());
  }

  // Everything the reader gets up to the sentinel, which is written with no fault left. A reader
  // seam acts when the service takes a sample, so what is there is taken before the clear.
  std::vector<Cmd> Drain(Writer<Cmd>& w, Reader<Cmd>& r) {
    std::vector<Cmd> got = TakeNow(r);
    engine_->Clear();
    EXPECT_TRUE(w.Write(Command(kSentinel)).ok());
    bool done = false;
    EXPECT_TRUE(rover::testing::WaitFor([&] {
      for (auto& s : r.Take()) {
        if (s->command_id == kSentinel) {
          done = true;
        } else {
          got.push_back(s.data());
        }
      }
      return done;
    }));
    return got;
  }
  // What the reader has now (local delivery is synchronous; two empty takes 5 ms apart).
  static std::vector<Cmd> TakeNow(Reader<Cmd>& r) {
    std::vector<Cmd> got;
    for (int empty = 0; empty < 2;) {
      auto batch = r.Take();
      empty = batch.empty() ? empty + 1 : 0;
      for (auto& x : batch) got.push_back(x.data());
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return got;
  }
  static std::vector<std::uint32_t> Ids(const std::vector<Cmd>& v) {
    std::vector<std::uint32_t> out;
    for (const auto& c : v) out.push_back(c.command_id);
    return out;
  }
  std::vector<FaultRecord> Records(FaultRecord::Event e) {
    std::lock_guard lock(mu_);
    std::vector<FaultRecord> out;
    for (const auto& r : records_) {
      if (r.event == e) out.push_back(r);
    }
    return out;
  }
  void At(double seconds) {
    clock_.Set(Time::FromSeconds(seconds));
    engine_->Pump();
  }

  dds::DomainLease lease_;
  dds::Participant participant_;
  ManualClock clock_{Time{0}};
  std::unique_ptr<FaultEngine> engine_;
  std::mutex mu_;
  std::vector<FaultRecord> records_;
};

TEST_F(FaultEngineTest, EveryEndpointHasASeamAndPassesSamplesUntouchedWithoutFaults) {
  auto [w, r] = OpenCommands();
  EXPECT_NE(w.seam(), nullptr);
  EXPECT_NE(r.seam(), nullptr);
  Send(w, 1, 10);
  const auto got = Drain(w, r);
  ASSERT_EQ(got.size(), 10u);
  for (std::uint32_t i = 0; i < 10; ++i) {
    EXPECT_EQ(got[i].command_id, i + 1);
    EXPECT_EQ(got[i].distance, 2.0 + i);
  }
  // The fault topics themselves and topics outside the catalog get no seam.
  EXPECT_EQ(MakeWriter<rover_sys_FaultEvent>("sys/fault_event").seam(), nullptr);
  auto outside = Writer<Cmd>::Create(participant_, "test/cmd", dds::QosProfile::kCommand);
  ASSERT_TRUE(outside.ok());
  EXPECT_EQ(outside->seam(), nullptr);
}

TEST_F(FaultEngineTest, EndpointsCreatedBeforeAFaultAreAffected) {
  auto [w, r] = OpenCommands();
  Send(w, 1, 3);
  Add("{kind: drop, topic: dl/drive_command}");
  Send(w, 4, 6);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{1, 2, 3}));
}

TEST_F(FaultEngineTest, DropHitsTheSameSamplesForTheSameSeed) {
  auto run = [&](std::uint64_t seed, bool busy_neighbour) {
    auto w = MakeWriter<Cmd>("dl/drive_command");
    auto r = MakeReader<Cmd>("dl/drive_command");
    FaultSpec s = Spec("{kind: drop, topic: dl/drive_command, probability: 0.3}");
    s.seed = seed;
    EXPECT_TRUE(engine_->Add(s).ok());
    // An unrelated topic with its own fault, written concurrently, changes nothing here.
    std::thread neighbour;
    std::atomic<bool> stop{false};
    if (busy_neighbour) {
      EXPECT_TRUE(engine_->Add(Spec("{kind: drop, topic: dl/relative_pose, probability: 0.5}", 2)).ok());
      neighbour = std::thread([&] {
        auto nw = MakeWriter<rover_dl_RelativePose>("dl/relative_pose");
        rover_dl_RelativePose p{};
        while (!stop) (void)nw.Write(p);
      });
    }
    Send(w, 1, 200);
    stop = true;
    if (neighbour.joinable()) neighbour.join();
    const auto list = engine_->List();
    const auto got = Ids(Drain(w, r));
    EXPECT_EQ(list.front().seen, 200u);
    EXPECT_EQ(list.front().hit, 200u - got.size());
    return got;
  };
  const auto a = run(5, false);
  const auto b = run(5, true);
  const auto c = run(6, false);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // About 30 % dropped (the seed fixes the exact count).
  EXPECT_GT(a.size(), 110u);
  EXPECT_LT(a.size(), 170u);
}

TEST_F(FaultEngineTest, WindowsFollowTheRunClockAndAreRecorded) {
  auto [w, r] = OpenCommands();
  Add("{kind: drop, topic: dl/drive_command, start_s: 5, duration_s: 3}", 7);
  ASSERT_EQ(Records(FaultRecord::Event::kAdded).size(), 1u);
  for (int t = 0; t <= 10; ++t) {
    At(t);
    ASSERT_TRUE(w.Write(Command(static_cast<std::uint32_t>(t))).ok());
  }
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 8, 9, 10}));
  const auto started = Records(FaultRecord::Event::kStarted);
  ASSERT_EQ(started.size(), 1u);
  EXPECT_EQ(started[0].fault_id, 7u);
  EXPECT_EQ(started[0].at, Time::FromSeconds(5));
  EXPECT_EQ(started[0].service, "svc");
  const auto ended = Records(FaultRecord::Event::kEnded);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].at, Time::FromSeconds(8));
  EXPECT_EQ(ended[0].hit, 3u);
  EXPECT_EQ(ended[0].seen, 3u);
  // Counts while active: at 6 s and 7 s (one report period apart, the count changed).
  const auto counts = Records(FaultRecord::Event::kCount);
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0].hit, 1u);
  EXPECT_EQ(counts[1].hit, 2u);
  // Ended faults leave the active set (the seams are back on the fast path) but are listed.
  const auto list = engine_->List();
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].state, FaultState::kEnded);
}

// The simulator runs on wall time and makes the run clock: its faults move to the run clock
// (UseClock) before they open, so "start_s: 5" means 5 s of simulated time there too.
TEST_F(FaultEngineTest, UseClockMovesWindowsThatHaveNotOpenedToTheRunClock) {
  At(1000);  // the process's own clock (wall time) is far ahead of the run clock
  auto [w, r] = OpenCommands();
  Add("{kind: drop, topic: dl/drive_command, start_s: 5, duration_s: 3}", 7);
  ManualClock run(Time{0});
  engine_->UseClock(run, Time{0});
  for (int t = 0; t <= 10; ++t) {
    run.Set(Time::FromSeconds(t));
    engine_->Pump();
    ASSERT_TRUE(w.Write(Command(static_cast<std::uint32_t>(t))).ok());
  }
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 8, 9, 10}));
  const auto started = Records(FaultRecord::Event::kStarted);
  ASSERT_EQ(started.size(), 1u);
  EXPECT_EQ(started[0].at, Time::FromSeconds(5));  // on the run clock
  const auto list = engine_->List();
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].start, Time::FromSeconds(5));
}

TEST_F(FaultEngineTest, WriterDelayWritesTheSampleLaterOnTheRunClock) {
  auto [w, r] = OpenCommands();
  Add("{kind: delay, topic: dl/drive_command, delay: 2}");
  At(1);
  Send(w, 1, 1);
  At(2.9);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(r.Take().empty());
  ASSERT_TRUE(engine_->NextDue().has_value());
  EXPECT_EQ(*engine_->NextDue(), Time::FromSeconds(3));
  At(3.0);
  std::vector<Cmd> got;
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (auto& s : r.Take()) got.push_back(s.data());
    return !got.empty();
  }));
  EXPECT_EQ(got[0].command_id, 1u);
  EXPECT_EQ(got[0].distance, 2.0);
  EXPECT_FALSE(engine_->NextDue().has_value());
}

TEST_F(FaultEngineTest, DistributedDelaysReorderAndAreSeeded) {
  auto [w, r] = OpenCommands();
  Add("{kind: delay, topic: dl/drive_command, delay: {distribution: uniform, min: 0.1, max: 1.0}}");
  At(0);
  Send(w, 1, 20);
  for (int i = 1; i <= 12; ++i) At(0.1 * i);
  const auto got = Ids(Drain(w, r));
  ASSERT_EQ(got.size(), 20u);
  EXPECT_FALSE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(std::set<std::uint32_t>(got.begin(), got.end()).size(), 20u);
}

TEST_F(FaultEngineTest, ReaderDelayHoldsSamplesUntilDueThroughTheExecutor) {
  auto [w, r] = OpenCommands();
  Add("{kind: delay, topic: dl/drive_command, side: reader, delay: 0.5}");
  auto exec = Executor::Create(participant_, clock_);
  ASSERT_TRUE(exec.ok());
  std::vector<std::uint32_t> got;
  ASSERT_TRUE((*exec)->Subscribe<Cmd>(r, [&](const dds::Sample<Cmd>& s) { got.push_back(s->command_id); }).ok());
  ASSERT_TRUE((*exec)->SetActive(true).ok());
  clock_.Set(Time::FromSeconds(10));
  Send(w, 1, 2);
  for (int i = 0; i < 5; ++i) (*exec)->SpinOnce(std::chrono::milliseconds(20));
  EXPECT_TRUE(got.empty());
  clock_.Set(Time::FromSeconds(10.5));
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    (*exec)->SpinOnce(std::chrono::milliseconds(20));
    return got.size() == 2;
  }));
  EXPECT_EQ(got, (std::vector<std::uint32_t>{1, 2}));
}

TEST_F(FaultEngineTest, WriterDelayIsFlushedByTheExecutorPump) {
  auto [w, r] = OpenCommands();
  Add("{kind: delay, topic: dl/drive_command, delay: 1}");
  auto exec = Executor::Create(participant_, clock_);
  ASSERT_TRUE(exec.ok());
  ASSERT_TRUE((*exec)->SetActive(true).ok());
  Send(w, 1, 1);
  clock_.Set(Time::FromSeconds(1));
  std::size_t n = 0;
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    (*exec)->SpinOnce(std::chrono::milliseconds(10));
    n += r.Take().size();
    return n == 1;
  }));
}

TEST_F(FaultEngineTest, DuplicateSendsExtraCopies) {
  auto [w, r] = OpenCommands();
  Add("{kind: duplicate, topic: dl/drive_command, copies: 2}");
  Send(w, 1, 2);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{1, 1, 1, 2, 2, 2}));
  // On the reader side.
  Add("{kind: duplicate, topic: dl/drive_command, side: reader}");
  Send(w, 3, 3);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{3, 3}));
}

TEST_F(FaultEngineTest, ReorderSwapsNeighboursAndReleasesALoneSampleAfterItsHold) {
  auto [w, r] = OpenCommands();
  Add("{kind: reorder, topic: dl/drive_command, delay: 0.5}");
  Send(w, 1, 6);
  At(0.2);
  Send(w, 7, 7);  // held: nothing comes after it
  At(0.6);
  EXPECT_TRUE(engine_->NextDue().has_value());
  At(0.7);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{2, 1, 4, 3, 6, 5, 7}));
}

TEST_F(FaultEngineTest, FreezeRepeatsTheLastSampleBeforeTheWindow) {
  auto [w, r] = OpenCommands();
  Add("{kind: freeze, topic: dl/drive_command, start_s: 5, duration_s: 2}");
  At(1);
  Send(w, 1, 4);
  At(5);
  Send(w, 5, 8);
  At(7);
  Send(w, 9, 9);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{1, 2, 3, 4, 4, 4, 4, 4, 9}));
  EXPECT_EQ(engine_->List().front().hit, 4u);
}

TEST_F(FaultEngineTest, FreezeWithoutAnEarlierSampleRepeatsTheFirstOne) {
  auto [w, r] = OpenCommands();
  Add("{kind: freeze, topic: dl/drive_command, side: reader}");
  Send(w, 1, 3);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{1, 1, 1}));
}

TEST_F(FaultEngineTest, CorruptChangesTheNamedFieldOfACopy) {
  auto [w, r] = OpenCommands();
  Add("{kind: corrupt, topic: dl/drive_command, field: curvature, mode: nan}", 1);
  Add("{kind: corrupt, topic: dl/drive_command, field: distance, mode: -inf}", 2);
  // DDS refuses to send an enum outside its literals: that one is corrupted where it is read.
  Add("{kind: corrupt, topic: dl/drive_command, side: reader, field: primitive, mode: out_of_range}", 3);
  Add("{kind: corrupt, topic: dl/drive_command, field: command_id, mode: value, value: 77}", 4);
  Add("{kind: corrupt, topic: dl/drive_command, field: header.frame_id, mode: bitflip}", 5);
  Add("{kind: corrupt, topic: dl/drive_command, field: header.seq, mode: bitflip, bits: 3}", 6);
  const Cmd original = Command(1);
  Cmd sent;
  std::memcpy(&sent, &original, sizeof(Cmd));
  ASSERT_TRUE(w.Write(sent).ok());
  EXPECT_EQ(std::memcmp(&sent, &original, sizeof(Cmd)), 0);  // the caller's sample is untouched
  const auto got = Drain(w, r);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(std::isnan(got[0].curvature));
  EXPECT_EQ(got[0].distance, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(static_cast<int>(got[0].primitive), rover_dl_PRIMITIVE_STEER + 1);
  EXPECT_EQ(got[0].command_id, 77u);
  EXPECT_EQ(std::strlen(got[0].header.frame_id), 5u);
  EXPECT_STRNE(got[0].header.frame_id, "rover");
  EXPECT_EQ(__builtin_popcount(got[0].header.seq ^ original.header.seq), 3);
  EXPECT_EQ(got[0].angle, original.angle);
  EXPECT_EQ(got[0].header.stamp_ns, original.header.stamp_ns);
}

TEST_F(FaultEngineTest, CorruptOnAReaderChangesSequenceElementsInPlace) {
  auto w = MakeWriter<rover_apl_Plan>("apl/plan");
  auto r = MakeReader<rover_apl_Plan>("apl/plan");
  Add("{kind: corrupt, topic: apl/plan, side: reader, field: 'waypoints[*].x', mode: value, value: 5}");
  rover_apl_Plan p{};
  std::vector<rover_Vector3> wp = {{1, 2, 3}, {4, 5, 6}};
  dds::BorrowSequence(p.waypoints, wp);
  ASSERT_TRUE(w.Write(p).ok());
  std::vector<dds::OwnedSample<rover_apl_Plan>> got;
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (auto& s : r.Take()) got.push_back(std::move(s));
    return !got.empty();
  }));
  const auto v = dds::View(got[0]->waypoints);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].x, 5.0);
  EXPECT_EQ(v[1].x, 5.0);
  EXPECT_EQ(v[0].y, 2.0);
  EXPECT_EQ(v[1].z, 6.0);
  EXPECT_EQ(wp[0].x, 1.0);
}

TEST_F(FaultEngineTest, NoiseAndBiasOnNumbers) {
  auto [w, r] = OpenCommands();
  Add("{kind: bias, topic: dl/drive_command, field: curvature, value: 0.5}", 1);
  Add("{kind: noise, topic: dl/drive_command, field: distance, sigma: 1, seed: 11}", 2);
  Add("{kind: bias, topic: dl/drive_command, field: header.seq, value: -3}", 3);
  Send(w, 1, 400);
  const auto got = Drain(w, r);
  ASSERT_EQ(got.size(), 400u);
  double sum = 0, sum2 = 0;
  for (const auto& c : got) {
    EXPECT_EQ(c.curvature, 0.75);
    const double e = c.distance - (1.0 + c.command_id);
    sum += e;
    sum2 += e * e;
    EXPECT_EQ(c.header.seq, c.command_id > 3 ? c.command_id - 3 : 0u);  // saturates at 0
  }
  const double mean = sum / 400, sd = std::sqrt(sum2 / 400 - mean * mean);
  EXPECT_LT(std::abs(mean), 0.2);
  EXPECT_GT(sd, 0.8);
  EXPECT_LT(sd, 1.2);
}

TEST_F(FaultEngineTest, PartitionCutsTheServiceOffBothWays) {
  // Endpoints of another process: no seam (created before the engine is installed).
  engine_.reset();
  auto remote_w = MakeWriter<Cmd>("dl/drive_command");
  auto remote_r = MakeReader<Cmd>("dl/drive_command");
  EXPECT_EQ(remote_w.seam(), nullptr);
  engine_ = MakeEngine("svc");
  auto [w, r] = OpenCommands();
  Add("{kind: partition, service: other}", 1);  // not this service: no effect
  Send(remote_w, 1, 1);
  Send(w, 2, 2);
  EXPECT_EQ(Ids(TakeNow(r)), (std::vector<std::uint32_t>{1, 2}));
  Add("{kind: partition, service: svc}", 2);
  Send(remote_w, 3, 3);  // our reader drops it
  Send(w, 4, 4);         // our writer drops it
  auto collect = [&](Reader<Cmd>& reader) {
    std::vector<std::uint32_t> got;
    EXPECT_TRUE(rover::testing::WaitFor([&] {
      for (auto& s : reader.Take()) got.push_back(s->command_id);
      return !got.empty() && got.back() == kSentinel;
    }));
    return got;
  };
  EXPECT_TRUE(TakeNow(r).empty());  // 3 dropped on our side (4 never sent)
  engine_->Clear();
  ASSERT_TRUE(remote_w.Write(Command(kSentinel)).ok());
  EXPECT_EQ(collect(r), (std::vector<std::uint32_t>{kSentinel}));
  EXPECT_EQ(collect(remote_r), (std::vector<std::uint32_t>{1, 2, 3, kSentinel}));
  const auto added = Records(FaultRecord::Event::kAdded);
  ASSERT_GE(added.size(), 1u);
  EXPECT_NE(added[0].detail.find("(not for this service)"), std::string::npos);
}

TEST_F(FaultEngineTest, SidesAndServicesSelectEndpoints) {
  auto [w, r] = OpenCommands();
  Add("{kind: drop, topic: dl/drive_command, service: 'other-*'}", 1);
  Send(w, 1, 1);
  EXPECT_EQ(Ids(TakeNow(r)), (std::vector<std::uint32_t>{1}));
  Add("{kind: drop, topic: 'dl/*', service: 's?c', side: reader}", 2);
  Send(w, 2, 2);
  EXPECT_TRUE(TakeNow(r).empty());
  const auto list = engine_->List();
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].seen, 0u);  // other services' fault
  EXPECT_EQ(list[1].seen, 1u);  // the reader's, not the writer's
}

TEST_F(FaultEngineTest, RemoveAndClearEndFaultsWithTheirCounts) {
  auto [w, r] = OpenCommands();
  Add("{kind: drop, topic: dl/drive_command}", 3);
  Add("{kind: drop, topic: dl/drive_command, start_s: 100}", 4);
  At(0);
  Send(w, 1, 5);
  EXPECT_TRUE(engine_->Remove(3));
  EXPECT_FALSE(engine_->Remove(3));
  Send(w, 6, 6);
  engine_->Clear();
  const auto ended = Records(FaultRecord::Event::kEnded);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].fault_id, 3u);
  EXPECT_EQ(ended[0].hit, 5u);
  const auto removed = Records(FaultRecord::Event::kRemoved);
  ASSERT_EQ(removed.size(), 1u);  // 4 never started
  EXPECT_EQ(removed[0].fault_id, 4u);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{6}));
}

TEST_F(FaultEngineTest, AddingTheSameIdReplacesTheFault) {
  auto [w, r] = OpenCommands();
  Add("{kind: drop, topic: dl/drive_command}", 1);
  Add("{kind: duplicate, topic: dl/drive_command}", 1);
  Send(w, 1, 1);
  EXPECT_EQ(Ids(Drain(w, r)), (std::vector<std::uint32_t>{1, 1}));
}

TEST_F(FaultEngineTest, InvalidSpecsAreRefused) {
  FaultSpec s = Spec("{kind: drop, topic: dl/drive_command}");
  s.probability = 3;
  EXPECT_FALSE(engine_->Add(s).ok());
  s.probability = 1;
  s.id = 0;
  EXPECT_FALSE(engine_->Add(s).ok());
  EXPECT_TRUE(engine_->List().empty());
}

}  // namespace
}  // namespace rover::faults
