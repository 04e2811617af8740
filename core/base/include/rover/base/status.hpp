#pragma once
/// @file
/// Status and Result<T>: how functions report *bad user input* and *hardware or environment
/// faults* to their caller. Broken invariants (programming errors) are not reported this way;
/// they abort through ROVER_DEMAND (check.hpp). See docs/error-policy.md.

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace rover {

/// Why an operation failed.
enum class StatusCode {
  kOk = 0,
  kInvalidArgument,    ///< bad user input: parameter, file content, command field
  kNotFound,           ///< a named thing does not exist (file, key, camera, service)
  kFailedPrecondition, ///< valid request in the wrong state (e.g. activate before configure)
  kBusy,               ///< the resource is already doing something (MER's BUSY)
  kOutOfRange,         ///< a value outside its documented range
  kUnavailable,        ///< an external resource (DDS, file system, device) failed
  kTimeout,            ///< a deadline on the run clock passed
  kInternal,           ///< an unexpected failure of a library we depend on
};

/// Returns a stable lower-case name ("invalid_argument", ...).
const char* StatusCodeName(StatusCode code);

/// A success or an error code with a one-line, human-readable message that names what is wrong
/// (file, line, key, field) so that the user can fix it without reading code.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return {}; }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  /// "invalid_argument: <message>" or "ok".
  std::string ToString() const;

  /// Returns a copy whose message is "<prefix>: <message>".
  Status WithPrefix(const std::string& prefix) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status InvalidArgument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status NotFound(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status FailedPrecondition(std::string m) {
  return {StatusCode::kFailedPrecondition, std::move(m)};
}
inline Status OutOfRange(std::string m) { return {StatusCode::kOutOfRange, std::move(m)}; }
inline Status Unavailable(std::string m) { return {StatusCode::kUnavailable, std::move(m)}; }
inline Status Busy(std::string m) { return {StatusCode::kBusy, std::move(m)}; }
inline Status Timeout(std::string m) { return {StatusCode::kTimeout, std::move(m)}; }
inline Status Internal(std::string m) { return {StatusCode::kInternal, std::move(m)}; }

/// A value or an error Status.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Status status) : status_(std::move(status)) {  // NOLINT(google-explicit-constructor)
    if (status_.ok()) status_ = Internal("Result constructed from an ok Status without a value");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }

  /// Preconditions: ok().
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace rover

/// Returns early from the enclosing function if `expr` (a Status) is not ok.
#define ROVER_RETURN_IF_ERROR(expr)                 \
  do {                                              \
    ::rover::Status rover_status_tmp_ = (expr);     \
    if (!rover_status_tmp_.ok()) return rover_status_tmp_; \
  } while (false)

/// Evaluates `rexpr` (a Result<T>); returns its Status from the enclosing function if it is an
/// error, else moves the value into `lhs`, which may declare a variable:
///   ROVER_ASSIGN_OR_RETURN(auto writer, ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose"));
///   ROVER_ASSIGN_OR_RETURN(options_, DriveOptions::FromParams(params, "drive."));
/// The enclosing function must return Status or a Result<U>. `lhs` may not contain a
/// top-level comma (wrap such a type in a using-declaration).
#define ROVER_ASSIGN_OR_RETURN(lhs, rexpr) \
  ROVER_ASSIGN_OR_RETURN_IMPL_(ROVER_STATUS_CONCAT_(rover_result_, __LINE__), lhs, rexpr)

#define ROVER_STATUS_CONCAT_INNER_(a, b) a##b
#define ROVER_STATUS_CONCAT_(a, b) ROVER_STATUS_CONCAT_INNER_(a, b)
#define ROVER_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, rexpr) \
  auto tmp = (rexpr);                                 \
  if (!tmp.ok()) return tmp.status();                 \
  lhs = std::move(tmp).value()
