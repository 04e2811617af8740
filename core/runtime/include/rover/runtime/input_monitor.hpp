#pragma once
/// @file
/// InputMonitor: what a service knows about the health of its inputs, the same for every
/// service (issue 12: detection). The service harness (service.hpp) feeds it every sample of
/// every typed subscription and reports its worst finding on sys/health; it has no DDS and
/// reads no clock (every call passes the run-clock time `now`), so it is tested on its own.
///
/// Per input (one topic) it tracks:
///   - staleness: the age of the newest *accepted* sample, now - min(header.stamp, receipt)
///     (the receipt time when the stamp is zero), against the input's max_age_s (0: not
///     checked). A frozen source (its stamp repeats) therefore goes stale too. Before the first
///     sample the age counts from Start() and the limit is max(max_age_s, startup_s).
///   - header.seq per writer (seq counts 1, 2, 3, ... per writer, dds::Writer): a jump forward
///     loses samples. It is a gap finding when the share of lost samples (an exponential average
///     over about the last 50 samples, kLossMemory) exceeds the input's `tolerated_loss`: 0 on
///     keep-all topics (every lost command counts), kStreamTolerableLoss on best-effort streams
///     (a lost sample is replaced by the next), 1 on keep-last-1 topics (a reader legitimately
///     misses overwritten samples: gaps never count). A seq at or below the writer's last one is
///     a repeat (a duplicate or a frozen source) or out of order. seq 0 (unnumbered) and a
///     writer's first sample are not checked.
///   - rejections: samples the service refused (a failed conversion or range check), with the
///     conversion's message.
///   - latency: an accepted sample whose header stamp is more than the input's max_latency_s
///     older than its arrival (0: not checked) is late: data captured long before it is used
///     (a delayed range image) is reported even though it keeps arriving.
///
/// Findings and their verdicts:
///   stale                      fault     until an accepted fresh sample arrives
///   rejected                   degraded  until hold_s after the last rejection, and at least
///                                        until an accepted sample follows it
///   seq gap, repeat, reorder   degraded  until hold_s after the last one
///   late                       degraded  until hold_s after the last late sample
/// Report() orders the findings worst first (verdict, then stale > rejected > gap > repeat >
/// reorder, then the most recent) and its reason is the first one's, e.g.
///   "dl/pose stale: last sample 1.8 s ago (limit 0.5 s)"
///   "dl/pose rejected: pose.position.x is nan (must be finite)"
///   "ddl/imu seq gap: 3 samples missing (seq 41 after 37)"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::runtime {

/// Lost-sample share tolerated on best-effort stream topics (see the file comment).
inline constexpr double kStreamTolerableLoss = 0.2;
/// Weight of one sample in the lost-sample average (memory of about 1 / kLossMemory samples).
inline constexpr double kLossMemory = 0.02;

/// Nominal < degraded < fault.
enum class InputVerdict : std::uint8_t { kNominal = 0, kDegraded = 1, kFault = 2 };
/// "nominal", "degraded", "fault".
const char* InputVerdictName(InputVerdict v);

enum class InputProblem : std::uint8_t {
  kStale,
  kRejected,
  kSeqGap,
  kSeqRepeat,
  kSeqReorder,
  kLate
};
/// "stale", "rejected", "seq gap", "seq repeated", "out of order", "late".
const char* InputProblemName(InputProblem p);

/// The limits of one input; parameters `inputs.<key>.*` (InputParamKey) of a service that
/// declares the input (Service::Inputs()).
struct InputLimits {
  double max_age_s = 0.0;  ///< [s] stale when the newest accepted sample is older; 0 = no check
  bool check_seq = true;   ///< check header.seq (gaps, repeats, order)
  /// [s] late when an accepted sample's stamp is older than this at its arrival; 0 = no check
  double max_latency_s = 0.0;
  /// Not a parameter (the harness sets it from the topic's QoS): the share of lost samples that
  /// is no finding; 0 = every gap is one, 1 = gaps never are.
  double tolerated_loss = 0.0;

  Status Validate() const;
  static void BindParams(ParamBinder<InputLimits>& b);
};

/// Parameters `inputs.*` of every service.
struct InputMonitorOptions {
  double hold_s = 2.0;     ///< [s] a rejection or seq finding stays this long after its last one
  double startup_s = 5.0;  ///< [s] no sample yet: stale only after max(max_age_s, startup_s)

  Status Validate() const;
  static void BindParams(ParamBinder<InputMonitorOptions>& b);
};

/// One input a service declares, with its default limits.
struct InputSpec {
  std::string topic;  ///< catalog name, "dl/pose"
  InputLimits limits;
};

/// The parameter key of a topic: '/' becomes '_' ("dl/pose" -> "dl_pose").
std::string InputParamKey(const std::string& topic);

/// Declares `inputs.hold_s`, `inputs.startup_s` and, per spec, `inputs.<key>.max_age_s` and
/// `inputs.<key>.check_seq` with the spec's limits as defaults. Two specs of one topic are a
/// programming error.
void DeclareInputParams(ParamSet& params, const std::vector<InputSpec>& inputs);

struct InputFinding {
  std::string topic;
  InputProblem problem = InputProblem::kStale;
  InputVerdict verdict = InputVerdict::kNominal;
  Time since;          ///< the (latest) occurrence; for stale: when the limit was passed
  std::string reason;  ///< "<topic> <problem>: <what>"
};

/// The monitor's verdict at one time.
struct InputReport {
  InputVerdict verdict = InputVerdict::kNominal;
  /// The worst finding's reason, with " (+N more)" when there are N others; "" when nominal.
  std::string reason;
  std::vector<InputFinding> findings;  ///< worst first
};

class InputMonitor {
 public:
  /// Errors: InvalidArgument from options.Validate().
  static Result<InputMonitor> Create(const InputMonitorOptions& options);
  /// The monitor of a service's parameters (declared by DeclareInputParams with the same
  /// `inputs`): options and every declared input, limits checked; errors name the key.
  static Result<InputMonitor> FromParams(const ParamSet& params,
                                         const std::vector<InputSpec>& inputs);

  /// Declares an input (or replaces its limits, keeping what was seen). Errors:
  /// InvalidArgument from limits.Validate() or an empty topic.
  Status Declare(const std::string& topic, const InputLimits& limits);
  /// Makes sure `topic` is watched (default limits when it was not declared); returns its
  /// index for the fast calls below. Its tolerated_loss becomes the larger of the two.
  std::size_t Watch(const std::string& topic, double tolerated_loss);
  bool Has(const std::string& topic) const;
  const InputLimits* LimitsOf(const std::string& topic) const;

  /// Ages of inputs without a sample count from here (the service's activation). Also clears
  /// every finding (a reactivated service starts afresh).
  void Start(Time now);

  /// A sample of input `index` arrived from `writer` with header `seq` (0: unnumbered). Returns
  /// true when it raised a new seq finding.
  bool OnArrival(std::size_t index, std::uint64_t writer, std::uint32_t seq, Time now);
  /// The service used the sample; `stamp` its header stamp (zero: use `now`).
  void OnAccepted(std::size_t index, Time stamp, Time now);
  /// The service refused the sample: `why` as the conversion said it.
  void OnRejected(std::size_t index, const std::string& why, Time now);

  /// The findings at `now`.
  InputReport Report(Time now) const;

  const InputMonitorOptions& options() const { return options_; }
  /// Samples accepted / rejected on `topic` so far (0 for an unknown topic).
  std::uint64_t accepted(const std::string& topic) const;
  std::uint64_t rejected(const std::string& topic) const;

 private:
  struct SeqEvent {
    InputProblem problem = InputProblem::kSeqGap;
    Time at;                              // the latest event of the episode
    std::uint32_t seq = 0, previous = 0;  // the episode's first event
    double loss = 0.0;                    // the lost share then
  };
  struct Input {
    std::string topic;
    InputLimits limits;
    std::optional<Time> newest;         // freshness of the newest accepted sample
    std::optional<Time> last_accepted;  // receipt time
    std::optional<Time> last_rejected;
    std::string rejected_why;
    std::uint64_t accepted = 0, rejected = 0;
    std::uint64_t rejected_since_accept = 0;
    std::map<std::uint64_t, std::uint32_t> last_seq;  // per writer
    double loss = 0.0;                                // lost share, exponential average
    std::optional<SeqEvent> gap, repeat, reorder;
    std::optional<Time> late_at;     // the latest late sample's arrival
    Time late_stamp;                 // the episode's first late sample: its stamp ...
    double late_latency_s = 0.0;     // ... and how late it was
  };

  explicit InputMonitor(const InputMonitorOptions& options) : options_(options) {}
  const Input* Find(const std::string& topic) const;
  void Note(std::optional<SeqEvent>* slot, InputProblem p, std::uint32_t seq, std::uint32_t prev,
            double loss, Time now) const;
  void AddFindings(const Input& in, Time now, std::vector<InputFinding>* out) const;

  InputMonitorOptions options_;
  std::vector<Input> inputs_;
  Time start_;
};

}  // namespace rover::runtime
