#include "rover/runtime/input_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::runtime {
namespace {

constexpr std::size_t kMaxWritersPerInput = 64;  // beyond: forget them all (writers churned)

int Rank(InputProblem p) {
  switch (p) {
    case InputProblem::kStale: return 0;
    case InputProblem::kRejected: return 1;
    case InputProblem::kSeqGap: return 2;
    case InputProblem::kSeqRepeat: return 3;
    case InputProblem::kSeqReorder: return 4;
    case InputProblem::kLate: return 5;
  }
  return 6;
}

std::string Seconds1(double s) { return FormatNumber(s, 3) + " s"; }

}  // namespace

const char* InputVerdictName(InputVerdict v) {
  switch (v) {
    case InputVerdict::kNominal: return "nominal";
    case InputVerdict::kDegraded: return "degraded";
    case InputVerdict::kFault: return "fault";
  }
  return "?";
}

const char* InputProblemName(InputProblem p) {
  switch (p) {
    case InputProblem::kStale: return "stale";
    case InputProblem::kRejected: return "rejected";
    case InputProblem::kSeqGap: return "seq gap";
    case InputProblem::kSeqRepeat: return "seq repeated";
    case InputProblem::kSeqReorder: return "out of order";
    case InputProblem::kLate: return "late";
  }
  return "?";
}

Status InputLimits::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckNonNegative("max_latency_s", max_latency_s, "s"));
  return CheckNonNegative("max_age_s", max_age_s, "s");
}

void InputLimits::BindParams(ParamBinder<InputLimits>& b) {
  b.Bind("max_age_s", &InputLimits::max_age_s, "s",
         "stale (a fault on sys/health) when the newest accepted sample is older; 0 = not checked")
      .Min(0.0);
  b.Bind("check_seq", &InputLimits::check_seq,
         "report header.seq gaps (history topics), repeats and reordering");
  b.Bind("max_latency_s", &InputLimits::max_latency_s, "s",
         "late (degraded on sys/health) when an accepted sample's stamp is older than this at "
         "its arrival; 0 = not checked")
      .Min(0.0);
}

Status InputMonitorOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckPositive("hold_s", hold_s, "s"));
  return CheckNonNegative("startup_s", startup_s, "s");
}

void InputMonitorOptions::BindParams(ParamBinder<InputMonitorOptions>& b) {
  b.Bind("hold_s", &InputMonitorOptions::hold_s, "s",
         "a rejected sample or a seq gap stays on sys/health this long after the last one")
      .Min(0.0);
  b.Bind("startup_s", &InputMonitorOptions::startup_s, "s",
         "an input without any sample is stale only after max(its max_age_s, this) from start")
      .Min(0.0);
}

std::string InputParamKey(const std::string& topic) {
  std::string key = topic;
  std::replace(key.begin(), key.end(), '/', '_');
  return key;
}

void DeclareInputParams(ParamSet& params, const std::vector<InputSpec>& inputs) {
  DeclareParams<InputMonitorOptions>(params, "inputs.");
  std::set<std::string> seen;
  for (const InputSpec& in : inputs) {
    ROVER_DEMAND_MSG(seen.insert(in.topic).second, ("input declared twice: " + in.topic).c_str());
    DeclareParams<InputLimits>(params, "inputs." + InputParamKey(in.topic) + ".", in.limits);
  }
}

Result<InputMonitor> InputMonitor::Create(const InputMonitorOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return InputMonitor(options);
}

Result<InputMonitor> InputMonitor::FromParams(const ParamSet& params,
                                              const std::vector<InputSpec>& inputs) {
  ROVER_ASSIGN_OR_RETURN(const InputMonitorOptions options,
                         ReadParams<InputMonitorOptions>(params, "inputs."));
  ROVER_ASSIGN_OR_RETURN(InputMonitor monitor, Create(options));
  for (const InputSpec& in : inputs) {
    ROVER_ASSIGN_OR_RETURN(
        const InputLimits limits,
        ReadParams<InputLimits>(params, "inputs." + InputParamKey(in.topic) + ".", in.limits));
    ROVER_RETURN_IF_ERROR(monitor.Declare(in.topic, limits));
  }
  return monitor;
}

Status InputMonitor::Declare(const std::string& topic, const InputLimits& limits) {
  if (topic.empty()) return InvalidArgument("input topic is empty");
  if (const Status s = limits.Validate(); !s.ok()) return s.WithPrefix("input " + topic);
  for (Input& in : inputs_) {
    if (in.topic == topic) {
      in.limits = limits;
      return Status::Ok();
    }
  }
  Input in;
  in.topic = topic;
  in.limits = limits;
  inputs_.push_back(std::move(in));
  return Status::Ok();
}

std::size_t InputMonitor::Watch(const std::string& topic, double tolerated_loss) {
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    if (inputs_[i].topic == topic) {
      inputs_[i].limits.tolerated_loss = std::max(inputs_[i].limits.tolerated_loss, tolerated_loss);
      return i;
    }
  }
  Input in;
  in.topic = topic;
  in.limits.tolerated_loss = tolerated_loss;
  inputs_.push_back(std::move(in));
  return inputs_.size() - 1;
}

const InputMonitor::Input* InputMonitor::Find(const std::string& topic) const {
  for (const Input& in : inputs_) {
    if (in.topic == topic) return &in;
  }
  return nullptr;
}

bool InputMonitor::Has(const std::string& topic) const { return Find(topic) != nullptr; }

const InputLimits* InputMonitor::LimitsOf(const std::string& topic) const {
  const Input* in = Find(topic);
  return in == nullptr ? nullptr : &in->limits;
}

std::uint64_t InputMonitor::accepted(const std::string& topic) const {
  const Input* in = Find(topic);
  return in == nullptr ? 0 : in->accepted;
}

std::uint64_t InputMonitor::rejected(const std::string& topic) const {
  const Input* in = Find(topic);
  return in == nullptr ? 0 : in->rejected;
}

void InputMonitor::Start(Time now) {
  start_ = now;
  for (Input& in : inputs_) {
    in.newest.reset();
    in.last_accepted.reset();
    in.last_rejected.reset();
    in.rejected_since_accept = 0;
    in.last_seq.clear();
    in.loss = 0.0;
    in.gap.reset();
    in.repeat.reset();
    in.reorder.reset();
  }
}

void InputMonitor::Note(std::optional<SeqEvent>* slot, InputProblem p, std::uint32_t seq,
                        std::uint32_t prev, double loss, Time now) const {
  // Within one episode (events less than hold_s apart) the first event names it, so that the
  // reason on sys/health does not change with every sample.
  if (slot->has_value() && ToSeconds(now - (*slot)->at) <= options_.hold_s) {
    (*slot)->at = now;
    return;
  }
  SeqEvent e;
  e.problem = p;
  e.at = now;
  e.seq = seq;
  e.previous = prev;
  e.loss = loss;
  *slot = e;
}

bool InputMonitor::OnArrival(std::size_t index, std::uint64_t writer, std::uint32_t seq,
                             Time now) {
  ROVER_DEMAND(index < inputs_.size());
  Input& in = inputs_[index];
  if (!in.limits.check_seq || seq == 0) return false;
  auto it = in.last_seq.find(writer);
  if (it == in.last_seq.end()) {
    if (in.last_seq.size() >= kMaxWritersPerInput) in.last_seq.clear();
    in.last_seq.emplace(writer, seq);
    return false;
  }
  const std::uint32_t prev = it->second;
  if (seq > prev) {
    // Lost samples each move the average towards 1, the one received towards 0.
    const double lost = static_cast<double>(seq - prev - 1);
    in.loss = 1.0 - (1.0 - in.loss) * std::pow(1.0 - kLossMemory, lost);
    in.loss *= 1.0 - kLossMemory;
    it->second = seq;
    if (lost == 0.0 || in.limits.tolerated_loss >= 1.0) return false;
    if (in.loss <= in.limits.tolerated_loss && in.limits.tolerated_loss > 0.0) return false;
    Note(&in.gap, InputProblem::kSeqGap, seq, prev, in.loss, now);
    return true;
  }
  if (seq == prev) {
    Note(&in.repeat, InputProblem::kSeqRepeat, seq, prev, in.loss, now);
  } else {
    Note(&in.reorder, InputProblem::kSeqReorder, seq, prev, in.loss, now);
  }
  return true;
}

void InputMonitor::OnAccepted(std::size_t index, Time stamp, Time now) {
  ROVER_DEMAND(index < inputs_.size());
  Input& in = inputs_[index];
  // A stamp ahead of the run clock (a corrupt one, or a clock step) counts as now; a stamp of
  // zero means "not stamped".
  const Time fresh = stamp.ns > 0 ? std::min(stamp, now) : now;
  if (!in.newest || fresh > *in.newest) in.newest = fresh;
  if (in.limits.max_latency_s > 0.0 && stamp.ns > 0 &&
      ToSeconds(now - stamp) > in.limits.max_latency_s) {
    // The episode's first late sample names it (the reason stays put while it lasts).
    if (!in.late_at || ToSeconds(now - *in.late_at) > options_.hold_s) {
      in.late_stamp = stamp;
      in.late_latency_s = ToSeconds(now - stamp);
    }
    in.late_at = now;
  }
  in.last_accepted = now;
  in.accepted += 1;
  in.rejected_since_accept = 0;
}

void InputMonitor::OnRejected(std::size_t index, const std::string& why, Time now) {
  ROVER_DEMAND(index < inputs_.size());
  Input& in = inputs_[index];
  const bool active = in.last_rejected &&
                      (ToSeconds(now - *in.last_rejected) <= options_.hold_s ||
                       !in.last_accepted || *in.last_accepted < *in.last_rejected);
  if (!active) in.rejected_why = why;  // the episode's first reason stays its reason
  in.last_rejected = now;
  in.rejected += 1;
  in.rejected_since_accept += 1;
}

void InputMonitor::AddFindings(const Input& in, Time now, std::vector<InputFinding>* out) const {
  const auto add = [&](InputProblem p, InputVerdict v, Time since, std::string what) {
    out->push_back(InputFinding{in.topic, p, v, since,
                                in.topic + " " + InputProblemName(p) + ": " + std::move(what)});
  };
  // Reasons name times and first events, not ages or running counts: they stay the same while a
  // problem lasts, so sys/health changes when the problem does.
  const double limit = in.limits.max_age_s;
  const std::string rejected_note =
      in.rejected_since_accept > 0 ? "; since then rejected: " + in.rejected_why : "";
  if (limit > 0.0) {
    if (in.newest) {
      if (ToSeconds(now - *in.newest) > limit) {
        add(InputProblem::kStale, InputVerdict::kFault, *in.newest + Seconds(limit),
            "no sample since t = " + Seconds1(in.newest->seconds()) + " (limit " +
                Seconds1(limit) + ")" + rejected_note);
      }
    } else {
      const double startup_limit = std::max(limit, options_.startup_s);
      if (ToSeconds(now - start_) > startup_limit) {
        add(InputProblem::kStale, InputVerdict::kFault, start_ + Seconds(startup_limit),
            "no sample since the start at t = " + Seconds1(start_.seconds()) + " (limit " +
                Seconds1(startup_limit) + ")" + rejected_note);
      }
    }
  }
  if (in.last_rejected) {
    const bool recent = ToSeconds(now - *in.last_rejected) <= options_.hold_s;
    const bool unanswered = !in.last_accepted || *in.last_accepted < *in.last_rejected;
    if (recent || unanswered) {
      add(InputProblem::kRejected, InputVerdict::kDegraded, *in.last_rejected, in.rejected_why);
    }
  }
  const auto seq_finding = [&](const std::optional<SeqEvent>& e) {
    if (!e || ToSeconds(now - e->at) > options_.hold_s) return;
    std::string what = "seq " + std::to_string(e->seq) + " after " + std::to_string(e->previous);
    if (e->problem == InputProblem::kSeqGap) {
      const std::uint32_t missing = e->seq - e->previous - 1;
      what += " (" + std::to_string(missing) + (missing == 1 ? " sample" : " samples") + " lost";
      if (in.limits.tolerated_loss > 0.0) {
        what += "; " + FormatNumber(100.0 * e->loss, 2) + " % of recent samples, tolerated " +
                FormatNumber(100.0 * in.limits.tolerated_loss, 2) + " %";
      }
      what += ")";
    }
    add(e->problem, InputVerdict::kDegraded, e->at, std::move(what));
  };
  seq_finding(in.gap);
  seq_finding(in.repeat);
  seq_finding(in.reorder);
  if (in.late_at && ToSeconds(now - *in.late_at) <= options_.hold_s) {
    add(InputProblem::kLate, InputVerdict::kDegraded, *in.late_at,
        "a sample stamped t = " + Seconds1(in.late_stamp.seconds()) + " arrived " +
            Seconds1(in.late_latency_s) + " later (limit " + Seconds1(in.limits.max_latency_s) +
            ")");
  }
}

InputReport InputMonitor::Report(Time now) const {
  InputReport r;
  for (const Input& in : inputs_) AddFindings(in, now, &r.findings);
  std::stable_sort(r.findings.begin(), r.findings.end(),
                   [](const InputFinding& a, const InputFinding& b) {
                     if (a.verdict != b.verdict) return a.verdict > b.verdict;
                     if (a.problem != b.problem) return Rank(a.problem) < Rank(b.problem);
                     return a.since > b.since;
                   });
  if (r.findings.empty()) return r;
  r.verdict = r.findings.front().verdict;
  r.reason = r.findings.front().reason;
  if (r.findings.size() > 1) r.reason += " (+" + std::to_string(r.findings.size() - 1) + " more)";
  return r;
}

}  // namespace rover::runtime
