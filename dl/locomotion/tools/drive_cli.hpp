#pragma once
/// @file
/// Command line of rover-drive, the operator tool that sends one drive primitive on
/// dl/drive_command and follows its dl/drive_status until it is terminal. Parsing, local checks,
/// the command sample and the status lines live here so they can be tested without DDS.
///
///   rover-drive [global options] <primitive> [primitive options]
///     arc      --curvature K [1/m] --distance S [m]
///     straight --distance S [m]
///     turn     --angle-deg A [deg] | --angle A [rad]     (positive = left, counter-clockwise)
///     steer    --curvature K [1/m]
///     stop
///   global: --domain N (else ROVER_DOMAIN, else 0), --clock wall|sim (else ROVER_CLOCK, else
///           wall; stamps the command), --timeout T (wall seconds the tool waits, a harness
///           limit; default 600), --speed V [m/s] (0 = the service's default),
///           --drive-timeout T (run-clock seconds for the primitive; 0 = derived by the service),
///           --id N (command id; default derived from the wall time and pid), --raw (skip the
///           local checks, to exercise the service's own validation).
/// Exit codes: 0 DONE, 1 FAILED / REJECTED / DDS failure, 2 bad arguments, 3 no terminal status
/// (or no dl-locomotion) within --timeout, 130 interrupted (a STOP was sent).

#include <cstdint>
#include <optional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/dl/locomotion/drive_types.hpp"
#include "rover/idl/types.hpp"

namespace rover::dl::locomotion::tools {

inline constexpr int kExitDone = 0;
inline constexpr int kExitNotDone = 1;
inline constexpr int kExitBadArguments = 2;
inline constexpr int kExitTimeout = 3;
inline constexpr int kExitInterrupted = 130;

struct DriveCliOptions {
  int domain = 0;
  std::string clock = "wall";
  double timeout_s = 600.0;      ///< [s] wall time the tool waits for a terminal status
  std::uint32_t command_id = 0;  ///< 0 = choose one
  DrivePrimitive primitive = DrivePrimitive::kStop;
  double curvature = 0.0;        ///< [1/m]
  double distance = 0.0;         ///< [m]
  double angle = 0.0;            ///< [rad]
  double speed = 0.0;            ///< [m/s]
  double drive_timeout_s = 0.0;  ///< [s] run clock
  bool raw = false;
};

/// What parsing decided: run with `options`, or exit at once with `exit_code` after printing
/// `output` (help text on stdout for --help; "rover-drive: error: ..." on stderr otherwise).
struct ParseOutcome {
  std::optional<DriveCliOptions> options;
  int exit_code = 0;
  std::string output;
  bool output_is_error = false;
};

/// Parses the command line. `env_domain` / `env_clock` are ROVER_DOMAIN / ROVER_CLOCK (nullptr
/// if unset). Never throws.
ParseOutcome ParseDriveCli(int argc, const char* const* argv, const char* env_domain,
                           const char* env_clock);

/// Local checks (skipped with --raw): finite values, speed >= 0, drive timeout >= 0, timeout
/// > 0, a domain in [0, 232]. The service checks the limits (curvature, distance, speed) itself
/// and answers REJECTED / INVALID with its reason.
Status CheckDriveOptions(const DriveCliOptions& o);

/// The dl/drive_command sample (header stamp `stamp_ns`, frame "rover", seq 1).
rover_dl_DriveCommand MakeDriveCommand(const DriveCliOptions& o, std::uint32_t command_id,
                                       std::int64_t stamp_ns);

/// One line per status, e.g.
///   "t=12.500 s  #42 ARC DRIVING  distance 0.512 m  heading 14.7 deg  driving".
std::string FormatDriveStatus(const rover_dl_DriveStatus& s);

/// DONE, FAILED or REJECTED.
bool IsTerminal(const rover_dl_DriveStatus& s);

}  // namespace rover::dl::locomotion::tools
