#pragma once
/// @file
/// Structured logging: one line per event, logfmt (`key=value`) or JSON, on stderr, e.g.
///   2026-11-22T01:02:03.456Z warn  drive-loco msg="tilt over limit" tilt_deg=31.2 limit_deg=30
/// A sink can be added (the runtime adds one that republishes warnings and errors on sys/event).

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>

namespace rover::log {

enum class Level { kDebug = 0, kInfo = 1, kWarning = 2, kError = 3 };
enum class Format { kText, kJson };

/// A key and its value already formatted as text.
struct Field {
  template <class T>
  Field(std::string_view k, const T& v) : key(k) {  // NOLINT(google-explicit-constructor)
    if constexpr (std::is_same_v<T, bool>) {
      value = v ? "true" : "false";
    } else if constexpr (std::is_arithmetic_v<T>) {
      value = FormatNumber(v);
    } else {
      value = std::string(std::string_view(v));
      quoted = true;
    }
  }
  std::string key;
  std::string value;
  bool quoted = false;

 private:
  static std::string FormatNumber(double v);
  static std::string FormatNumber(long long v);
  template <class N>
  static std::string FormatNumber(N v) {
    if constexpr (std::is_floating_point_v<N>) {
      return FormatNumber(static_cast<double>(v));
    } else {
      return FormatNumber(static_cast<long long>(v));
    }
  }
};

/// Sets the name printed on every line, the minimum level and the format. Safe to call again.
void Init(std::string_view name, Level min_level = Level::kInfo, Format format = Format::kText);
/// Reads ROVER_LOG_LEVEL (debug|info|warn|error) and ROVER_LOG_FORMAT (text|json) if set.
void InitFromEnvironment(std::string_view name);
void SetLevel(Level level);
Level GetLevel();

/// Called for every line at or above `min_level` with the level, message and formatted fields.
using Sink = std::function<void(Level, std::string_view message, std::string_view fields)>;
void SetSink(Sink sink, Level min_level);

void Write(Level level, std::string_view message, std::initializer_list<Field> fields = {});
inline void Debug(std::string_view m, std::initializer_list<Field> f = {}) { Write(Level::kDebug, m, f); }
inline void Info(std::string_view m, std::initializer_list<Field> f = {}) { Write(Level::kInfo, m, f); }
inline void Warn(std::string_view m, std::initializer_list<Field> f = {}) { Write(Level::kWarning, m, f); }
inline void Error(std::string_view m, std::initializer_list<Field> f = {}) { Write(Level::kError, m, f); }

const char* LevelName(Level level);
/// Parses "debug", "info", "warn"/"warning", "error".
bool ParseLevel(std::string_view text, Level* level);

}  // namespace rover::log
