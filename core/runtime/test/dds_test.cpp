#include "rover/runtime/dds.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <vector>

#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

class DdsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = testing::IsolatedDomain();
    auto p = Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok()) << p.status().message();
    participant_ = std::move(*p);
  }
  DomainLease lease_;
  Participant participant_;
};

TEST_F(DdsTest, ParticipantRejectsBadDomain) {
  auto p = Participant::Create(400);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("out of range"), std::string::npos);
}

TEST_F(DdsTest, WriterAndReaderRoundTripWithSequences) {
  auto w = Writer<rover_hw_CameraFrame>::Create(participant_, "hw/camera_frame");
  ASSERT_TRUE(w.ok()) << w.status().message();
  auto r = Reader<rover_hw_CameraFrame>::Create(participant_, "hw/camera_frame");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(w->profile(), QosProfile::kCommand);  // images: reliable, keep-all
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() == 1; }));

  std::vector<uint8_t> left(64 * 32), right(64 * 32);
  for (std::size_t i = 0; i < left.size(); ++i) {
    left[i] = static_cast<uint8_t>(i);
    right[i] = static_cast<uint8_t>(255 - i % 256);
  }
  rover_hw_CameraFrame f{};
  f.request_id = 42;
  f.camera = rover_CAMERA_NAVCAM;
  f.width = 64;
  f.height = 32;
  CopyString(f.header.frame_id, "navcam_left");
  BorrowSequence(f.left, left);
  BorrowSequence(f.right, right);
  ASSERT_TRUE(w->Write(f).ok());

  std::vector<OwnedSample<rover_hw_CameraFrame>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& s : r->Take()) got.push_back(std::move(s));
    return !got.empty();
  }));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0]->request_id, 42u);
  EXPECT_STREQ(got[0]->header.frame_id, "navcam_left");
  auto l = View(got[0]->left);
  auto rr = View(got[0]->right);
  ASSERT_EQ(l.size(), left.size());
  EXPECT_TRUE(std::equal(l.begin(), l.end(), left.begin()));
  EXPECT_TRUE(std::equal(rr.begin(), rr.end(), right.begin()));
}

TEST_F(DdsTest, TakeEachLendsSamplesWithoutCopying) {
  auto w = Writer<rover_hw_CameraFrame>::Create(participant_, "hw/camera_frame");
  auto r = Reader<rover_hw_CameraFrame>::Create(participant_, "hw/camera_frame");
  ASSERT_TRUE(w.ok() && r.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() == 1; }));
  std::vector<uint8_t> left(100, 3), right(100, 4);
  rover_hw_CameraFrame f{};
  f.width = f.height = 10;
  BorrowSequence(f.left, left);
  BorrowSequence(f.right, right);
  ASSERT_TRUE(w->Write(f).ok());
  std::size_t sum = 0, calls = 0;
  ASSERT_TRUE(testing::WaitFor([&] {
    r->TakeEach([&](const Sample<rover_hw_CameraFrame>& s) {
      ++calls;
      for (uint8_t v : View(s->left)) sum += v;
      for (uint8_t v : View(s->right)) sum += v;
      EXPECT_TRUE(s.info().valid_data);
    });
    return calls > 0;
  }));
  EXPECT_EQ(calls, 1u);
  EXPECT_EQ(sum, 700u);
  EXPECT_EQ(r->TakeEach([](const Sample<rover_hw_CameraFrame>&) {}), 0u);  // taken, not read
}

TEST_F(DdsTest, CatalogDecidesTypeAndQos) {
  // Wrong type for a catalog topic.
  auto bad = Writer<rover_ddl_Imu>::Create(participant_, "dl/pose");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "topic 'dl/pose' carries rover_dl_PoseEstimate in the catalog, not rover_ddl_Imu");
  // A profile contradicting the catalog.
  auto wrong_qos = Reader<rover_dl_PoseEstimate>::Create(participant_, "dl/pose", QosProfile::kStream);
  ASSERT_FALSE(wrong_qos.ok());
  EXPECT_NE(wrong_qos.status().message().find("uses QoS profile 'state'"), std::string::npos);
  // A topic outside the catalog needs an explicit profile.
  auto unknown = Writer<rover_ddl_Imu>::Create(participant_, "test/imu");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().code(), StatusCode::kNotFound);
  auto explicit_ok = Writer<rover_ddl_Imu>::Create(participant_, "test/imu", QosProfile::kStream);
  EXPECT_TRUE(explicit_ok.ok());
}

TEST_F(DdsTest, LatchedStatusReachesLateJoiner) {
  auto w = Writer<rover_dl_DriveStatus>::Create(participant_, "dl/drive_status");
  ASSERT_TRUE(w.ok());
  rover_dl_DriveStatus s{};
  s.command_id = 7;
  ASSERT_TRUE(w->Write(s).ok());
  auto r = Reader<rover_dl_DriveStatus>::Create(participant_, "dl/drive_status");
  ASSERT_TRUE(r.ok());
  std::vector<OwnedSample<rover_dl_DriveStatus>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& x : r->Take()) got.push_back(std::move(x));
    return !got.empty();
  }));
  EXPECT_EQ(got[0]->command_id, 7u);
}

// A seam that drops every second sample and adds 1 to command_id of the others proves that
// writers route samples through it.
class EveryOtherSeam : public TopicSeam {
 public:
  dds_return_t OnWrite(dds_entity_t writer, const void* sample,
                       const dds_topic_descriptor_t*) override {
    if (++n_ % 2 == 0) return DDS_RETCODE_OK;
    rover_dl_DriveCommand copy = *static_cast<const rover_dl_DriveCommand*>(sample);
    copy.command_id += 1000;
    return dds_write(writer, &copy);
  }
  void OnRead(void* sample, const dds_sample_info_t& info, const dds_topic_descriptor_t*,
              SampleSink& out) override {
    static_cast<rover_dl_DriveCommand*>(sample)->distance *= 2;
    out.Deliver(sample, info);
  }
  std::atomic<int> n_{0};
};

TEST_F(DdsTest, FaultSeamSeesEveryWriteAndRead) {
  auto seam = std::make_shared<EveryOtherSeam>();
  InstallSeamFactory([seam](const std::string& topic, Direction) -> std::shared_ptr<TopicSeam> {
    return topic == "dl/drive_command" ? seam : nullptr;
  });
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  InstallSeamFactory(nullptr);
  ASSERT_TRUE(w.ok() && r.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() == 1; }));
  for (uint32_t i = 1; i <= 4; ++i) {
    rover_dl_DriveCommand c{};
    c.command_id = i;
    c.distance = 1.0;
    ASSERT_TRUE(w->Write(c).ok());
  }
  std::vector<OwnedSample<rover_dl_DriveCommand>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& x : r->Take()) got.push_back(std::move(x));
    return got.size() >= 2;
  }));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0]->command_id, 1001u);
  EXPECT_EQ(got[1]->command_id, 1003u);
  EXPECT_EQ(got[0]->distance, 2.0);
}

TEST_F(DdsTest, WaitSetWakesOnGuardAndData) {
  auto ws = WaitSet::Create(participant_);
  auto g = GuardCondition::Create(participant_);
  ASSERT_TRUE(ws.ok() && g.ok());
  ASSERT_TRUE(ws->Attach(g->handle(), 99).ok());
  EXPECT_TRUE(ws->Wait(DDS_MSECS(10)).empty());
  g->Trigger();
  auto tokens = ws->Wait(DDS_SECS(5));
  ASSERT_EQ(tokens.size(), 1u);
  EXPECT_EQ(tokens[0], 99);
  EXPECT_TRUE(g->TakeTriggered());
  EXPECT_TRUE(ws->Detach(g->handle()).ok());
  EXPECT_FALSE(ws->Detach(g->handle()).ok());  // not attached any more: an error, not a crash
}

TEST(DomainLease, ExclusivePerMachine) {
  auto a = DomainLease::AcquireFree(200, 201);
  ASSERT_TRUE(a.ok());
  auto b = DomainLease::Acquire(a->domain());
  EXPECT_EQ(b.status().code(), StatusCode::kBusy);
  EXPECT_FALSE(DomainLease::Acquire(999).ok());
  EXPECT_FALSE(DomainLease::AcquireFree(5, 1).ok());
}


// ---- commands and discovery ---------------------------------------------------------------------
// Discovery between processes takes time; within one process Cyclone matches endpoints at once.
// So the writer of these tests lives in a child process, forked before this process touches DDS
// (a fork after Cyclone started would leave the child without its threads).

class CommandDelivery : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = testing::IsolatedDomain();
    ASSERT_EQ(pipe(to_child_), 0);
    ASSERT_EQ(pipe(to_parent_), 0);
  }
  void TearDown() override {
    if (child_ > 0) {
      close(to_child_[1]);  // the child ends when this closes
      int status = 0;
      waitpid(child_, &status, 0);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "writer process failed";
    }
  }
  // Forks the writer's process; `body` runs there and gets a writer of dl/drive_command.
  void ForkWriter(const std::function<bool(Writer<rover_dl_DriveCommand>&)>& body) {
    child_ = fork();
    ASSERT_GE(child_, 0);
    if (child_ > 0) return;
    close(to_child_[1]);
    bool ok = false;
    {
      auto p = Participant::Create(lease_.domain());
      auto w = p.ok() ? Writer<rover_dl_DriveCommand>::Create(*p, "dl/drive_command")
                      : Result<Writer<rover_dl_DriveCommand>>(p.status());
      ok = w.ok() && body(*w);
      // Keep the writer alive until the test is done with it (the parent closes the pipe).
      char c;
      while (read(to_child_[0], &c, 1) > 0) {
      }
    }
    _exit(ok ? 0 : 1);
  }
  // In the child: waits for the parent's signal.
  bool AwaitParent() {
    char c = 0;
    return read(to_child_[0], &c, 1) == 1;
  }
  void SignalChild() { ASSERT_EQ(write(to_child_[1], "g", 1), 1); }
  bool SignalParent() { return write(to_parent_[1], "w", 1) == 1; }
  void AwaitChild() {
    char c = 0;
    ASSERT_EQ(read(to_parent_[0], &c, 1), 1);
  }
  static bool Send(Writer<rover_dl_DriveCommand>& w, std::uint32_t id) {
    rover_dl_DriveCommand c{};
    c.command_id = id;
    return w.Write(c).ok();
  }

  DomainLease lease_;
  int to_child_[2] = {-1, -1}, to_parent_[2] = {-1, -1};
  pid_t child_ = -1;
};

// The reader exists; the writer is created and publishes at once, before discovery has matched
// the two. The command must still arrive (a volatile command topic lost it).
TEST_F(CommandDelivery, CommandWrittenRightAfterTheWriterIsCreatedArrives) {
  ForkWriter([this](Writer<rover_dl_DriveCommand>& w) { return AwaitParent() && Send(w, 7); });
  auto p = Participant::Create(lease_.domain());
  ASSERT_TRUE(p.ok());
  auto r = Reader<rover_dl_DriveCommand>::Create(*p, "dl/drive_command");
  ASSERT_TRUE(r.ok());
  SignalChild();
  std::vector<std::uint32_t> got;
  EXPECT_TRUE(testing::WaitFor([&] {
    for (auto& s : r->Take()) got.push_back(s->command_id);
    return !got.empty();
  })) << "the first command was lost to discovery";
  EXPECT_EQ(got, (std::vector<std::uint32_t>{7}));
}

// A reader that joins after a command was written (a restarted service) must not execute it:
// only commands written after the reader was created reach it.
TEST_F(CommandDelivery, LateJoiningReaderDoesNotGetCommandsOlderThanItself) {
  ForkWriter([this](Writer<rover_dl_DriveCommand>& w) {
    if (!Send(w, 1) || !SignalParent()) return false;
    if (!testing::WaitFor([&] { return w.MatchedReaders() > 0; })) return false;
    return Send(w, 2);
  });
  AwaitChild();  // command 1 is written
  auto p = Participant::Create(lease_.domain());
  ASSERT_TRUE(p.ok());
  auto r = Reader<rover_dl_DriveCommand>::Create(*p, "dl/drive_command");
  ASSERT_TRUE(r.ok());
  std::vector<std::uint32_t> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& s : r->Take()) got.push_back(s->command_id);
    return std::find(got.begin(), got.end(), 2u) != got.end();
  }));
  EXPECT_EQ(got, (std::vector<std::uint32_t>{2})) << "a stale command reached a late joiner";
}

}  // namespace
}  // namespace rover::dds
