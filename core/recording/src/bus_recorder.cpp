#include "rover/recording/bus_recorder.hpp"

#include <time.h>

#include <filesystem>

#include "rover/base/clock.hpp"
#include "rover/runtime/topic_catalog.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::recording {
namespace {

constexpr dds_attach_t kStopToken = -1;

Result<dds::QosProfile> ProfileFor(const dds::TopicInfo& t,
                                   const std::map<std::string, std::string>& overrides) {
  const auto it = overrides.find(std::string(t.name));
  if (it == overrides.end()) return t.profile;
  auto p = dds::ParseQosProfile(it->second);
  if (!p.ok()) return p.status().WithPrefix("QoS override of " + it->first);
  return *p;
}

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace

std::vector<CatalogTopic> CatalogTopics() {
  std::vector<CatalogTopic> out;
  for (const auto& t : dds::TopicCatalog()) out.push_back({std::string(t.name), std::string(t.type_name)});
  return out;
}

Result<std::unique_ptr<BusRecorder>> BusRecorder::Create(const dds::Participant& participant,
                                                         BusRecorderOptions options) {
  ROVER_RETURN_IF_ERROR(options.record.Validate());
  if (options.record.path.empty()) return InvalidArgument("the recording needs a file name");
  // What to read, checked before the file is made. The clock first, so that every pass reads it
  // before the samples it stamps.
  struct Wanted {
    const dds::TopicInfo* info;
    const dds_topic_descriptor_t* descriptor;
    dds::QosProfile profile;
    bool recorded;
  };
  std::vector<Wanted> wanted;
  bool any_recorded = false;
  for (const auto& t : dds::TopicCatalog()) {
    const bool is_clock = t.name == kClockTopic;
    const bool recorded = options.record.topics.Selects(t.name);
    if (!recorded && !(is_clock && options.clock == LogClock::Mode::kSim)) continue;
    const dds_topic_descriptor_t* desc = dds::DescriptorForType(t.type_name);
    if (desc == nullptr) {
      return Internal("catalog topic '" + std::string(t.name) + "' has type " +
                      std::string(t.type_name) + ", which has no topic descriptor in this build");
    }
    ROVER_ASSIGN_OR_RETURN(const dds::QosProfile profile, ProfileFor(t, options.qos_overrides));
    const Wanted w{&t, desc, profile, recorded};
    if (is_clock) wanted.insert(wanted.begin(), w);
    else wanted.push_back(w);
    any_recorded = any_recorded || recorded;
  }
  if (!any_recorded) {
    return InvalidArgument("topics " + options.record.topics.Describe() +
                           " select no topic of the catalog");
  }

  std::unique_ptr<BusRecorder> r(new BusRecorder(participant, std::move(options)));
  const BusRecorderOptions& o = r->options_;
  ROVER_ASSIGN_OR_RETURN(r->session_,
                         RecordingSession::Create(o.record.path, o.record.WriterOptions()));
  auto setup = [&]() -> Status {
    ROVER_ASSIGN_OR_RETURN(r->waitset_, dds::WaitSet::Create(participant));
    ROVER_ASSIGN_OR_RETURN(r->stop_guard_, dds::GuardCondition::Create(participant));
    ROVER_RETURN_IF_ERROR(r->waitset_.Attach(r->stop_guard_.handle(), kStopToken));
    for (const Wanted& w : wanted) {
      const std::string name(w.info->name);
      Input in;
      in.recorded = w.recorded;
      if (w.recorded) {
        ROVER_ASSIGN_OR_RETURN(
            in.topic, r->session_->AddTopic(name, std::string(w.info->type_name),
                                            {{"qos_profile", dds::QosProfileName(w.profile)}}));
      }
      auto reader = dds::RawReader::Create(participant, name, w.descriptor, w.profile);
      if (!reader.ok()) return reader.status().WithPrefix("recording " + name);
      in.reader = std::move(*reader);
      ROVER_RETURN_IF_ERROR(
          r->waitset_.Attach(in.reader.handle(), static_cast<dds_attach_t>(r->inputs_.size())));
      if (name == kClockTopic) r->has_clock_input_ = true;
      r->inputs_.push_back(std::move(in));
    }
    return Status::Ok();
  };
  if (const Status s = setup(); !s.ok()) {
    // Not a recording: leave no file behind.
    (void)r->session_->Close();
    std::error_code ec;
    if (std::filesystem::is_regular_file(o.record.path, ec)) std::filesystem::remove(o.record.path, ec);
    r->stopped_ = true;
    return s;
  }
  return r;
}

BusRecorder::~BusRecorder() { (void)Stop(); }

Status BusRecorder::Start() {
  std::lock_guard<std::mutex> lock(mu_);
  if (started_) return FailedPrecondition("the recorder was started already");
  started_ = true;
  start_mono_ns_ = MonotonicNow().ns;
  thread_ = std::thread([this] { Run(); });
  return Status::Ok();
}

void BusRecorder::Run() {
  const auto timeout_ns = static_cast<std::int64_t>(options_.poll_s * 1e9);
  std::int64_t last_lost_check = MonotonicNow().ns;
  while (!stop_.load()) {
    (void)waitset_.Wait(timeout_ns);
    std::lock_guard<std::mutex> lock(mu_);
    if (!failure_.ok()) break;
    PumpLocked();
    if (MonotonicNow().ns - last_lost_check > 1'000'000'000) {
      CountLostLocked();
      last_lost_check = MonotonicNow().ns;
    }
  }
  std::lock_guard<std::mutex> lock(mu_);
  if (failure_.ok()) {
    PumpLocked();  // what arrived before Stop
    CountLostLocked();
  }
  cpu_s_ = ThreadCpuSeconds();
}

void BusRecorder::PumpLocked() {
  for (auto& in : inputs_) {
    const bool is_clock = has_clock_input_ && &in == &inputs_.front();
    in.reader.TakeEach([&](std::span<const std::uint8_t> bytes, const dds_sample_info_t&) {
      if (!failure_.ok()) return;
      if (is_clock) clock_.OnClockSample(bytes);
      if (!in.recorded) return;
      const Status s = session_->Write(in.topic, clock_.Now(), bytes);
      if (!s.ok()) failure_ = s;
    });
    if (!failure_.ok()) {
      // Stop taking: the readers go, the error stays (the file keeps no footer).
      for (auto& i : inputs_) i.reader = dds::RawReader();
      return;
    }
  }
}

void BusRecorder::CountLostLocked() {
  for (auto& in : inputs_) {
    if (!in.recorded || !in.reader.valid()) continue;
    const std::uint64_t lost = in.reader.LostSamples();
    if (lost > in.lost_seen) session_->CountLost(in.topic, lost - in.lost_seen);
    in.lost_seen = lost;
  }
}

RecordingReport BusRecorder::Stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopped_) return report_;
    stopped_ = true;
    if (!session_) return report_;  // Create failed before the file was made
  }
  stop_.store(true);
  if (stop_guard_.valid()) stop_guard_.Trigger();
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mu_);
  mcap::StringMap meta = options_.metadata;
  meta["clock"] = clock_.mode() == LogClock::Mode::kSim ? "sim" : "wall";
  meta["topics"] = options_.record.topics.Describe();
  const Status closed = session_->Close(meta);
  report_.path = options_.record.path;
  report_.status = failure_.ok() ? closed : failure_;
  report_.stats = session_->stats();
  report_.wall_s = started_ ? static_cast<double>(MonotonicNow().ns - start_mono_ns_) * 1e-9 : 0;
  report_.cpu_s = cpu_s_;
  for (auto& in : inputs_) in.reader = dds::RawReader();
  return report_;
}

Status BusRecorder::health() const {
  std::lock_guard<std::mutex> lock(mu_);
  return failure_;
}

SessionStats BusRecorder::Snapshot() const {
  std::lock_guard<std::mutex> lock(mu_);
  return session_->stats();
}

std::int64_t BusRecorder::RunClockNs() const {
  std::lock_guard<std::mutex> lock(mu_);
  return clock_.Now();
}

bool BusRecorder::clock_valid() const {
  std::lock_guard<std::mutex> lock(mu_);
  return clock_.mode() == LogClock::Mode::kWall || clock_.heard_clock();
}

std::vector<std::string> BusRecorder::topics() const {
  std::lock_guard<std::mutex> lock(mu_);
  std::vector<std::string> out;
  for (const auto& t : session_->stats().topics) out.push_back(t.topic);
  return out;
}

}  // namespace rover::recording
