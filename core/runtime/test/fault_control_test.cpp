#include "rover/runtime/fault_control.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <mutex>
#include <thread>

#include "rover/runtime/service.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::faults {
namespace {

using Cmd = rover_dl_DriveCommand;

// A service context (fault agent installed, executor spinning in a thread) and a client on a
// second participant, as roverctl would be.
class FaultControlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = rover::testing::IsolatedDomain();
    ServiceOptions o;
    o.name = "svc-a";
    o.domain = lease_.domain();
    auto initial = ParseFaults("- {kind: duplicate, topic: dl/drive_status, start_s: 3600, id: 1}\n",
                               "initial.yaml");
    ASSERT_TRUE(initial.ok()) << initial.status().message();
    o.faults = *initial;
    auto ctx = ServiceContext::Create(o);
    ASSERT_TRUE(ctx.ok()) << ctx.status().message();
    ctx_ = std::move(*ctx);
    ASSERT_NE(ctx_->faults(), nullptr);
    auto p = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok());
    client_participant_ = std::move(*p);
    auto c = FaultClient::Create(client_participant_);
    ASSERT_TRUE(c.ok()) << c.status().message();
    client_ = std::make_unique<FaultClient>(std::move(*c));
    spinner_ = std::thread([this] { ctx_->executor().Spin(); });
    ASSERT_TRUE(client_->WaitForServices(1, std::chrono::seconds(20)).ok());
  }
  void TearDown() override {
    if (ctx_) ctx_->executor().Stop();
    if (spinner_.joinable()) spinner_.join();
    client_.reset();
    ctx_.reset();
  }

  // Waits for a record matching `pred` (records that arrived earlier count too).
  std::optional<FaultRecord> WaitRecord(const std::function<bool(const FaultRecord&)>& pred) {
    std::optional<FaultRecord> found;
    rover::testing::WaitFor([&] {
      for (auto& r : client_->TakeRecords()) seen_.push_back(std::move(r));
      auto it = std::find_if(seen_.begin(), seen_.end(), pred);
      if (it == seen_.end()) return false;
      found = *it;
      seen_.erase(it);
      return true;
    });
    return found;
  }
  static std::function<bool(const FaultRecord&)> Is(FaultRecord::Event e, std::uint32_t id) {
    return [e, id](const FaultRecord& r) { return r.event == e && r.fault_id == id; };
  }

  dds::DomainLease lease_;
  std::unique_ptr<ServiceContext> ctx_;
  dds::Participant client_participant_;
  std::unique_ptr<FaultClient> client_;
  std::thread spinner_;
  std::vector<FaultRecord> seen_;
};

TEST_F(FaultControlTest, AddListRemoveClearOverTheControlTopic) {
  // The initial fault (ROVER_FAULTS) was added at start; its record may predate the client.
  auto writer = ctx_->MakeWriter<Cmd>("dl/drive_command");  // created before the fault
  ASSERT_TRUE(writer.ok());
  auto reader = dds::Reader<Cmd>::Create(client_participant_, "dl/drive_command");
  ASSERT_TRUE(reader.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] { return writer->MatchedReaders() >= 1; }));

  auto spec = ParseFault("{kind: drop, topic: dl/drive_command, id: 5, name: lose commands}", "cli");
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  spec->start_mode = StartMode::kOnReceipt;
  ASSERT_TRUE(client_->Add(*spec).ok());
  auto added = WaitRecord(Is(FaultRecord::Event::kAdded, 5));
  ASSERT_TRUE(added);
  EXPECT_EQ(added->service, "svc-a");
  EXPECT_EQ(added->kind, FaultKind::kDrop);
  EXPECT_EQ(added->detail, spec->Describe());

  for (std::uint32_t i = 1; i <= 5; ++i) {
    Cmd c{};
    c.command_id = i;
    ASSERT_TRUE(writer->Write(c).ok());
  }
  auto started = WaitRecord(Is(FaultRecord::Event::kStarted, 5));
  ASSERT_TRUE(started);
  // Counted while active (one report period of the run clock, here wall time).
  auto count = WaitRecord([](const FaultRecord& r) {
    return r.event == FaultRecord::Event::kCount && r.fault_id == 5 && r.hit == 5;
  });
  ASSERT_TRUE(count);
  EXPECT_EQ(count->seen, 5u);
  EXPECT_TRUE(reader->Take().empty());

  const auto listed = client_->List(std::chrono::milliseconds(500));
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].fault_id, 1u);
  EXPECT_EQ(listed[0].detail.rfind("pending: ", 0), 0u) << listed[0].detail;
  EXPECT_EQ(listed[1].fault_id, 5u);
  EXPECT_EQ(listed[1].detail.rfind("active: ", 0), 0u) << listed[1].detail;
  EXPECT_EQ(listed[1].hit, 5u);

  ASSERT_TRUE(client_->Remove(5).ok());
  auto ended = WaitRecord(Is(FaultRecord::Event::kEnded, 5));
  ASSERT_TRUE(ended);
  EXPECT_EQ(ended->hit, 5u);
  Cmd c{};
  c.command_id = 6;
  ASSERT_TRUE(writer->Write(c).ok());
  std::vector<std::uint32_t> got;
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (auto& s : reader->Take()) got.push_back(s->command_id);
    return !got.empty();
  }));
  EXPECT_EQ(got, std::vector<std::uint32_t>{6});

  ASSERT_TRUE(client_->Remove(5).ok());  // gone: the service says so
  ASSERT_TRUE(WaitRecord(Is(FaultRecord::Event::kRejected, 5)));
  ASSERT_TRUE(client_->Clear().ok());
  ASSERT_TRUE(WaitRecord(Is(FaultRecord::Event::kRemoved, 1)));  // never started
}

TEST_F(FaultControlTest, InvalidControlMessagesAreRejectedWithTheReason) {
  // Bypass the client's own validation, as another tool might.
  auto w = dds::Writer<rover_sys_FaultControl>::Create(client_participant_, "sys/fault_control");
  ASSERT_TRUE(w.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] { return w->MatchedReaders() >= 1; }));
  auto spec = ParseFault("{kind: corrupt, topic: dl/pose, field: odometer, mode: nan, id: 9}", "cli");
  ASSERT_TRUE(spec.ok());
  rover_sys_FaultControl m{};
  ToControl(*spec, &m);
  dds::CopyString(m.field, "odometre");
  ASSERT_TRUE(w->Write(m).ok());
  auto rejected = WaitRecord(Is(FaultRecord::Event::kRejected, 9));
  ASSERT_TRUE(rejected);
  EXPECT_EQ(rejected->detail.rfind("sys/fault_control: fault 9: key 'field': rover::dl::PoseEstimate "
                                   "has no field 'odometre' (nearest: odometer",
                                   0),
            0u)
      << rejected->detail;
  EXPECT_EQ(ctx_->faults()->engine().List().size(), 1u);  // only the initial fault
}

TEST_F(FaultControlTest, EventsRoundTripThroughIdl) {
  FaultRecord r;
  r.event = FaultRecord::Event::kCount;
  r.fault_id = 3;
  r.kind = FaultKind::kNoise;
  r.service = "dl-pose";
  r.topic = "ddl/imu";
  r.seen = 10;
  r.hit = 4;
  r.start = Time{5};
  r.end = Time{9};
  r.detail = "fault 3: ...";
  rover_sys_FaultEvent e{};
  ToIdl(r, &e);
  const FaultRecord back = FromIdl(e);
  EXPECT_EQ(back.event, r.event);
  EXPECT_EQ(back.fault_id, 3u);
  EXPECT_EQ(back.kind, FaultKind::kNoise);
  EXPECT_EQ(back.service, "dl-pose");
  EXPECT_EQ(back.topic, "ddl/imu");
  EXPECT_EQ(back.seen, 10u);
  EXPECT_EQ(back.hit, 4u);
  EXPECT_EQ(back.start, Time{5});
  EXPECT_EQ(back.end, Time{9});
  EXPECT_EQ(back.detail, r.detail);
}

// A service given ROVER_FAULTS validates the file before anything starts.
class Idle : public Service {
 public:
  Idle() : Service("idle") {}
  Status OnConfigure(ServiceContext&, const ParamSet&) override { return Status::Ok(); }
};

TEST(FaultDelivery, ServicesValidateRoverFaultsBeforeStarting) {
  const std::string dir = rover::testing::MakeTempDir("faults");
  const std::string good = dir + "/good.yaml", bad = dir + "/bad.yaml";
  std::ofstream(good) << "- {kind: drop, topic: dl/pose, probability: 0.1}\n";
  std::ofstream(bad) << "- kind: drop\n  topic: dl/pose\n  probability: 2\n";
  Idle service;
  char arg0[] = "idle", arg1[] = "--validate";
  char* argv[] = {arg0, arg1, nullptr};
  setenv("ROVER_FAULTS", good.c_str(), 1);
  EXPECT_EQ(RunServiceMain(service, 2, argv), 0);
  setenv("ROVER_FAULTS", bad.c_str(), 1);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(RunServiceMain(service, 2, argv), 2);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "idle: error: " + bad + ":3: probability = 2 is outside [0, 1]\n");
  setenv("ROVER_FAULTS_EPOCH_NS", "soon", 1);
  setenv("ROVER_FAULTS", good.c_str(), 1);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(RunServiceMain(service, 2, argv), 2);
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("ROVER_FAULTS_EPOCH_NS: 'soon'"),
            std::string::npos);
  unsetenv("ROVER_FAULTS_EPOCH_NS");
  unsetenv("ROVER_FAULTS");
}

}  // namespace
}  // namespace rover::faults
