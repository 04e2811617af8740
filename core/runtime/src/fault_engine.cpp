#include "rover/runtime/fault_engine.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>

#include "rover/runtime/lockstep.hpp"
#include "rover/runtime/topic_catalog.hpp"
#include "rover/runtime/type_layout.hpp"

namespace rover::faults {

const char* FaultStateName(FaultState s) {
  switch (s) {
    case FaultState::kPending: return "pending";
    case FaultState::kActive: return "active";
    case FaultState::kEnded: return "ended";
  }
  return "?";
}

const char* FaultEventName(FaultRecord::Event e) {
  switch (e) {
    case FaultRecord::Event::kAdded: return "added";
    case FaultRecord::Event::kStarted: return "started";
    case FaultRecord::Event::kCount: return "count";
    case FaultRecord::Event::kEnded: return "ended";
    case FaultRecord::Event::kRemoved: return "removed";
    case FaultRecord::Event::kListed: return "listed";
    case FaultRecord::Event::kRejected: return "rejected";
  }
  return "?";
}

namespace internal {
namespace {

constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
constexpr std::size_t kHistory = 64;

std::uint64_t Mix(std::uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t HashName(std::string_view s) {  // FNV-1a
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

// The random numbers of one sample for one fault: a pure function of the key.
class SampleRng {
 public:
  SampleRng(std::uint64_t seed, std::uint64_t topic_hash, dds::Direction dir, std::uint64_t n)
      : state_(Mix(Mix(Mix(seed) ^ topic_hash) ^ (n * 2 + (dir == dds::Direction::kRead ? 1 : 0)))) {}
  std::uint64_t Next() {
    state_ += 0x9e3779b97f4a7c15ull;
    return Mix(state_);
  }
  /// [0, 1)
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  double Normal() {  // Box-Muller
    const double u1 = 1.0 - Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  std::uint64_t Below(std::uint64_t n) { return n == 0 ? 0 : Next() % n; }

 private:
  std::uint64_t state_;
};

Duration Draw(const DelaySpec& d, SampleRng& rng) {
  double s = d.a_s;
  switch (d.distribution) {
    case DelayDistribution::kFixed: break;
    case DelayDistribution::kUniform: s = d.a_s + (d.b_s - d.a_s) * rng.Uniform(); break;
    case DelayDistribution::kNormal: s = d.a_s + d.b_s * rng.Normal(); break;
    case DelayDistribution::kExponential: s = -d.a_s * std::log(1.0 - rng.Uniform()); break;
  }
  return Seconds(std::max(0.0, s));
}

// ---- changing one leaf -------------------------------------------------------------------------

std::int64_t IntMin(std::uint32_t size) {
  return size >= 8 ? std::numeric_limits<std::int64_t>::min() : -(std::int64_t{1} << (size * 8 - 1));
}
std::int64_t IntMax(std::uint32_t size) {
  return size >= 8 ? std::numeric_limits<std::int64_t>::max() : (std::int64_t{1} << (size * 8 - 1)) - 1;
}
std::uint64_t UIntMax(std::uint32_t size) {
  return size >= 8 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t{1} << (size * 8)) - 1;
}

std::uint64_t ReadBits(const void* p, std::uint32_t size) {
  std::uint64_t v = 0;
  std::memcpy(&v, p, size);  // little endian host: low bytes first
  return v;
}
void WriteBits(void* p, std::uint32_t size, std::uint64_t v) { std::memcpy(p, &v, size); }

std::int64_t ReadSigned(const void* p, std::uint32_t size) {
  const std::uint64_t v = ReadBits(p, size);
  if (size >= 8) return static_cast<std::int64_t>(v);
  const std::uint64_t sign = std::uint64_t{1} << (size * 8 - 1);
  return static_cast<std::int64_t>((v ^ sign) - sign);  // sign-extend
}

double ReadFloat(const void* p, std::uint32_t size) {
  if (size == 4) {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  double d;
  std::memcpy(&d, p, 8);
  return d;
}
void WriteFloat(void* p, std::uint32_t size, double v) {
  if (size == 4) {
    const float f = static_cast<float>(v);
    std::memcpy(p, &f, 4);
  } else {
    std::memcpy(p, &v, 8);
  }
}

// Adds `delta` to a number, rounding and saturating integers to their type.
void AddTo(void* p, const dds::FieldNode& leaf, double delta) {
  using dds::FieldKind;
  if (leaf.kind == FieldKind::kFloat) {
    WriteFloat(p, leaf.size, ReadFloat(p, leaf.size) + delta);
    return;
  }
  const std::int64_t d = std::llround(std::clamp(delta, -9.0e18, 9.0e18));
  if (leaf.kind == FieldKind::kInt) {
    const std::int64_t lo = IntMin(leaf.size), hi = IntMax(leaf.size);
    std::int64_t v = ReadSigned(p, leaf.size);
    if (d > 0 && v > hi - d) {
      v = hi;
    } else if (d < 0 && v < lo - d) {
      v = lo;
    } else {
      v += d;
    }
    WriteBits(p, leaf.size, static_cast<std::uint64_t>(v));
  } else if (leaf.kind == FieldKind::kUInt) {
    const std::uint64_t hi = UIntMax(leaf.size);
    std::uint64_t v = ReadBits(p, leaf.size);
    const std::uint64_t mag = static_cast<std::uint64_t>(d < 0 ? -d : d);
    if (d >= 0) {
      v = v > hi - mag ? hi : v + mag;
    } else {
      v = v < mag ? 0 : v - mag;
    }
    WriteBits(p, leaf.size, v);
  }
}

void FlipBits(void* p, std::uint32_t size, std::uint32_t bits, SampleRng& rng) {
  const std::uint32_t width = size * 8;
  std::uint64_t mask = 0;
  for (std::uint32_t i = 0, n = std::min(bits, width); i < n;) {
    const std::uint64_t bit = std::uint64_t{1} << rng.Below(width);
    if ((mask & bit) == 0) {
      mask |= bit;
      ++i;
    }
  }
  WriteBits(p, size, ReadBits(p, size) ^ mask);
}

void FlipCharBit(char* s, std::size_t capacity, SampleRng& rng) {
  if (s == nullptr) return;
  const std::size_t len = strnlen(s, capacity);
  if (len == 0) return;
  char& c = s[rng.Below(len)];
  c = static_cast<char>(c ^ (1 << rng.Below(7)));
  if (c == '\0') c = '?';  // keep the string's length
}

void Corrupt(void* p, const dds::FieldNode& leaf, const FaultSpec& s, SampleRng& rng) {
  using dds::FieldKind;
  switch (s.corruption) {
    case Corruption::kNan:
      WriteFloat(p, leaf.size, std::numeric_limits<double>::quiet_NaN());
      break;
    case Corruption::kPosInf:
      WriteFloat(p, leaf.size, std::numeric_limits<double>::infinity());
      break;
    case Corruption::kNegInf:
      WriteFloat(p, leaf.size, -std::numeric_limits<double>::infinity());
      break;
    case Corruption::kValue:
      if (leaf.kind == FieldKind::kFloat) {
        WriteFloat(p, leaf.size, s.value);
      } else if (leaf.kind == FieldKind::kUInt) {
        WriteBits(p, leaf.size, static_cast<std::uint64_t>(s.value));
      } else {  // signed, enum, bool
        WriteBits(p, leaf.size, static_cast<std::uint64_t>(static_cast<std::int64_t>(s.value)));
      }
      break;
    case Corruption::kOutOfRange:
      if (leaf.kind == FieldKind::kFloat) {
        WriteFloat(p, leaf.size, leaf.size == 4 ? FLT_MAX : DBL_MAX);
      } else if (leaf.kind == FieldKind::kInt) {
        WriteBits(p, leaf.size, static_cast<std::uint64_t>(IntMax(leaf.size)));
      } else if (leaf.kind == FieldKind::kUInt) {
        WriteBits(p, leaf.size, UIntMax(leaf.size));
      } else if (leaf.kind == FieldKind::kEnum) {
        WriteBits(p, leaf.size, std::uint64_t{leaf.enum_max} + 1);
      }
      break;
    case Corruption::kBitFlip:
      if (leaf.kind == FieldKind::kBool) {
        auto* b = static_cast<unsigned char*>(p);
        *b = *b ? 0 : 1;
      } else if (leaf.kind == FieldKind::kBoundedString) {
        FlipCharBit(static_cast<char*>(p), leaf.capacity, rng);
      } else if (leaf.kind == FieldKind::kString) {
        FlipCharBit(*static_cast<char**>(p), std::numeric_limits<std::size_t>::max(), rng);
      } else {
        FlipBits(p, leaf.size, s.bits, rng);
      }
      break;
  }
}

void ChangeField(void* sample, const dds::FieldSelector& sel, const FaultSpec& s, SampleRng& rng) {
  sel.ForEachLeaf(sample, [&](void* p, const dds::FieldNode& leaf) {
    switch (s.kind) {
      case FaultKind::kNoise: AddTo(p, leaf, s.sigma * rng.Normal()); break;
      case FaultKind::kBias: AddTo(p, leaf, s.value); break;
      case FaultKind::kCorrupt: Corrupt(p, leaf, s, rng); break;
      default: break;
    }
  });
}

bool SideMatches(Side side, dds::Direction d) {
  return side == Side::kBoth || (side == Side::kWriter) == (d == dds::Direction::kWrite);
}

}  // namespace

// One fault added to this process.
struct Fault {
  FaultSpec spec;
  Time start{0};
  Time end{kNever};
  bool applies = false;  // the spec's service glob matches this process
  std::atomic<std::uint64_t> seen{0};
  std::atomic<std::uint64_t> hit{0};
  // Record state; guarded by EngineCore::mu_.
  bool started = false;
  bool ended = false;
  Time last_report{0};
  std::uint64_t reported_hit = 0;
  std::uint64_t endpoints_checked = 0;  // EngineCore::seams_made_ when last looked for one

  bool Active(Time now) const { return now >= start && now < end; }
  std::optional<Time> End() const {
    return end.ns == kNever ? std::nullopt : std::optional<Time>(end);
  }
};

struct FaultSet {
  std::vector<std::shared_ptr<Fault>> faults;  // by id
};

class EndpointSeam;

class EngineCore final : public dds::SeamPump, public std::enable_shared_from_this<EngineCore> {
 public:
  explicit EngineCore(FaultEngine::Options o)
      : options_(std::move(o)), clock_(options_.clock), set_(std::make_shared<FaultSet>()) {}

  Time Now() const {
    const Clock* c = clock_.load(std::memory_order_acquire);
    return c != nullptr ? c->Now() : Time{0};
  }
  std::uint64_t generation() const { return generation_.load(std::memory_order_acquire); }
  const std::atomic<std::uint64_t>& generation_counter() const { return generation_; }
  std::shared_ptr<const FaultSet> Snapshot(std::uint64_t* gen) const {
    std::lock_guard lock(mu_);
    *gen = generation_.load(std::memory_order_relaxed);
    return set_;
  }
  void NoteDue(Time t) {
    std::int64_t cur = next_due_.load(std::memory_order_relaxed);
    while (t.ns < cur && !next_due_.compare_exchange_weak(cur, t.ns)) {
    }
  }
  const FaultEngine::Options& options() const { return options_; }

  std::shared_ptr<dds::TopicSeam> MakeSeam(const std::string& topic, dds::Direction d);
  Status Add(const FaultSpec& spec);
  void UseClock(const Clock* clock, Time epoch);
  bool Remove(std::uint32_t id);
  void Clear();
  std::vector<FaultStatus> List() const;
  void Pump() override;
  std::optional<Time> NextDue() const override {
    const std::int64_t t = next_due_.load(std::memory_order_acquire);
    return t == kNever ? std::nullopt : std::optional<Time>(Time{t});
  }
  void SetSink(FaultEngine::RecordSink sink) {
    std::lock_guard lock(sink_mu_);
    sink_ = std::move(sink);
  }
  void Shutdown() {
    Clear();
    clock_.store(nullptr, std::memory_order_release);
  }

 private:
  FaultRecord Record(FaultRecord::Event e, const Fault& f, Time now) const {
    FaultRecord r;
    r.event = e;
    r.fault_id = f.spec.id;
    r.kind = f.spec.kind;
    r.service = options_.service;
    r.topic = f.spec.topic;
    r.seen = f.seen.load();
    r.hit = f.hit.load();
    r.start = f.start;
    r.end = f.End();
    r.at = now;
    r.detail = f.spec.Describe();
    return r;
  }
  void Emit(const std::vector<FaultRecord>& records) {
    if (records.empty()) return;
    FaultEngine::RecordSink sink;
    {
      std::lock_guard lock(sink_mu_);
      sink = sink_;
    }
    if (!sink) return;
    for (const auto& r : records) sink(r);
  }
  // Ends `f` (removed or replaced): its final record. Guarded by mu_.
  void Retire(const std::shared_ptr<Fault>& f, Time now, std::vector<FaultRecord>* out) {
    if (f->started && !f->ended) {
      f->ended = true;
      out->push_back(Record(FaultRecord::Event::kEnded, *f, now));
    } else if (!f->started) {
      f->ended = true;
      out->push_back(Record(FaultRecord::Event::kRemoved, *f, now));
    }
    Remember(f);
  }
  void Remember(const std::shared_ptr<Fault>& f) {
    history_.push_back(f);
    if (history_.size() > kHistory) history_.erase(history_.begin());
  }
  void Publish(std::vector<std::shared_ptr<Fault>> faults) {  // guarded by mu_
    auto next = std::make_shared<FaultSet>();
    next->faults = std::move(faults);
    set_ = std::move(next);
    generation_.fetch_add(1, std::memory_order_acq_rel);
  }
  bool HasEndpoint(const Fault& f, const std::vector<std::shared_ptr<EndpointSeam>>& seams) const;

  FaultEngine::Options options_;
  std::atomic<const Clock*> clock_;
  std::atomic<std::uint64_t> generation_{1};
  std::atomic<std::int64_t> next_due_{kNever};
  mutable std::mutex mu_;
  std::shared_ptr<const FaultSet> set_;
  std::vector<std::shared_ptr<Fault>> history_;
  std::vector<std::weak_ptr<EndpointSeam>> seams_;
  std::uint64_t seams_made_ = 0;  // guarded by mu_
  std::mutex sink_mu_;
  FaultEngine::RecordSink sink_;
};

// The seam of one endpoint.
class EndpointSeam final : public dds::TopicSeam {
 public:
  EndpointSeam(std::shared_ptr<EngineCore> core, std::string topic, dds::Direction dir,
               std::shared_ptr<const dds::TypeLayout> layout)
      : core_(std::move(core)),
        topic_(std::move(topic)),
        topic_hash_(HashName(topic_)),
        dir_(dir),
        layout_(std::move(layout)) {
    generation_ = &core_->generation_counter();
  }

  const std::string& topic() const { return topic_; }
  dds::Direction direction() const { return dir_; }
  bool Matches(const Fault& f) const {
    return f.applies && SideMatches(f.spec.side, dir_) && TopicMatches(f.spec.topic, topic_);
  }

  dds_return_t OnWrite(dds_entity_t writer, const void* sample, const dds_topic_descriptor_t*) override {
    if (Idle()) return dds::lockstep::Write(writer, sample);
    std::lock_guard lock(mu_);
    writer_ = writer;
    RefreshIfStale();
    if (bindings_.empty()) return dds::lockstep::Write(writer, sample);
    const Time now = core_->Now();
    dds_return_t rc = DDS_RETCODE_OK;
    Process(sample, dds_sample_info_t{}, now, &scratch_);
    for (const Emission& e : scratch_) {
      const dds_return_t r = dds::lockstep::Write(writer, e.sample);
      if (r < 0) rc = r;
    }
    scratch_.clear();  // keeps its capacity: no allocation per sample
    return rc;
  }

  void OnRead(void* sample, const dds_sample_info_t& info, const dds_topic_descriptor_t*,
              dds::SampleSink& out) override {
    if (Idle()) {
      out.Deliver(sample, info);
      return;
    }
    std::vector<Emission> now_list;
    {
      std::lock_guard lock(mu_);
      RefreshIfStale();
      if (bindings_.empty()) {
        now_list.push_back({sample, nullptr, Time{0}, info});
      } else {
        Process(sample, info, core_->Now(), &now_list);
      }
    }
    for (const Emission& e : now_list) out.Deliver(e.sample, e.info);  // copies live in now_list
  }

  bool HasDue() const override {
    const std::int64_t due = held_due_ns_.load(std::memory_order_acquire);
    return due != kNever && due <= core_->Now().ns;
  }

  void ReleaseDue(dds::SampleSink& out) override {
    if (held_due_ns_.load(std::memory_order_acquire) == kNever) return;
    std::vector<Emission> due;
    {
      std::lock_guard lock(mu_);
      due = PopDue(core_->Now());
    }
    for (const Emission& e : due) out.Deliver(e.sample, e.info);
  }

  // Writer side: writes the held samples that are due.
  void FlushDue(Time now) {
    if (dir_ != dds::Direction::kWrite || held_due_ns_.load(std::memory_order_acquire) > now.ns) return;
    std::lock_guard lock(mu_);
    for (const Emission& e : PopDue(now)) (void)dds::lockstep::Write(writer_, e.sample);
  }
  std::int64_t earliest() const { return held_due_ns_.load(std::memory_order_acquire); }

 private:
  struct Emission {
    const void* sample;
    std::shared_ptr<void> owner;  // keeps a copy alive (nullptr: the caller's or DDS's memory)
    Time due;
    dds_sample_info_t info;
    std::uint32_t held_by = 0;    // reorder: the fault holding it
  };
  struct Binding {
    std::shared_ptr<Fault> fault;
    std::uint64_t n = 0;  // samples this fault saw here while active
    std::optional<dds::FieldSelector> selector;
    std::shared_ptr<void> frozen;  // freeze: the sample repeated
    std::shared_ptr<void> last;    // freeze pending: the latest sample
  };

  std::shared_ptr<void> Clone(const void* p) const {
    std::shared_ptr<const dds::TypeLayout> layout = layout_;
    return std::shared_ptr<void>(layout_->Clone(p), [layout](void* q) { layout->Free(q); });
  }

  void RefreshIfStale() {
    const std::uint64_t want = core_->generation();
    if (state_.load(std::memory_order_relaxed) / 2 == want) return;
    std::uint64_t gen = 0;
    auto set = core_->Snapshot(&gen);
    std::vector<Binding> next;
    for (const auto& f : set->faults) {
      if (!Matches(*f)) continue;
      auto old = std::find_if(bindings_.begin(), bindings_.end(),
                              [&](const Binding& b) { return b.fault == f; });
      if (old != bindings_.end()) {
        next.push_back(std::move(*old));
        continue;
      }
      Binding b;
      b.fault = f;
      if (!f->spec.field.empty()) {
        auto sel = dds::FieldSelector::Resolve(*layout_, f->spec.field);
        if (!sel.ok()) continue;  // validated on Add; a mismatch means another type: skip
        b.selector = std::move(*sel);
      }
      next.push_back(std::move(b));
    }
    // Samples held by a reorder fault that no longer applies go on now.
    for (Emission& e : queue_) {
      if (e.held_by == 0) continue;
      const bool kept = std::any_of(next.begin(), next.end(), [&](const Binding& b) {
        return b.fault->spec.id == e.held_by;
      });
      if (!kept) {
        e.held_by = 0;
        e.due = Time{0};
      }
    }
    SortQueue();
    bindings_ = std::move(next);
    state_.store(gen * 2 + (bindings_.empty() ? 1 : 0), std::memory_order_release);
  }

  // Runs the sample through the active faults; queues what is due later and leaves in `out`
  // (empty on entry) what is due now.
  void Process(const void* sample, const dds_sample_info_t& info, Time now, std::vector<Emission>* out) {
    std::vector<Emission>& list = *out;
    list.push_back({sample, nullptr, now, info});
    for (Binding& b : bindings_) {
      Fault& f = *b.fault;
      const FaultSpec& s = f.spec;
      if (!f.Active(now)) {
        if (s.kind == FaultKind::kFreeze && now < f.start && !list.empty()) {
          b.last = Clone(list.front().sample);
        }
        continue;
      }
      f.seen.fetch_add(1, std::memory_order_relaxed);
      SampleRng rng(s.seed, topic_hash_, dir_, b.n++);
      const bool chosen = rng.Uniform() < s.probability;
      bool hit = false;
      switch (s.kind) {
        case FaultKind::kPartition:
          hit = !list.empty();
          list.clear();
          break;
        case FaultKind::kDrop:
          if (chosen && !list.empty()) {
            list.clear();
            hit = true;
          }
          break;
        case FaultKind::kFreeze: {
          if (list.empty()) break;
          if (!b.frozen) {
            b.frozen = b.last ? b.last : Clone(list.front().sample);
            const bool first_is_frozen = !b.last;
            b.last.reset();
            if (first_is_frozen) break;  // this sample is the frozen one: unchanged
          }
          for (Emission& e : list) {
            e.sample = b.frozen.get();
            e.owner = b.frozen;
          }
          hit = true;
          break;
        }
        case FaultKind::kDuplicate:
          if (chosen && !list.empty()) {
            const std::size_t n0 = list.size();
            for (std::size_t i = 0; i < n0; ++i) {
              for (std::uint32_t c = 0; c < s.copies; ++c) list.push_back(list[i]);
            }
            hit = true;
          }
          break;
        case FaultKind::kDelay:
          if (chosen && !list.empty()) {
            const Duration d = Draw(s.delay, rng);
            for (Emission& e : list) e.due = e.due + d;
            hit = true;
          }
          break;
        case FaultKind::kReorder: {
          auto held = std::find_if(queue_.begin(), queue_.end(),
                                   [&](const Emission& e) { return e.held_by == s.id; });
          if (held != queue_.end()) {  // the sample to swap with has come: release after it
            for (auto it = queue_.begin(); it != queue_.end();) {
              if (it->held_by == s.id) {
                it->held_by = 0;
                it->due = now;
                list.push_back(std::move(*it));
                it = queue_.erase(it);
              } else {
                ++it;
              }
            }
            UpdateEarliest();
          } else if (chosen && !list.empty()) {
            const Time deadline = now + Seconds(s.delay.a_s);
            for (Emission& e : list) {
              e.held_by = s.id;
              e.due = std::max(e.due, deadline);
              Queue(std::move(e));
            }
            list.clear();
            hit = true;
          }
          break;
        }
        case FaultKind::kCorrupt:
        case FaultKind::kNoise:
        case FaultKind::kBias:
          if (chosen && !list.empty() && b.selector) {
            ChangeAll(list, *b.selector, s, rng);
            hit = true;
          }
          break;
      }
      if (hit) f.hit.fetch_add(1, std::memory_order_relaxed);
    }
    // Keep what is due now in order; queue the rest.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (list[i].due <= now) {
        if (kept != i) list[kept] = std::move(list[i]);
        ++kept;
      } else {
        Queue(std::move(list[i]));
      }
    }
    list.erase(list.begin() + static_cast<std::ptrdiff_t>(kept), list.end());
  }

  // Changes the field once per distinct sample storage in `list`.
  void ChangeAll(std::vector<Emission>& list, const dds::FieldSelector& sel, const FaultSpec& s,
                 SampleRng& rng) {
    std::vector<std::pair<const void*, Emission>> done;
    for (Emission& e : list) {
      auto it = std::find_if(done.begin(), done.end(), [&](const auto& d) { return d.first == e.sample; });
      if (it != done.end()) {
        e.sample = it->second.sample;
        e.owner = it->second.owner;
        continue;
      }
      const void* original = e.sample;
      void* target = nullptr;
      if (dir_ == dds::Direction::kRead && !e.owner) {
        target = const_cast<void*>(e.sample);  // the reader's own (lent) sample: change in place
      } else {
        e.owner = Clone(e.sample);
        target = e.owner.get();
      }
      ChangeField(target, sel, s, rng);
      e.sample = target;
      done.emplace_back(original, e);
    }
  }

  void Queue(Emission e) {
    if (!e.owner) {
      e.owner = Clone(e.sample);
      e.sample = e.owner.get();
    }
    auto pos = std::upper_bound(queue_.begin(), queue_.end(), e.due,
                                [](Time t, const Emission& q) { return t < q.due; });
    queue_.insert(pos, std::move(e));
    UpdateEarliest();
  }
  void SortQueue() {
    std::stable_sort(queue_.begin(), queue_.end(),
                     [](const Emission& a, const Emission& b) { return a.due < b.due; });
    UpdateEarliest();
  }
  void UpdateEarliest() {
    const std::int64_t t = queue_.empty() ? kNever : queue_.front().due.ns;
    held_due_ns_.store(t, std::memory_order_release);
    if (t != kNever) core_->NoteDue(Time{t});
  }
  std::vector<Emission> PopDue(Time now) {
    std::vector<Emission> out;
    auto end = queue_.begin();
    while (end != queue_.end() && end->due <= now) ++end;
    out.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(end));
    queue_.erase(queue_.begin(), end);
    UpdateEarliest();
    return out;
  }

  std::shared_ptr<EngineCore> core_;
  std::string topic_;
  std::uint64_t topic_hash_;
  dds::Direction dir_;
  std::shared_ptr<const dds::TypeLayout> layout_;
  // state_ (TopicSeam): generation * 2 + (no fault matches); held_due_ns_: the queue's front.
  std::mutex mu_;
  dds_entity_t writer_ = 0;
  std::vector<Binding> bindings_;
  std::vector<Emission> queue_;    // held samples, by due time
  std::vector<Emission> scratch_;  // writer side: the samples of the current write
};

std::shared_ptr<dds::TopicSeam> EngineCore::MakeSeam(const std::string& topic, dds::Direction d) {
  if (IsFaultInfrastructure(topic)) return nullptr;
  const auto info = dds::FindTopic(topic);
  if (!info) return nullptr;
  auto layout = dds::TypeLayout::For(dds::DescriptorForType(info->type_name));
  if (!layout.ok()) return nullptr;
  auto seam = std::make_shared<EndpointSeam>(shared_from_this(), topic, d, *layout);
  std::lock_guard lock(mu_);
  seams_.erase(std::remove_if(seams_.begin(), seams_.end(), [](const auto& w) { return w.expired(); }),
               seams_.end());
  seams_.push_back(seam);
  ++seams_made_;
  return seam;
}

Status EngineCore::Add(const FaultSpec& spec) {
  ROVER_RETURN_IF_ERROR(spec.Validate());
  if (spec.id == 0) return InvalidArgument(spec.source + ": a fault needs an id > 0");
  auto f = std::make_shared<Fault>();
  f->spec = spec;
  const Time now = Now();
  const Time base = spec.start_mode == StartMode::kOnReceipt ? now : options_.epoch;
  f->start = base + Seconds(spec.start_s);
  if (spec.duration_s > 0) f->end = f->start + Seconds(spec.duration_s);
  f->applies = GlobMatch(spec.service, options_.service);
  std::vector<FaultRecord> records;
  {
    std::lock_guard lock(mu_);
    std::vector<std::shared_ptr<Fault>> faults;
    for (const auto& old : set_->faults) {
      if (old->spec.id == spec.id) {
        Retire(old, now, &records);
      } else {
        faults.push_back(old);
      }
    }
    auto pos = std::upper_bound(faults.begin(), faults.end(), spec.id,
                                [](std::uint32_t id, const auto& x) { return id < x->spec.id; });
    faults.insert(pos, f);
    Publish(std::move(faults));
    FaultRecord r = Record(FaultRecord::Event::kAdded, *f, now);
    if (!f->applies) r.detail += " (not for this service)";
    records.push_back(std::move(r));
  }
  Emit(records);
  return Status::Ok();
}

void EngineCore::UseClock(const Clock* clock, Time epoch) {
  std::lock_guard lock(mu_);
  const Time old_now = Now();
  clock_.store(clock, std::memory_order_release);
  options_.epoch = epoch;
  const Time now = Now();
  // Windows that have not opened yet move to the new clock: run-epoch faults count from the
  // new epoch, faults started on receipt keep the delay they had left.
  std::vector<std::shared_ptr<Fault>> faults;
  for (const auto& old : set_->faults) {
    if (old->started || old->ended) {
      faults.push_back(old);
      continue;
    }
    auto f = std::make_shared<Fault>();
    f->spec = old->spec;
    f->applies = old->applies;
    f->start = old->spec.start_mode == StartMode::kOnReceipt ? now + (old->start - old_now)
                                                             : epoch + Seconds(old->spec.start_s);
    if (old->spec.duration_s > 0) f->end = f->start + Seconds(old->spec.duration_s);
    faults.push_back(std::move(f));
  }
  Publish(std::move(faults));
}

bool EngineCore::Remove(std::uint32_t id) {
  std::vector<FaultRecord> records;
  bool found = false;
  {
    std::lock_guard lock(mu_);
    std::vector<std::shared_ptr<Fault>> faults;
    for (const auto& f : set_->faults) {
      if (f->spec.id == id) {
        found = true;
        Retire(f, Now(), &records);
      } else {
        faults.push_back(f);
      }
    }
    if (found) Publish(std::move(faults));
  }
  Emit(records);
  return found;
}

void EngineCore::Clear() {
  std::vector<FaultRecord> records;
  {
    std::lock_guard lock(mu_);
    if (set_->faults.empty()) return;
    for (const auto& f : set_->faults) Retire(f, Now(), &records);
    Publish({});
  }
  Emit(records);
}

std::vector<FaultStatus> EngineCore::List() const {
  const Time now = Now();
  std::lock_guard lock(mu_);
  std::vector<FaultStatus> out;
  auto add = [&](const Fault& f, bool ended) {
    FaultStatus st;
    st.spec = f.spec;
    st.start = f.start;
    st.end = f.End();
    st.state = ended || now >= f.end ? FaultState::kEnded
               : f.Active(now)       ? FaultState::kActive
                                     : FaultState::kPending;
    st.seen = f.seen.load();
    st.hit = f.hit.load();
    out.push_back(std::move(st));
  };
  for (const auto& f : set_->faults) add(*f, false);
  for (const auto& f : history_) add(*f, true);
  return out;
}

bool EngineCore::HasEndpoint(const Fault& f,
                             const std::vector<std::shared_ptr<EndpointSeam>>& seams) const {
  return std::any_of(seams.begin(), seams.end(), [&](const auto& s) { return s->Matches(f); });
}

void EngineCore::Pump() {
  const Time now = Now();
  std::vector<std::shared_ptr<EndpointSeam>> seams;
  std::uint64_t made = 0;  // seams_made_ for this snapshot
  {
    std::lock_guard lock(mu_);
    if (set_->faults.empty() && next_due_.load(std::memory_order_relaxed) == kNever) return;
    made = seams_made_;
    for (const auto& w : seams_) {
      if (auto s = w.lock()) seams.push_back(std::move(s));
    }
  }
  // Held samples: write the due ones, then recompute the earliest.
  std::int64_t earliest = kNever;
  for (const auto& s : seams) {
    s->FlushDue(now);
    earliest = std::min(earliest, s->earliest());
  }
  next_due_.store(earliest, std::memory_order_release);
  // Windows and records.
  std::vector<FaultRecord> records;
  {
    std::lock_guard lock(mu_);
    std::vector<std::shared_ptr<Fault>> keep;
    bool changed = false;
    for (const auto& f : set_->faults) {
      // Started in this service once it has a matching endpoint (looked for again only when
      // the endpoints change).
      if (f->applies && !f->started && f->Active(now) && f->endpoints_checked != made &&
          (f->endpoints_checked = made, HasEndpoint(*f, seams))) {
        f->started = true;
        f->last_report = now;
        records.push_back(Record(FaultRecord::Event::kStarted, *f, now));
      }
      if (now >= f->end) {  // the window closed: report and forget
        if (f->started && !f->ended) records.push_back(Record(FaultRecord::Event::kEnded, *f, now));
        f->ended = true;
        Remember(f);
        changed = true;
        continue;
      }
      if (f->started && now - f->last_report >= options_.report_period &&
          f->hit.load() != f->reported_hit) {
        f->last_report = now;
        f->reported_hit = f->hit.load();
        records.push_back(Record(FaultRecord::Event::kCount, *f, now));
      }
      keep.push_back(f);
    }
    if (changed) Publish(std::move(keep));
  }
  Emit(records);
}

}  // namespace internal

// ---- FaultEngine ------------------------------------------------------------------------------

FaultEngine::FaultEngine(Options options)
    : core_(std::make_shared<internal::EngineCore>(std::move(options))) {}

FaultEngine::~FaultEngine() {
  Uninstall();
  core_->Shutdown();
}

void FaultEngine::Install() {
  std::weak_ptr<internal::EngineCore> weak = core_;
  dds::InstallSeamFactory([weak](const std::string& topic, dds::Direction d) -> std::shared_ptr<dds::TopicSeam> {
    auto core = weak.lock();
    return core ? core->MakeSeam(topic, d) : nullptr;
  });
  dds::InstallSeamPump(core_);
}

void FaultEngine::Uninstall() {
  if (dds::CurrentSeamPump() == core_) {
    dds::InstallSeamFactory(nullptr);
    dds::InstallSeamPump(nullptr);
  }
}

std::shared_ptr<dds::TopicSeam> FaultEngine::MakeSeam(const std::string& topic, dds::Direction d) {
  return core_->MakeSeam(topic, d);
}
Status FaultEngine::Add(const FaultSpec& spec) { return core_->Add(spec); }
void FaultEngine::UseClock(const Clock& clock, Time epoch) { core_->UseClock(&clock, epoch); }
bool FaultEngine::Remove(std::uint32_t id) { return core_->Remove(id); }
void FaultEngine::Clear() { core_->Clear(); }
std::vector<FaultStatus> FaultEngine::List() const { return core_->List(); }
void FaultEngine::Pump() { core_->Pump(); }
std::optional<Time> FaultEngine::NextDue() const { return core_->NextDue(); }
void FaultEngine::SetRecordSink(RecordSink sink) { core_->SetSink(std::move(sink)); }
const std::string& FaultEngine::service() const { return core_->options().service; }

}  // namespace rover::faults
