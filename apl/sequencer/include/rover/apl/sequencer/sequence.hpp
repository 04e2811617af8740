#pragma once
/// @file
/// A parsed sequence: the syntax tree the parser builds (parser.hpp) and the interpreter runs
/// (interpreter.hpp). Every value in it is resolved and checked: numbers are in their
/// argument's or quantity's unit (command_table.hpp, condition.hpp), TARGET and CONST names are
/// replaced by their values (the name is kept for messages), and each command and WAIT has its
/// step number. A Sequence only comes out of a parse without errors.

#include <map>
#include <string>
#include <vector>

#include "rover/apl/sequencer/command_table.hpp"

namespace rover::apl::sequencer {

/// A site-frame point [m].
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  friend bool operator==(const Vec3&, const Vec3&) = default;
};

/// 1-based line and column (column counts bytes; a tab is one column). Line 0 = not from the
/// sequence text (an override given to the parser).
struct SourcePos {
  int line = 0;
  int column = 0;
  friend bool operator==(const SourcePos&, const SourcePos&) = default;
};

/// One resolved argument value.
struct ArgValue {
  ArgType type = ArgType::kNumber;
  double number = 0.0;          ///< kNumber, kInteger: in the argument's unit
  std::vector<double> numbers;  ///< kPoint2 (x, y), kPoint3 (x, y, z), kPixel (u, v), kTuple
  std::string word;             ///< kWord, upper case
  std::string name;             ///< the TARGET or CONST written, "" for a literal
  bool given = false;           ///< false: filled from the table's default
  SourcePos pos;
};

/// One command statement.
struct CommandCall {
  CommandKind kind = CommandKind::kStop;
  std::map<std::string, ArgValue> args;  ///< given ones plus defaults of absent optional ones
  bool continue_on_goal_error = false;   ///< on_fault=CONTINUE
  std::string text;                      ///< the statement as written (comment stripped)
  SourcePos pos;

  const CommandSpec& spec() const { return SpecOf(kind); }
  bool Has(const std::string& arg) const { return args.count(arg) > 0; }
  /// Preconditions: Has(arg).
  const ArgValue& Get(const std::string& arg) const;
};

/// What a condition can look at (see condition.hpp for units and meaning).
enum class Quantity {
  kLastTermination,  ///< last.termination: NONE NOMINAL FAULT REJECTED
  kLastFault,        ///< last.fault: NONE and the Fault names
  kLastClass,        ///< last.class: NONE GOAL_ERROR MOTION_ERROR
  kDistanceTo,       ///< distance_to(target) [m]
  kVisodomFailures,  ///< visodom.failures [count]
  kTilt,             ///< tilt [deg]
  kElapsed,          ///< elapsed [s] since the sequence started
};

enum class Relation { kEq, kNe, kLt, kLe, kGt, kGe };

/// `quantity relation value`.
struct Comparison {
  Quantity quantity = Quantity::kLastTermination;
  Relation relation = Relation::kEq;
  double number = 0.0;  ///< numeric quantities, in the quantity's unit
  int enum_value = 0;   ///< enumerated quantities: the Termination, Fault::Index() or msg::FaultClass value
  Vec3 point;           ///< kDistanceTo: the point
  std::string name;     ///< kDistanceTo: the TARGET name ("" for a literal point)
};

struct Condition {
  enum class Op { kCompare, kAnd, kOr, kNot };
  Op op = Op::kCompare;
  Comparison compare;               ///< kCompare
  std::vector<Condition> operands;  ///< kAnd, kOr: two or more; kNot: one
  std::string text;                 ///< as written
  SourcePos pos;
};

struct Statement {
  enum class Kind { kCommand, kWait, kWaitUntil, kIf, kRepeat, kWhile };
  Kind kind = Kind::kCommand;
  SourcePos pos;
  int step = 0;             ///< kCommand, kWait, kWaitUntil: step number (1-based)
  CommandCall command;      ///< kCommand
  double seconds = 0.0;     ///< kWait: duration; kWaitUntil: TIMEOUT [s]
  Condition condition;      ///< kWaitUntil, kIf, kWhile
  int count = 0;            ///< kRepeat: n; kWhile: MAX n
  std::vector<Statement> body;       ///< kIf: then-branch; kRepeat, kWhile: loop body
  std::vector<Statement> else_body;  ///< kIf (ELSE IF is an IF alone in here)
  std::string text;                  ///< the line as written
};

/// A named CONST: a number and the unit it was written in ("" = none).
struct Constant {
  double value = 0.0;
  std::string unit;
};

/// One step (a command or a WAIT) for status reports.
struct StepInfo {
  int line = 0;
  std::string text;
};

struct Sequence {
  std::string source;                ///< name for messages ("approach.seq")
  std::vector<Statement> statements;
  std::vector<Statement> on_abort;   ///< the ON_ABORT block, empty when there is none
  std::map<std::string, Vec3> targets;
  std::map<std::string, Constant> constants;
  std::vector<StepInfo> steps;       ///< steps[i] describes step i + 1
};

}  // namespace rover::apl::sequencer
