#include "tools/drive_cli.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>

#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/msg/drive_idl.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::dl::locomotion::tools {
namespace {

constexpr const char* kProgram = "rover-drive";
constexpr const char* kPrimitives = "arc, straight, turn, steer, stop";

ParseOutcome Error(const std::string& message) {
  ParseOutcome out;
  out.exit_code = kExitBadArguments;
  out.output = std::string(kProgram) + ": error: " + message + " (see rover-drive --help)\n";
  out.output_is_error = true;
  return out;
}

}  // namespace

ParseOutcome ParseDriveCli(int argc, const char* const* argv, const char* env_domain,
                           const char* env_clock) {
  DriveCliOptions o;
  CLI::App app{
      "rover-drive: send one drive primitive on dl/drive_command and print every dl/drive_status "
      "of it until it is DONE, FAILED or REJECTED. Exit code 0 only for DONE.",
      kProgram};
  app.require_subcommand(1, 1);
  CLI::Option* domain_opt =
      app.add_option("--domain", o.domain, "DDS domain id (default: $ROVER_DOMAIN, else 0)");
  CLI::Option* clock_opt =
      app.add_option("--clock", o.clock,
                     "run clock that stamps the command: wall or sim ($ROVER_CLOCK, else wall)");
  app.add_option("--timeout", o.timeout_s,
                 "wall seconds to wait for a terminal status (a harness limit)")
      ->capture_default_str();
  app.add_option("--speed", o.speed, "[m/s] speed; 0 = the service's default")
      ->capture_default_str();
  app.add_option("--drive-timeout", o.drive_timeout_s,
                 "[s] run-clock time limit of the primitive; 0 = derived by the service")
      ->capture_default_str();
  app.add_option("--id", o.command_id, "command id (default: derived from the time and pid)");
  app.add_flag("--raw", o.raw, "send the values unchecked (to test the service's validation)");

  CLI::App* arc = app.add_subcommand("arc", "drive --distance along an arc of --curvature");
  arc->add_option("--curvature", o.curvature, "[1/m] positive turns left")->required();
  arc->add_option("--distance", o.distance, "[m] along the path; negative drives backwards")
      ->required();
  CLI::App* straight = app.add_subcommand("straight", "drive --distance straight");
  straight->add_option("--distance", o.distance, "[m]; negative drives backwards")->required();
  CLI::App* turn = app.add_subcommand("turn", "turn in place by --angle-deg (or --angle)");
  double angle_deg = 0.0, angle_rad = 0.0;
  CLI::Option* a_deg = turn->add_option("--angle-deg", angle_deg, "[deg] positive = left");
  CLI::Option* a_rad = turn->add_option("--angle", angle_rad, "[rad] positive = left");
  a_deg->excludes(a_rad);
  CLI::App* steer = app.add_subcommand("steer", "point the corner wheels for --curvature");
  steer->add_option("--curvature", o.curvature, "[1/m] positive turns left")->required();
  CLI::App* stop = app.add_subcommand("stop", "brake every mobility motor now");
  for (CLI::App* sub : {arc, straight, turn, steer, stop}) sub->fallthrough();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    ParseOutcome out;
    out.exit_code = 0;
    out.output = app.help();
    return out;
  } catch (const CLI::CallForAllHelp&) {
    ParseOutcome out;
    out.exit_code = 0;
    out.output = app.help("", CLI::AppFormatMode::All);
    return out;
  } catch (const CLI::ParseError& e) {
    if (app.get_subcommands().empty()) {
      // No primitive recognised: name the word that was meant to be one, if any.
      for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const std::string prev = i > 1 ? argv[i - 1] : "";
        const bool is_value = prev.rfind("--", 0) == 0 && prev != "--raw";
        if (a.rfind("-", 0) != 0 && !is_value) {
          return Error("unknown primitive '" + a + "' (expected one of: " + kPrimitives + ")");
        }
      }
      if (std::string(e.what()).find("subcommand") != std::string::npos) {
        return Error(std::string("a primitive is required: one of ") + kPrimitives);
      }
    }
    return Error(e.what());
  }

  if (arc->parsed()) o.primitive = DrivePrimitive::kArc;
  if (straight->parsed()) o.primitive = DrivePrimitive::kStraight;
  if (steer->parsed()) o.primitive = DrivePrimitive::kSteer;
  if (stop->parsed()) o.primitive = DrivePrimitive::kStop;
  if (turn->parsed()) {
    o.primitive = DrivePrimitive::kTurnInPlace;
    if (a_deg->count() == 0 && a_rad->count() == 0) {
      return Error("turn needs --angle-deg A [deg] or --angle A [rad]");
    }
    o.angle = a_deg->count() > 0 ? angle_deg * kDegree : angle_rad;
  }

  if (domain_opt->count() == 0 && env_domain != nullptr && *env_domain != '\0') {
    char* end = nullptr;
    const long v = std::strtol(env_domain, &end, 10);
    if (end == env_domain || *end != '\0' || v < 0 || v > 232) {
      return Error(std::string("ROVER_DOMAIN '") + env_domain +
                   "' is not a domain id (an integer in [0, 232])");
    }
    o.domain = static_cast<int>(v);
  }
  if (clock_opt->count() == 0 && env_clock != nullptr && *env_clock != '\0') {
    o.clock = env_clock;
  }
  if (o.clock != "wall" && o.clock != "sim") {
    return Error("--clock '" + o.clock + "' is not one of: wall, sim");
  }
  if (o.domain < 0 || o.domain > 232) {
    return Error("--domain " + std::to_string(o.domain) + " is out of range [0, 232]");
  }
  if (!o.raw) {
    const Status s = CheckDriveOptions(o);
    if (!s.ok()) return Error(s.message());
  }
  ParseOutcome out;
  out.options = o;
  return out;
}

Status CheckDriveOptions(const DriveCliOptions& o) {
  if (o.domain < 0 || o.domain > 232) {
    return InvalidArgument("--domain " + std::to_string(o.domain) + " is out of range [0, 232]");
  }
  if (!std::isfinite(o.timeout_s) || o.timeout_s <= 0.0) {
    return InvalidArgument("--timeout " + FormatNumber(o.timeout_s) +
                           " must be > 0 (wall seconds)");
  }
  struct Field {
    const char* flag;
    double value;
  };
  const Field fields[] = {{"--curvature", o.curvature},
                          {"--distance", o.distance},
                          {"--angle", o.angle},
                          {"--speed", o.speed},
                          {"--drive-timeout", o.drive_timeout_s}};
  for (const Field& f : fields) {
    if (!std::isfinite(f.value)) {
      return InvalidArgument(std::string(f.flag) + " " + FormatNumber(f.value) +
                             " must be a finite number");
    }
  }
  if (o.speed < 0.0) {
    return InvalidArgument("--speed " + FormatNumber(o.speed) + " m/s must be >= 0 (0 = default)");
  }
  if (o.drive_timeout_s < 0.0) {
    return InvalidArgument("--drive-timeout " + FormatNumber(o.drive_timeout_s) +
                           " s must be >= 0 (0 = derived)");
  }
  return Status::Ok();
}

rover_dl_DriveCommand MakeDriveCommand(const DriveCliOptions& o, std::uint32_t command_id,
                                       std::int64_t stamp_ns) {
  DriveCommand d;
  d.stamp = Time{stamp_ns};
  d.command_id = command_id;
  d.primitive = o.primitive;
  d.curvature = o.curvature;
  d.distance = o.distance;
  d.angle = o.angle;
  d.speed = o.speed;
  d.timeout_s = o.drive_timeout_s;
  rover_dl_DriveCommand c{};
  dds::CopyString(c.header.frame_id, "rover");
  c.header.seq = 1;
  msg::DriveCommandToIdl(d, &c);
  return c;
}

std::string FormatDriveStatus(const rover_dl_DriveStatus& s) {
  char head[160];
  std::snprintf(
      head, sizeof(head), "t=%.3f s  #%u %s %s", static_cast<double>(s.header.stamp_ns) * 1e-9,
      s.command_id,
      DrivePrimitiveName(static_cast<DrivePrimitive>(static_cast<std::int32_t>(s.primitive))),
      DriveStateName(static_cast<DriveState>(static_cast<std::int32_t>(s.state))));
  std::string line = head;
  if (s.termination != rover_dl_TERMINATION_NONE) {
    line += std::string(" (") +
            DriveTerminationName(
                static_cast<DriveTermination>(static_cast<std::int32_t>(s.termination))) +
            ")";
  }
  char tail[96];
  std::snprintf(tail, sizeof(tail), "  distance %.3f m  heading %.1f deg", s.distance_done,
                s.heading_change / kDegree);
  line += tail;
  const std::string message(s.message, strnlen(s.message, sizeof(s.message)));
  if (!message.empty()) line += "  " + message;
  return line;
}

bool IsTerminal(const rover_dl_DriveStatus& s) {
  return s.state == rover_dl_DRIVE_DONE || s.state == rover_dl_DRIVE_FAILED ||
         s.state == rover_dl_DRIVE_REJECTED;
}

}  // namespace rover::dl::locomotion::tools
