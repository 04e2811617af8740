#include "rover/runtime/fault_control.hpp"

#include <thread>

#include "rover/base/log.hpp"

namespace rover::faults {

namespace {

rover_sys_FaultEventKind ToIdl(FaultRecord::Event e) {
  switch (e) {
    case FaultRecord::Event::kAdded: return rover_sys_FAULT_EVENT_ADDED;
    case FaultRecord::Event::kStarted: return rover_sys_FAULT_EVENT_STARTED;
    case FaultRecord::Event::kCount: return rover_sys_FAULT_EVENT_COUNT;
    case FaultRecord::Event::kEnded: return rover_sys_FAULT_EVENT_ENDED;
    case FaultRecord::Event::kRemoved: return rover_sys_FAULT_EVENT_REMOVED;
    case FaultRecord::Event::kListed: return rover_sys_FAULT_EVENT_LISTED;
    case FaultRecord::Event::kRejected: return rover_sys_FAULT_EVENT_REJECTED;
  }
  return rover_sys_FAULT_EVENT_REJECTED;
}

}  // namespace

void ToIdl(const FaultRecord& r, rover_sys_FaultEvent* e) {
  e->fault_id = r.fault_id;
  e->event = ToIdl(r.event);
  e->kind = faults::ToIdl(r.kind);
  dds::CopyString(e->service, r.service);
  dds::CopyString(e->topic, r.topic);
  e->samples_seen = r.seen;
  e->samples_hit = r.hit;
  e->start_ns = r.start.ns;
  e->end_ns = r.end ? r.end->ns : 0;
  dds::CopyString(e->detail, r.detail);
}

FaultRecord FromIdl(const rover_sys_FaultEvent& e) {
  FaultRecord r;
  const int ev = e.event;
  r.event = ev >= rover_sys_FAULT_EVENT_ADDED && ev <= rover_sys_FAULT_EVENT_REJECTED
                ? static_cast<FaultRecord::Event>(ev)
                : FaultRecord::Event::kRejected;
  r.fault_id = e.fault_id;
  const int k = e.kind;
  r.kind = k >= rover_sys_FAULT_DROP && k <= rover_sys_FAULT_PARTITION ? static_cast<FaultKind>(k)
                                                                       : FaultKind::kDrop;
  r.service = e.service;
  r.topic = e.topic;
  r.seen = e.samples_seen;
  r.hit = e.samples_hit;
  r.start = Time{e.start_ns};
  if (e.end_ns != 0) r.end = Time{e.end_ns};
  r.at = Time{e.header.stamp_ns};
  r.detail = e.detail;
  return r;
}

// ---- FaultAgent --------------------------------------------------------------------------------

FaultAgent::FaultAgent(const Clock& clock, Options options)
    : clock_(&clock),
      options_(std::move(options)),
      engine_(FaultEngine::Options{options_.service, &clock, options_.epoch, options_.report_period}) {}

void FaultAgent::UseClock(const Clock& clock, Time epoch) {
  clock_ = &clock;
  engine_.UseClock(clock, epoch);
}

std::unique_ptr<FaultAgent> FaultAgent::Install(const Clock& clock, Options options) {
  std::unique_ptr<FaultAgent> agent(new FaultAgent(clock, std::move(options)));
  agent->engine_.Install();
  return agent;
}

FaultAgent::~FaultAgent() { engine_.SetRecordSink(nullptr); }

Status FaultAgent::Attach(const dds::Participant& participant, Executor& executor) {
  auto w = dds::Writer<rover_sys_FaultEvent>::Create(participant, "sys/fault_event");
  if (!w.ok()) return w.status();
  events_ = std::move(*w);
  engine_.SetRecordSink([this](const FaultRecord& r) { Publish(r); });
  auto r = dds::Reader<rover_sys_FaultControl>::Create(participant, "sys/fault_control");
  if (!r.ok()) return r.status();
  control_ = std::make_unique<dds::Reader<rover_sys_FaultControl>>(std::move(*r));
  ROVER_RETURN_IF_ERROR(executor.Subscribe<rover_sys_FaultControl>(
      *control_, [this](const dds::Sample<rover_sys_FaultControl>& s) { OnControl(s.data()); },
      /*always=*/true));
  for (const auto& spec : options_.initial) ROVER_RETURN_IF_ERROR(engine_.Add(spec));
  return Status::Ok();
}

void FaultAgent::Publish(const FaultRecord& r) {
  rover_sys_FaultEvent e{};
  e.header.stamp_ns = clock_->Now().ns;
  e.header.seq = ++seq_;
  ToIdl(r, &e);
  (void)events_.Write(e);
  log::Write(r.event == FaultRecord::Event::kCount || r.event == FaultRecord::Event::kListed
                 ? log::Level::kDebug
                 : log::Level::kInfo,
             "fault", {{"event", FaultEventName(r.event)}, {"id", r.fault_id}, {"seen", r.seen},
                       {"hit", r.hit}, {"detail", r.detail}});
}

void FaultAgent::Reject(std::uint32_t id, rover_sys_FaultKind kind, const std::string& why) {
  FaultRecord r;
  r.event = FaultRecord::Event::kRejected;
  r.fault_id = id;
  const int k = kind;
  r.kind = k >= rover_sys_FAULT_DROP && k <= rover_sys_FAULT_PARTITION ? static_cast<FaultKind>(k)
                                                                       : FaultKind::kDrop;
  r.service = options_.service;
  r.at = clock_->Now();
  r.detail = why;
  log::Warn("fault control rejected", {{"id", id}, {"error", why}});
  Publish(r);
}

void FaultAgent::OnControl(const rover_sys_FaultControl& m) {
  switch (m.action) {
    case rover_sys_FAULT_ACTION_ADD: {
      auto spec = FromControl(m);
      Status s = spec.ok() ? engine_.Add(*spec) : spec.status();
      if (!s.ok()) Reject(m.fault_id, m.kind, s.message());
      break;
    }
    case rover_sys_FAULT_ACTION_REMOVE:
      if (!engine_.Remove(m.fault_id)) {
        Reject(m.fault_id, m.kind, "no fault " + std::to_string(m.fault_id) + " in " + options_.service);
      }
      break;
    case rover_sys_FAULT_ACTION_CLEAR:
      engine_.Clear();
      break;
    case rover_sys_FAULT_ACTION_LIST:
      for (const FaultStatus& st : engine_.List()) {
        FaultRecord r;
        r.event = FaultRecord::Event::kListed;
        r.fault_id = st.spec.id;
        r.kind = st.spec.kind;
        r.service = options_.service;
        r.topic = st.spec.topic;
        r.seen = st.seen;
        r.hit = st.hit;
        r.start = st.start;
        r.end = st.end;
        r.at = clock_->Now();
        r.detail = std::string(FaultStateName(st.state)) + ": " + st.spec.Describe();
        if (!GlobMatch(st.spec.service, options_.service)) r.detail += " (not for this service)";
        Publish(r);
      }
      break;
    default:
      Reject(m.fault_id, m.kind, "unknown fault action " + std::to_string(m.action));
  }
}

// ---- FaultClient -------------------------------------------------------------------------------

Result<FaultClient> FaultClient::Create(const dds::Participant& participant) {
  FaultClient c;
  auto w = dds::Writer<rover_sys_FaultControl>::Create(participant, "sys/fault_control");
  if (!w.ok()) return w.status();
  auto r = dds::Reader<rover_sys_FaultEvent>::Create(participant, "sys/fault_event");
  if (!r.ok()) return r.status();
  c.control_ = std::move(*w);
  c.events_ = std::move(*r);
  return c;
}

Status FaultClient::WaitForServices(int services, Duration timeout) {
  const Time end = MonotonicNow() + timeout;
  while (control_.MatchedReaders() < services || events_.MatchedWriters() < services) {
    if (MonotonicNow() >= end) {
      return Timeout("fault control: " + std::to_string(control_.MatchedReaders()) + " of " +
                     std::to_string(services) + " services listening after " +
                     std::to_string(ToSeconds(timeout)) + " s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return Status::Ok();
}

Status FaultClient::Send(rover_sys_FaultControl& m) {
  m.header.stamp_ns = WallNow().ns;
  m.header.seq = ++seq_;
  return control_.Write(m);
}

Status FaultClient::Add(const FaultSpec& spec) {
  if (spec.id == 0) return InvalidArgument("fault add: the fault needs an id > 0");
  ROVER_RETURN_IF_ERROR(spec.Validate());
  rover_sys_FaultControl m{};
  ToControl(spec, &m);
  return Send(m);
}

Status FaultClient::Remove(std::uint32_t id) {
  rover_sys_FaultControl m{};
  m.action = rover_sys_FAULT_ACTION_REMOVE;
  m.fault_id = id;
  return Send(m);
}

Status FaultClient::Clear() {
  rover_sys_FaultControl m{};
  m.action = rover_sys_FAULT_ACTION_CLEAR;
  return Send(m);
}

std::vector<FaultRecord> FaultClient::List(Duration collect) {
  (void)TakeRecords();  // older records are not answers
  rover_sys_FaultControl m{};
  m.action = rover_sys_FAULT_ACTION_LIST;
  std::vector<FaultRecord> out;
  if (!Send(m).ok()) return out;
  const Time end = MonotonicNow() + collect;
  while (MonotonicNow() < end) {
    for (auto& r : TakeRecords()) {
      if (r.event == FaultRecord::Event::kListed) out.push_back(std::move(r));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return out;
}

std::vector<FaultRecord> FaultClient::TakeRecords() {
  std::vector<FaultRecord> out;
  events_.TakeEach([&](const dds::Sample<rover_sys_FaultEvent>& s) { out.push_back(FromIdl(s.data())); });
  return out;
}

}  // namespace rover::faults
