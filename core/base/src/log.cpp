#include "rover/base/log.hpp"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

namespace rover::log {
namespace {

struct State {
  std::mutex mutex;
  std::string name = "rover";
  Format format = Format::kText;
  std::atomic<int> min_level{static_cast<int>(Level::kInfo)};
  Sink sink;
  Level sink_level = Level::kWarning;
  std::shared_ptr<spdlog::logger> logger;
};

State& GetState() {
  static State s;
  return s;
}

std::shared_ptr<spdlog::logger> MakeLogger() {
  auto sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  auto logger = std::make_shared<spdlog::logger>("rover", sink);
  logger->set_level(spdlog::level::trace);
  logger->flush_on(spdlog::level::trace);
  // The message is already fully formatted; only add nothing.
  logger->set_pattern("%v");
  return logger;
}

std::string Escape(std::string_view s, bool json) {
  std::string out;
  out.reserve(s.size() + 2);
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (json && static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

bool NeedsQuotes(std::string_view s) {
  if (s.empty()) return true;
  for (char c : s) {
    if (c == ' ' || c == '"' || c == '=' || c == '\\' || static_cast<unsigned char>(c) < 0x20)
      return true;
  }
  return false;
}

std::string IsoUtcNow() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  tm t{};
  gmtime_r(&ts.tv_sec, &t);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", t.tm_year + 1900,
                t.tm_mon + 1, t.tm_mday, t.tm_hour, t.tm_min, t.tm_sec,
                static_cast<int>(ts.tv_nsec / 1000000));
  return buf;
}

}  // namespace

std::string Field::FormatNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
std::string Field::FormatNumber(long long v) { return std::to_string(v); }

const char* LevelName(Level level) {
  switch (level) {
    case Level::kDebug: return "debug";
    case Level::kInfo: return "info";
    case Level::kWarning: return "warn";
    case Level::kError: return "error";
  }
  return "?";
}

bool ParseLevel(std::string_view text, Level* level) {
  if (text == "debug") *level = Level::kDebug;
  else if (text == "info") *level = Level::kInfo;
  else if (text == "warn" || text == "warning") *level = Level::kWarning;
  else if (text == "error") *level = Level::kError;
  else return false;
  return true;
}

void Init(std::string_view name, Level min_level, Format format) {
  State& s = GetState();
  std::lock_guard lock(s.mutex);
  s.name = std::string(name);
  s.min_level = static_cast<int>(min_level);
  s.format = format;
  if (!s.logger) s.logger = MakeLogger();
}

void InitFromEnvironment(std::string_view name) {
  Level level = Level::kInfo;
  if (const char* l = std::getenv("ROVER_LOG_LEVEL")) {
    if (!ParseLevel(l, &level)) level = Level::kInfo;
  }
  Format format = Format::kText;
  if (const char* f = std::getenv("ROVER_LOG_FORMAT")) {
    if (std::string_view(f) == "json") format = Format::kJson;
  }
  Init(name, level, format);
}

void SetLevel(Level level) { GetState().min_level = static_cast<int>(level); }
Level GetLevel() { return static_cast<Level>(GetState().min_level.load()); }

void SetSink(Sink sink, Level min_level) {
  State& s = GetState();
  std::lock_guard lock(s.mutex);
  s.sink = std::move(sink);
  s.sink_level = min_level;
}

void Write(Level level, std::string_view message, std::initializer_list<Field> fields) {
  State& s = GetState();
  if (static_cast<int>(level) < s.min_level.load()) return;
  std::string field_text;
  for (const Field& f : fields) {
    field_text += ' ';
    field_text += f.key;
    field_text += '=';
    if (f.quoted && NeedsQuotes(f.value)) {
      field_text += '"' + Escape(f.value, false) + '"';
    } else {
      field_text += f.value;
    }
  }
  std::string line;
  Sink sink;
  {
    std::lock_guard lock(s.mutex);
    if (!s.logger) s.logger = MakeLogger();
    if (s.format == Format::kJson) {
      line = "{\"time\":\"" + IsoUtcNow() + "\",\"level\":\"" + LevelName(level) +
             "\",\"service\":\"" + Escape(s.name, true) + "\",\"msg\":\"" +
             Escape(message, true) + "\"";
      for (const Field& f : fields) {
        line += ",\"" + Escape(f.key, true) + "\":";
        line += f.quoted ? "\"" + Escape(f.value, true) + "\"" : f.value;
      }
      line += "}";
    } else {
      char lvl[8];
      std::snprintf(lvl, sizeof lvl, "%-5s", LevelName(level));
      line = IsoUtcNow() + " " + lvl + " " + s.name + " msg=\"" + Escape(message, false) + "\"" +
             field_text;
    }
    s.logger->info(line);
    if (s.sink && level >= s.sink_level) sink = s.sink;
  }
  if (sink) sink(level, message, field_text);
}

}  // namespace rover::log
