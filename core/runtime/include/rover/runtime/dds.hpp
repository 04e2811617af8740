#pragma once
/// @file
/// RAII wrappers over Cyclone DDS's C API: Participant, typed Writer<T> and Reader<T> (T is an
/// idlc-generated C struct registered in <rover/idl/types.hpp>), GuardCondition and WaitSet.
///
/// Creation can fail for environmental reasons (bad domain, bad Cyclone configuration), so the
/// factories return Result<>. Samples with sequences: a writer borrows the caller's memory
/// (see BorrowSequence); a reader hands out Sample<T>, which owns what DDS allocated.
///
/// Every Writer<T>::Write and Reader<T>::Take / TakeEach passes through the fault seam (seam.hpp).
/// Under strict lock-step (lockstep.hpp) writes carry the thread's tick as their source
/// timestamp and readers taken from on a gated thread hold samples back until a later tick.

#include <dds/dds.h>

#include <algorithm>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/status.hpp"
#include "rover/idl/access.hpp"
#include "rover/idl/types.hpp"
#include "rover/runtime/lockstep.hpp"
#include "rover/runtime/qos.hpp"
#include "rover/runtime/seam.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::dds {

/// "dds_create_writer failed: <cyclone's text>".
Status DdsError(const std::string& what, dds_return_t rc);

/// Owns one DDS entity handle; deleting it deletes its children too.
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  ~Entity() { Reset(); }
  Entity(Entity&& o) noexcept : handle_(std::exchange(o.handle_, 0)) {}
  Entity& operator=(Entity&& o) noexcept {
    if (this != &o) {
      Reset();
      handle_ = std::exchange(o.handle_, 0);
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;

  dds_entity_t handle() const { return handle_; }
  bool valid() const { return handle_ > 0; }
  void Reset() {
    if (handle_ > 0) dds_delete(handle_);
    handle_ = 0;
  }

 protected:
  dds_entity_t handle_ = 0;
};

/// One DDS domain participant. One process = one participant in this stack.
class Participant : public Entity {
 public:
  Participant() = default;
  /// Creates a participant on `domain` using the Cyclone configuration in CYCLONEDDS_URI.
  static Result<Participant> Create(dds_domainid_t domain);
  dds_domainid_t domain() const { return domain_; }

 private:
  Participant(dds_entity_t h, dds_domainid_t d) : Entity(h), domain_(d) {}
  dds_domainid_t domain_ = 0;
};

/// The QoS profile for a topic: the catalog's if the topic is in it (and then the type must
/// match), else `fallback`. A type mismatch with the catalog is InvalidArgument.
Result<QosProfile> ResolveProfile(const std::string& topic, const char* type_name,
                                  std::optional<QosProfile> requested);

namespace internal {
Result<dds_entity_t> CreateTopic(const Participant& p, const std::string& name,
                                 const dds_topic_descriptor_t* desc, QosProfile profile);
/// `partition` empty: the default partition; otherwise the endpoint gets a publisher or
/// subscriber of its own in that one partition.
Result<dds_entity_t> CreateEndpoint(const Participant& p, dds_entity_t topic, QosProfile profile,
                                    bool writer, const std::string& partition = {});
/// Deep-copies a sample of `type` into `dst` (zeroed), which then owns its buffers
/// (type_layout.hpp); dds_sample_free(dst, type, DDS_FREE_CONTENTS) frees them.
void CopySample(void* dst, const void* src, const dds_topic_descriptor_t* type);
/// A SampleSink that calls a callable.
template <class F>
class SinkOf final : public SampleSink {
 public:
  explicit SinkOf(F& f) : f_(f) {}
  void Deliver(const void* sample, const dds_sample_info_t& info) override { f_(sample, info); }

 private:
  F& f_;
};
}  // namespace internal

/// A sample taken from a reader, owning its contents (sequences, unbounded strings).
template <class T>
class OwnedSample {
 public:
  OwnedSample() : data_(Allocate()) {}
  OwnedSample(OwnedSample&&) noexcept = default;
  OwnedSample& operator=(OwnedSample&&) noexcept = default;

  T& data() { return *data_; }
  const T& data() const { return *data_; }
  const T* operator->() const { return data_.get(); }
  T* operator->() { return data_.get(); }
  const dds_sample_info_t& info() const { return info_; }
  dds_sample_info_t& mutable_info() { return info_; }

 private:
  struct Free {
    void operator()(T* p) const {
      dds_sample_free(p, TopicType<T>::Descriptor(), DDS_FREE_ALL);
    }
  };
  static T* Allocate() {
    void* p = dds_alloc(sizeof(T));
    std::memset(p, 0, sizeof(T));
    return static_cast<T*>(p);
  }
  std::unique_ptr<T, Free> data_;
  dds_sample_info_t info_{};
};

/// A read-only view of a sample that DDS lends to a callback; valid only during the callback.
template <class T>
class Sample {
 public:
  Sample(const T* data, const dds_sample_info_t* info) : data_(data), info_(info) {}
  const T& data() const { return *data_; }
  const T* operator->() const { return data_; }
  const dds_sample_info_t& info() const { return *info_; }

 private:
  const T* data_;
  const dds_sample_info_t* info_;
};

/// Types whose samples start with a rover::Header (every topic type of the catalog).
template <class T>
concept HasHeader = requires(T t) { t.header.seq; };

/// A typed writer on one topic. It numbers the samples it writes (header.seq = 1, 2, 3, ... per
/// writer, as the IDL says) unless the caller set a non-zero header.seq itself.
template <class T>
class Writer {
 public:
  Writer() = default;
  /// Creates the writer; QoS comes from the topic catalog, or from `profile` for a topic that is
  /// not in the catalog (a profile that contradicts the catalog is an error).
  static Result<Writer> Create(const Participant& p, const std::string& topic,
                               std::optional<QosProfile> profile = std::nullopt) {
    return CreateInPartition(p, topic, {}, profile);
  }
  /// The same in one DDS partition (empty: the default one): it reaches only readers of that
  /// partition (strict lock-step's per-service sim/clock, lockstep::ClockPartition).
  static Result<Writer> CreateInPartition(const Participant& p, const std::string& topic,
                                          const std::string& partition,
                                          std::optional<QosProfile> profile = std::nullopt) {
    auto prof = ResolveProfile(topic, TopicType<T>::kTypeName, profile);
    if (!prof.ok()) return prof.status();
    auto t = internal::CreateTopic(p, topic, TopicType<T>::Descriptor(), *prof);
    if (!t.ok()) return t.status();
    auto w = internal::CreateEndpoint(p, *t, *prof, true, partition);
    if (!w.ok()) return w.status();
    Writer out;
    out.writer_ = Entity(*w);
    out.topic_ = Entity(*t);
    out.name_ = topic;
    out.profile_ = *prof;
    out.seam_ = SeamFor(topic, Direction::kWrite);
    lockstep::RegisterWriter(out.writer_.handle(), p.handle(), topic);
    return out;
  }

  /// Publishes one sample (numbered, then through the fault seam, if any: a dropped sample
  /// leaves a gap in header.seq).
  Status Write(const T& sample) {
    ROVER_DEMAND(writer_.valid());
    if constexpr (HasHeader<T>) {
      if (sample.header.seq == 0) {
        T numbered = sample;  // shallow: sequences stay borrowed from the caller
        if (++seq_ == 0) seq_ = 1;
        numbered.header.seq = seq_;
        return WriteAsIs(numbered);
      }
    }
    return WriteAsIs(sample);
  }

  /// The header.seq of the last sample this writer numbered (0 before the first).
  std::uint32_t last_seq() const { return seq_; }

  /// Readers currently matched.
  int MatchedReaders() const {
    dds_publication_matched_status_t st{};
    if (dds_get_publication_matched_status(writer_.handle(), &st) < 0) return 0;
    return static_cast<int>(st.current_count);
  }

  const std::string& topic_name() const { return name_; }
  QosProfile profile() const { return profile_; }
  dds_entity_t handle() const { return writer_.handle(); }
  bool valid() const { return writer_.valid(); }
  /// The fault seam samples pass through (nullptr when injection is off).
  TopicSeam* seam() const { return seam_.get(); }

 private:
  Entity writer_;
  Entity topic_;
  Status WriteAsIs(const T& sample) {
    dds_return_t rc = seam_ && !seam_->Idle()
                          ? seam_->OnWrite(writer_.handle(), &sample, TopicType<T>::Descriptor())
                          : lockstep::Write(writer_.handle(), &sample);
    if (rc < 0) return DdsError("write on " + name_, rc);
    return Status::Ok();
  }

  std::string name_;
  QosProfile profile_ = QosProfile::kState;
  std::shared_ptr<TopicSeam> seam_;
  std::uint32_t seq_ = 0;
};

/// A typed reader on one topic. Under a "fresh only" profile (commands, qos.hpp) it drops
/// samples written before the reader was created.
template <class T>
class Reader {
 public:
  Reader() = default;
  static Result<Reader> Create(const Participant& p, const std::string& topic,
                               std::optional<QosProfile> profile = std::nullopt) {
    return CreateInPartition(p, topic, {}, profile);
  }
  /// The same in one DDS partition (empty: the default one): it hears only writers of that
  /// partition.
  static Result<Reader> CreateInPartition(const Participant& p, const std::string& topic,
                                          const std::string& partition,
                                          std::optional<QosProfile> profile = std::nullopt) {
    auto prof = ResolveProfile(topic, TopicType<T>::kTypeName, profile);
    if (!prof.ok()) return prof.status();
    auto t = internal::CreateTopic(p, topic, TopicType<T>::Descriptor(), *prof);
    if (!t.ok()) return t.status();
    auto r = internal::CreateEndpoint(p, *t, *prof, false, partition);
    if (!r.ok()) return r.status();
    Reader out;
    out.reader_ = Entity(*r);
    out.topic_ = Entity(*t);
    out.name_ = topic;
    out.profile_ = *prof;
    out.seam_ = SeamFor(topic, Direction::kRead);
    out.ungated_ = lockstep::Ungated(topic);
    out.topic_index_ = lockstep::CatalogIndex(topic);
    if (DescribeQos(*prof).fresh_only) out.fresh_after_ = dds_time();
    return out;
  }

  /// Calls `fn(const Sample<T>&)` for every sample with valid data, oldest first, on memory
  /// DDS lends (no copy); passes each through the fault seam, and first hands out the samples
  /// the seam held back that are now due. Returns the number delivered.
  template <class F>
  std::size_t TakeEach(F&& fn) {
    ROVER_DEMAND(reader_.valid());
    if (const std::int64_t gate = ungated_ ? lockstep::kOff : lockstep::ReadGate();
        gate != lockstep::kOff) {
      AwaitFrontier(gate);
      Stash();
      std::size_t delivered = 0;
      for (auto& s : TakeVisible(gate, held_.size())) {
        ++delivered;
        fn(Sample<T>(&s.data(), &s.info()));
      }
      return delivered;
    }
    constexpr std::size_t kBatch = 32;
    void* ptrs[kBatch];
    dds_sample_info_t infos[kBatch];
    std::size_t delivered = 0;
    auto deliver = [&](const void* p, const dds_sample_info_t& info) {
      ++delivered;
      fn(Sample<T>(static_cast<const T*>(p), &info));
    };
    internal::SinkOf<decltype(deliver)> sink(deliver);
    if (seam_ && seam_->Holding()) seam_->ReleaseDue(sink);
    while (true) {
      ptrs[0] = nullptr;  // ask DDS to lend its buffers
      const dds_return_t n = dds_take(reader_.handle(), ptrs, infos, kBatch, kBatch);
      if (n <= 0) break;
      for (dds_return_t i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;
        NoteArrival(infos[i]);
        if (Stale(infos[i])) continue;
        if (seam_ && !seam_->Idle()) {
          seam_->OnRead(ptrs[i], infos[i], TopicType<T>::Descriptor(), sink);
        } else {
          deliver(ptrs[i], infos[i]);
        }
      }
      dds_return_loan(reader_.handle(), ptrs, n);
      if (static_cast<std::size_t>(n) < kBatch) break;
    }
    return delivered;
  }

  /// Takes up to `max` samples with valid data, oldest first, as owned copies (through the fault
  /// seam, if any, after the held-back samples that are due). Buffers are pooled: only samples
  /// actually taken cost an allocation.
  std::vector<OwnedSample<T>> Take(std::size_t max = 32) {
    ROVER_DEMAND(reader_.valid() && max > 0);
    if (const std::int64_t gate = ungated_ ? lockstep::kOff : lockstep::ReadGate();
        gate != lockstep::kOff) {
      AwaitFrontier(gate);
      Stash();
      return TakeVisible(gate, max);
    }
    return TakeFromDds(max, /*check_stale=*/true);
  }

  /// Strict lock-step: takes every sample DDS holds (through the fault seam) into this reader's
  /// own queue without handing any out; a gated Take / TakeEach hands them out at their tick.
  void Stash() {
    while (true) {
      auto got = TakeFromDds(32, /*check_stale=*/false);
      if (got.empty()) break;
      for (auto& s : got) held_.push_back(std::move(s));
    }
  }
  /// Samples stashed and not yet handed out.
  std::size_t held() const { return held_.size(); }

 private:
  // Up to `max` samples from DDS (and the seam's due ones), as owned copies.
  std::vector<OwnedSample<T>> TakeFromDds(std::size_t max, bool check_stale) {
    if (pool_.size() < max) pool_.resize(max);
    std::vector<void*> ptrs(max);
    std::vector<dds_sample_info_t> infos(max);
    std::vector<OwnedSample<T>> out;
    std::size_t current = max;  // the pool slot being passed through the seam
    auto deliver = [&](const void* p, const dds_sample_info_t& info) {
      if (current < max && p == &pool_[current].data()) {  // the taken sample itself
        pool_[current].mutable_info() = info;
        out.push_back(std::move(pool_[current]));
        pool_[current] = OwnedSample<T>();
        current = max;
      } else {  // a copy the seam made: deep-copy it into a sample of our own
        OwnedSample<T> copy;
        internal::CopySample(&copy.data(), p, TopicType<T>::Descriptor());
        copy.mutable_info() = info;
        out.push_back(std::move(copy));
      }
    };
    internal::SinkOf<decltype(deliver)> sink(deliver);
    if (seam_ && seam_->Holding()) seam_->ReleaseDue(sink);
    for (std::size_t i = 0; i < max; ++i) ptrs[i] = &pool_[i].data();
    const dds_return_t n = dds_take(reader_.handle(), ptrs.data(), infos.data(), max,
                                    static_cast<uint32_t>(max));
    if (n <= 0) return out;
    out.reserve(out.size() + static_cast<std::size_t>(n));
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      NoteArrival(infos[i]);
      if (check_stale && Stale(infos[i])) continue;
      current = static_cast<std::size_t>(i);
      if (seam_ && !seam_->Idle()) {
        seam_->OnRead(&pool_[current].data(), infos[i], TopicType<T>::Descriptor(), sink);
      } else {
        deliver(&pool_[current].data(), infos[i]);
      }
      current = max;
    }
    return out;
  }

  // Strict lock-step: waits (stashing) until this reader has received every sample the frontier
  // of the tick being served counts on its topic. The frontier counts samples written so far;
  // this reader counts what it took from DDS by the tick it was written at (before the fault
  // seam, which may drop what it received). Counting starts at the second tick it serves (B1):
  // expected = frontier(T) - frontier(B1) samples, written at ticks in [B1, T). Gives up after
  // kFrontierWaitS and counts the rest missing.
  void AwaitFrontier(std::int64_t gate) {
    const lockstep::TopicCounts& f = lockstep::Frontier();
    if (topic_index_ < 0 || f.size() <= static_cast<std::size_t>(topic_index_)) return;
    const std::uint64_t frontier = f[static_cast<std::size_t>(topic_index_)];
    if (count_phase_ == 0) {  // first tick served: only note it
      count_phase_ = 1;
      first_tick_ = gate;
      return;
    }
    if (count_phase_ == 1) {
      if (gate <= first_tick_) return;
      count_phase_ = 2;
      count_from_ = gate;
      frontier_base_ = frontier;
      return;
    }
    const std::uint64_t expected = frontier > frontier_base_ ? frontier - frontier_base_ : 0;
    auto counted = [&] {
      // Fold what arrived for ticks before the gate into the count; later ticks wait.
      for (auto it = arrivals_.begin(); it != arrivals_.end() && it->first < gate;) {
        if (it->first >= count_from_) counted_ += it->second;
        it = arrivals_.erase(it);
      }
      return counted_;
    };
    if (counted() >= expected) return;
    const dds_time_t deadline =
        dds_time() + static_cast<dds_time_t>(lockstep::kFrontierWaitS * 1e9);
    while (true) {
      Stash();
      if (counted() >= expected) return;
      if (dds_time() > deadline) {
        lockstep::CountMissingSamples(name_, expected - counted_);
        counted_ = expected;
        return;
      }
      dds_sleepfor(DDS_USECS(50));
    }
  }

  // The stashed samples visible under `gate`, oldest tick first (then stamp and header.seq, so
  // that two writers' samples of one tick come in the same order every run); the others stay.
  std::vector<OwnedSample<T>> TakeVisible(std::int64_t gate, std::size_t max) {
    if (fresh_after_ != 0 && first_gate_ == lockstep::kOff) first_gate_ = gate;
    std::vector<OwnedSample<T>> out;
    std::deque<OwnedSample<T>> keep;
    for (auto& s : held_) {
      if (out.size() < max && lockstep::Visible(s.info().source_timestamp, gate)) {
        if (!Stale(s.info())) {
          // Visible at an earlier gate already: it came late (unless a fault delayed it).
          if (s.info().source_timestamp < lockstep::kWallStampFloor &&
              last_gate_ != lockstep::kOff && s.info().source_timestamp < last_gate_ &&
              (!seam_ || seam_->Idle())) {
            lockstep::CountLateSample(name_, s.info().source_timestamp, gate);
          }
          out.push_back(std::move(s));
        }
      } else {
        keep.push_back(std::move(s));
      }
    }
    held_ = std::move(keep);
    last_gate_ = gate;
    std::stable_sort(out.begin(), out.end(), [](const OwnedSample<T>& a, const OwnedSample<T>& b) {
      if (a.info().source_timestamp != b.info().source_timestamp) {
        return a.info().source_timestamp < b.info().source_timestamp;
      }
      if constexpr (HasHeader<T>) {
        if (a->header.stamp_ns != b->header.stamp_ns)
          return a->header.stamp_ns < b->header.stamp_ns;
        return a->header.seq < b->header.seq;
      }
      return false;
    });
    return out;
  }

 public:
  /// Writers currently matched.
  int MatchedWriters() const {
    dds_subscription_matched_status_t st{};
    if (dds_get_subscription_matched_status(reader_.handle(), &st) < 0) return 0;
    return static_cast<int>(st.current_count);
  }

  const std::string& topic_name() const { return name_; }
  QosProfile profile() const { return profile_; }
  dds_entity_t handle() const { return reader_.handle(); }
  bool valid() const { return reader_.valid(); }
  /// The fault seam samples pass through (nullptr when injection is off).
  TopicSeam* seam() const { return seam_.get(); }

 private:
  Entity reader_;
  Entity topic_;
  // Written before this reader existed (fresh-only profiles): an old command from a writer's
  // history, not one for us.
  // Under lock-step (a tick as the stamp) the wall time of creation says nothing: a sample is
  // stale when it was written before the first tick this reader was read at.
  bool Stale(const dds_sample_info_t& info) const {
    if (fresh_after_ == 0) return false;
    if (info.source_timestamp < lockstep::kWallStampFloor) {
      return first_gate_ != lockstep::kOff && info.source_timestamp < first_gate_;
    }
    return info.source_timestamp < fresh_after_;
  }
  std::deque<OwnedSample<T>> held_;
  std::int64_t first_gate_ = lockstep::kOff;  // first gate seen (fresh-only readers)
  bool ungated_ = false;                      // lockstep::Ungated(topic)
  int topic_index_ = -1;                      // lockstep::CatalogIndex(topic)
  // Strict lock-step frontier counting (AwaitFrontier): samples taken from DDS per source tick.
  void NoteArrival(const dds_sample_info_t& info) {
    if (count_phase_ == 0 || info.source_timestamp >= lockstep::kWallStampFloor) return;
    ++arrivals_[info.source_timestamp];
  }
  std::map<std::int64_t, std::uint64_t> arrivals_;  // tick -> samples not counted yet
  std::uint64_t counted_ = 0;       // arrived with ticks in [count_from_, last gate)
  std::uint64_t frontier_base_ = 0;
  std::int64_t first_tick_ = 0, count_from_ = 0;
  int count_phase_ = 0;             // 0: never served, 1: first tick served, 2: counting
  std::int64_t last_gate_ = lockstep::kOff;

  std::string name_;
  QosProfile profile_ = QosProfile::kState;
  std::shared_ptr<TopicSeam> seam_;
  std::vector<OwnedSample<T>> pool_;
  dds_time_t fresh_after_ = 0;  // 0: every sample counts
};

/// A condition the program triggers itself (e.g. to wake a WaitSet for shutdown).
class GuardCondition : public Entity {
 public:
  static Result<GuardCondition> Create(const Participant& p);
  /// Thread-safe.
  void Trigger();
  /// Returns whether it was triggered, and clears it.
  bool TakeTriggered();

 private:
  using Entity::Entity;
};

/// Waits for readers with data and guard conditions.
class WaitSet : public Entity {
 public:
  static Result<WaitSet> Create(const Participant& p);
  /// Attaches a reader (woken on DATA_AVAILABLE) or a guard condition; `token` comes back from
  /// Wait() when that entity triggers.
  Status Attach(dds_entity_t entity, dds_attach_t token);
  Status Detach(dds_entity_t entity);
  /// Blocks up to `timeout` (wall time); returns the tokens of triggered entities.
  std::vector<dds_attach_t> Wait(std::int64_t timeout_ns);

 private:
  using Entity::Entity;
  std::size_t attached_ = 0;
};

// ---- sequences ---------------------------------------------------------------------------------

// BorrowSequence (memory the caller keeps alive until Write() returns), View (a read-only view
// of a received sequence) and CopyString (std::string -> bounded IDL string): see
// rover/idl/access.hpp.
using idl::BorrowSequence;
using idl::CopyString;
using idl::View;

}  // namespace rover::dds
