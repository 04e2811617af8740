#pragma once
/// @file
/// MobilityManager: MER's Mobility Manager (seed 000) as a deterministic state machine, in the
/// style of dl/locomotion's DriveExecutor. It is fed time-stamped inputs (run-clock time `now`)
/// and returns what to send and publish; it never reads a clock, sleeps or touches DDS. Terrain
/// assessment and path selection are the injected nav_core interfaces (GESTALT in the service).
///
/// Inputs:  OnCommand (apl/mobility_command), OnPose (dl/pose), OnRangeImage (dl/range_image
///          as a RangeScan + camera + request id), OnDriveStatus (dl/drive_status),
///          OnMastStatus (dl/mast_status), OnVisOdom (dl/relative_pose from VO), Step (timer).
/// Outputs: MobilityOutput: drive requests, range requests, mast requests, statuses, and the
///          goodness map / arc votes after each assessment.
///
/// One command runs at a time. Its loop is a sequence of steps; each step is
///   [image] -> [assess + choose] -> drive -> [visual odometry] -> checks -> next step
/// where the bracketed parts depend on the mode:
///   DIRECTED, VISODOM: the primitives in order (VISODOM splits them into steps of at most
///     visodom_max_step / visodom_max_turn and waits for a VO result after each).
///   GO_TO_WAYPOINT (+VISODOM): blind pose-corrected steps: a turn in place toward the goal when
///     its bearing exceeds waypoint_turn_threshold, else the arc through the goal (at most
///     waypoint_step_length, or the VO step).
///   GUARDED (+VISODOM): the primitives, split into guard_segment_length pieces; before each,
///     a HAZCAM image (front, rear when backing) is assessed and the piece's swept centre track
///     must stay on cells of goodness >= guard_min_goodness, else the command ends NOPATH
///     ("vetoed") before the piece moves.
///   GUARDED_ARC (seed 003): the first primitive runs blind (the turn), the rest guarded.
///   AUTONAV (+VISODOM): evaluate the arcs over the existing map; unless every path is already
///     known safe (ArcEvaluation::all_paths_safe: skip imaging) request a range image (front
///     HAZCAM; rear when the choice backs up or ArcEvaluation::image_rear), update the assessor,
///     evaluate again and command the choice (an arc of step_length, or a point turn; K-turns
///     are the selector's GoalMode::kBackUp arcs) until the goal is within tolerance.
///     Drive while thinking (default; THINK_STOP_AND_GO keeps MER's stop-and-go): when an arc
///     is commanded, the map is evaluated from the arc's predicted end pose; if that is not
///     already all safe the next range image is requested at once, so it is captured and
///     merged (its scan carries the pose at capture) while the arc drives, and the next choice
///     is made the moment the drive reports DONE.
///   LONG_TRAVERSE: a GlobalPlanner plan, then autonav legs to its waypoints; rejected
///     (BAD_COMMAND, "not supported") when no planner is injected.
///   STOP: ends the running command STOPPED (a STOP drive is sent); CLEAR_FAULT: clears a
///     latched motion error. Both succeed at once.
///
/// Checks after each step (and in Step): goal reached -> SUCCEEDED; time budget -> WAYPT_TIMEOUT;
/// Mars time of day past lmst_end_h -> TOD; steps >= max_steps -> NOPROGRESS; distance to the
/// goal shrunk less than min_progress over progress_steps steps -> in the arc-voting modes
/// (AUTONAV, AUTONAV_VISODOM, LONG_TRAVERSE) a limit-cycle turn in place (up to
/// limit_cycle_turns per command, each where the turn's own cells are not forbidden: to face
/// the goal, or when it is within limit_cycle_min_bearing of ahead by limit_cycle_turn toward
/// the side of the best forward arc), after which the window starts again; otherwise
/// NOPROGRESS (limit cycle). A single-arc planner (GESTALT) whose chosen arc is forward while the
/// goal lies more than the tolerance inside the turning circle of its tightest forward arc
/// (reached by no arc) turns in place to face the goal instead, where its turns in place are
/// allowed. GESTALT is told the direction of the last arc
/// (ArcRequest::last_direction);
/// tilt over max_tilt -> TILT; northerly tilt (atan2 of the rover's up vector's north and up
/// components) below min_northerly_tilt -> NORTH. Before each drive: the swept centre track
/// within keepout_margin of a keep-out zone -> KEEPOUT (nothing moves). While waiting: a range
/// image later than image_timeout_s, from the wrong camera, malformed or with no valid pixel ->
/// IMG; dl/pose older than pose_stale_s, non-finite or jumping by pose_jump / pose_jump_angle ->
/// SAPP; a drive not finished by its watchdog -> DRIVE_TIMEOUT (a STOP drive is sent); no
/// dl/drive_status of the running drive for drive_status_timeout_s (locomotion reports every
/// cycle, 8 Hz, while a primitive runs) -> MOT (a STOP drive is sent);
/// dl/drive_status FAILED: TILT -> TILT, SUSPENSION -> SUSPENSION, motor terminations -> MOT,
/// TIMEOUT -> DRIVE_TIMEOUT, STALE_SENSOR -> SAPP, STOP_COMMAND -> STOPPED; REJECTED_BUSY (some
/// other client drives) -> ARB; REJECTED_INVALID -> BAD_COMMAND.
///
/// Input faults (OnInputRejected: a sample the service could not convert, or whose range checks
/// failed; issue 12): dl/pose while a command runs -> SAPP at once (motion stops, as MER's
/// manager did on a bad pose); dl/range_image of the pending request -> IMG; dl/relative_pose
/// while waiting for visual odometry -> a failed VO step; dl/drive_status -> not a report: the
/// drive's status time-out runs on (MOT when it expires, naming the rejection). Stale inputs are
/// the time-outs above (pose_stale_s, image_timeout_s, drive_status_timeout_s).
///
/// Fault classes (seed 000 Table 1): a goal error ends the command and leaves the rover ready;
/// a motion error ends it, latches, and refuses every motion command (with the latched fault)
/// until CLEAR_FAULT. Rejections at command time (BAD_COMMAND, BUSY, ACM, a latched motion
/// error, stale pose) start no motion; BUSY leaves the running command running.

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "rover/apl/mobility/mobility_options.hpp"
#include "rover/apl/mobility/mobility_types.hpp"
#include "rover/apl/mobility/motion_geometry.hpp"
#include "rover/apl/nav_core/arc_selector.hpp"
#include "rover/apl/nav_core/global_planner.hpp"
#include "rover/apl/nav_core/terrain_assessor.hpp"
#include "rover/msg/navigation.hpp"

namespace rover::apl::mobility {

/// One decision's votes (apl/arc_votes).
struct ArcVotesSnapshot {
  Time stamp;
  std::uint32_t command_id = 0;
  std::uint32_t step = 0;
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  nav_core::ArcEvaluation evaluation;
};

/// The apl/arc_votes value of a snapshot: one vote per candidate (votes clamped to 0..255,
/// directions as their sign), `chosen` as the evaluation's index (the conversion to the wire
/// carries the first msg::kMaxArcVotes and turns a chosen beyond them into -1).
msg::ArcVotes ArcVotesOf(const ArcVotesSnapshot& s);

/// What to send and publish after an input, in order.
struct MobilityOutput {
  std::vector<DriveCommand> drives;
  std::vector<RangeRequest> range_requests;
  std::vector<MastCommand> mast_requests;
  std::vector<MobilityStatus> statuses;
  std::optional<nav_core::GoodnessMap> goodness_map;  ///< after an assessment
  std::vector<ArcVotesSnapshot> arc_votes;
  std::vector<std::string> notes;  ///< for the service's log: "range request 7 ... sent again"
  bool empty() const {
    return drives.empty() && range_requests.empty() && mast_requests.empty() && statuses.empty() &&
           !goodness_map && arc_votes.empty();
  }
};

/// Time and work counters over the manager's life (for the m/h benchmark).
struct MotionCounters {
  double moving_s = 0.0;  ///< [s] running with a drive primitive outstanding
  double still_s = 0.0;   ///< [s] running without one (imaging, thinking, VO, steering waits)
  int drives = 0;
  int images = 0;          ///< range images requested
  int images_skipped = 0;  ///< autonav steps that skipped imaging (all paths known safe)
  int images_while_driving = 0;
  int goal_facing_turns = 0;  ///< single-arc planners: turns to face a goal no arc reaches
  double distance = 0.0;  ///< [m] path length reported by locomotion
};

/// The manager's inputs, for OnInputRejected.
enum class MobilityInput { kPose, kRangeImage, kDriveStatus, kVisOdom, kMastStatus };
/// "dl/pose", "dl/range_image", "dl/drive_status", "dl/relative_pose", "dl/mast_status".
const char* MobilityInputTopic(MobilityInput input);

class MobilityManager {
 public:
  /// Errors: InvalidArgument naming the field when options.Validate() fails, or a null
  /// assessor or selector. The planner may be null (LONG_TRAVERSE is then rejected).
  static Result<MobilityManager> Create(const MobilityOptions& options,
                                        std::unique_ptr<nav_core::TerrainAssessor> assessor,
                                        std::unique_ptr<nav_core::ArcSelector> selector,
                                        std::unique_ptr<nav_core::GlobalPlanner> planner = nullptr);

  MobilityOutput OnCommand(const MobilityCommand& command, Time now);
  /// Samples older than the stored one are ignored; non-finite ones count as SAPP while a
  /// command runs. A jump while idle clears the terrain map (it cannot be trusted).
  MobilityOutput OnPose(const PoseSample& pose, Time now);
  /// A range image for request `request_id` from `camera`. Images of requests this manager did
  /// not make (or no longer waits for) are ignored.
  MobilityOutput OnRangeImage(const nav_core::RangeScan& scan, CameraId camera,
                              std::uint32_t request_id, Time now);
  /// Reports of drive commands this manager did not send are ignored (apart from BUSY ones).
  MobilityOutput OnDriveStatus(const DriveStatus& report, Time now);
  MobilityOutput OnMastStatus(const MastStatus& report, Time now);
  /// A dl/relative_pose: only visual-odometry results count (other sources are ignored); a
  /// status other than CONVERGED is a failed VO step.
  MobilityOutput OnVisOdom(const RelativePose& result, Time now);
  /// A sample of `input` that could not be used (`why`: the conversion's message); for a range
  /// image, `request_id` is the id it carried. See "Input faults" above.
  MobilityOutput OnInputRejected(MobilityInput input, const std::string& why, Time now,
                                 std::uint32_t request_id = 0);
  /// Time-outs and the periodic running status.
  MobilityOutput Step(Time now);

  /// ACM: the software enable (initially options().software_enable).
  void SetSoftwareEnable(bool enable) { software_enable_ = enable; }

  bool busy() const { return run_.has_value(); }
  bool motion_error_latched() const { return latched_ != Fault::kNone; }
  Fault latched_fault() const { return latched_; }
  /// The latest status (of the running or the last command).
  const MobilityStatus& status() const { return status_; }
  const MotionCounters& counters() const { return counters_; }
  const MobilityOptions& options() const { return options_; }
  const nav_core::TerrainAssessor& assessor() const { return *assessor_; }
  const nav_core::ArcSelector& selector() const { return *selector_; }

  /// The command checks of OnCommand without the state ones (BUSY, ACM, latch, pose): Ok or
  /// InvalidArgument naming the field and value ("tolerance = -1 m is outside [0, inf)").
  Status ValidateCommand(const MobilityCommand& command) const;

 private:
  enum class Purpose { kStep, kThink };
  struct PendingImage {
    std::uint32_t request_id = 0;            ///< the latest send's
    std::vector<std::uint32_t> earlier_ids;  ///< earlier sends of the same request (re-sent)
    CameraId camera = CameraId::kFrontHazcam;
    Time first_sent;  ///< image_timeout_s counts from here
    Time sent;        ///< the latest send
    Purpose purpose = Purpose::kStep;
    bool Answers(std::uint32_t id) const;
  };
  struct PendingDrive {
    std::uint32_t command_id = 0;
    Primitive primitive;
    Time sent;
    Time deadline;
    Time last_report;           // the latest dl/drive_status of this drive (or `sent`)
    std::string rejected_note;  // the latest dl/drive_status rejected meanwhile
    bool guarded_check_done = false;
  };
  struct Run {
    MobilityCommand command;
    Time start;
    std::optional<Time> deadline;      // time budget
    std::optional<Time> tod_deadline;  // Mars time of day
    double tolerance = 0.0;
    double max_tilt = 0.0;
    int max_steps = 0;
    bool think = false;
    std::deque<Primitive> queue;            // directed / guarded pieces still to drive
    int blind_pieces = 0;                   // guarded arc: leading pieces that run blind
    std::vector<Eigen::Vector2d> goals;     // long traverse legs (last = the goal)
    std::optional<Primitive> guarded_next;  // guarded piece waiting for its image
    std::optional<Primitive> path_next;     // autonav: the chosen path's arc after its turn
    std::deque<CameraId> camera_queue;      // further images this step needs
    std::optional<PendingImage> image;
    std::optional<PendingDrive> drive;
    std::optional<Time> vo_since;     // waiting for a VO result since
    Time vo_after;                    // VO results must end after this (the last drive's start)
    bool think_image_merged = false;  // an image was merged while the last arc drove
    std::uint32_t steps = 0;
    std::uint32_t images = 0;
    int vo_failures = 0;
    double distance_driven = 0.0;
    std::vector<double> goal_distance_history;  // at each step end
    std::vector<Eigen::Vector2d> position_history;  // site x, y at the same step ends
    int last_direction = 0;                     // of the last arc driven: +1, -1, 0 none yet
    int limit_cycle_turns = 0;                  // limit-cycle turns taken
    Time last_status;
  };

  MobilityManager(const MobilityOptions& options,
                  std::unique_ptr<nav_core::TerrainAssessor> assessor,
                  std::unique_ptr<nav_core::ArcSelector> selector,
                  std::unique_ptr<nav_core::GlobalPlanner> planner);

  // Command handling.
  void Reject(const MobilityCommand& command, Time now, Fault fault, const std::string& message,
              MobilityOutput* out);
  void Start(const MobilityCommand& command, Time now, MobilityOutput* out);
  void Finish(Time now, State state, Fault fault, const std::string& message, MobilityOutput* out);
  void EmitStatus(Time now, MobilityOutput* out);
  // The step loop.
  void NextStep(Time now, MobilityOutput* out);
  bool CheckLimits(Time now, MobilityOutput* out);
  void AutonavStep(Time now, MobilityOutput* out);
  bool LimitCycleTurn(Time now, MobilityOutput* out);
  void GuardedStep(Time now, MobilityOutput* out);
  void WaypointStep(Time now, MobilityOutput* out);
  void ChooseAndDrive(Time now, const nav_core::ArcEvaluation& eval, MobilityOutput* out);
  void RequestImage(CameraId camera, Purpose purpose, Time now, MobilityOutput* out);
  bool SendDrive(const Primitive& p, Time now, MobilityOutput* out);
  void StartThinking(const Primitive& p, Time now, MobilityOutput* out);
  void StepDone(Time now, MobilityOutput* out);
  void SendStop(Time now, MobilityOutput* out);
  // Helpers.
  Result<nav_core::ArcEvaluation> Evaluate(const Pose2& from, Time now) const;
  Eigen::Vector2d CurrentGoal() const;
  double DistanceToGoal() const;
  // [m] of the arc (curvature, direction) from `from` to drive this step (before VO's limit):
  // step_length, or, when the final goal lies within step_length + tolerance and the planner
  // checks that far (ArcSelector::ChecksDriveLength), as far as the point of the arc nearest
  // the goal (the last step ends at the goal, not at its tolerance).
  double ArcStepLength(const Pose2& from, double curvature, int direction) const;
  // Appends the distance to the goal and the position to the progress window (at each step
  // end); ResetProgress starts the window again from here (a new leg, a limit-cycle turn).
  void RecordProgress();
  void ResetProgress();
  // The NOPROGRESS test over the last progress_steps steps: neither the straight-line distance
  // to the goal nor the planner's cost-to-go (when it keeps one) fell by min_progress_m.
  // Fills *why with the figures when there was none.
  bool NoProgress(std::string* why) const;
  bool PoseFresh(Time now, std::string* why) const;
  CameraId CameraFor(const nav_core::ArcEvaluation& eval) const;
  std::vector<Primitive> SplitForVisOdom(const Primitive& p) const;
  void Account(Time now);

  MobilityOptions options_;
  std::unique_ptr<nav_core::TerrainAssessor> assessor_;
  std::unique_ptr<nav_core::ArcSelector> selector_;
  std::unique_ptr<nav_core::GlobalPlanner> planner_;
  bool software_enable_ = true;
  Fault latched_ = Fault::kNone;
  std::optional<PoseSample> pose_;
  bool pose_bad_ = false;  // non-finite or jumping since the last good sample
  std::string pose_bad_why_;
  std::optional<Run> run_;
  MobilityStatus status_;
  MotionCounters counters_;
  std::optional<Time> last_account_;
  std::uint32_t next_id_ = 0;
};

}  // namespace rover::apl::mobility
