#pragma once
/// @file
/// Who may write and read each catalog topic, by role: every rover service executable, the
/// operator tools and roverctl's own participants (the scenario runner with its recorder, the
/// standalone recorder and replayer, the fault controller and the supervisor), and
/// rover-dds-bench on its own bench/ topics. No DDS calls.
///
/// This is what DDS Security's permissions are made from (deploy/security): a role may publish
/// exactly the topics it writes and subscribe to those it reads, nothing else. docs/topics.md
/// lists the same publishers and subscribers for people; a test keeps the two in step.
///
/// Every rover service also uses the harness's own topics (kServiceWrites, kServiceReads:
/// heartbeats, events, fault control and the lock-step clock), whatever its role.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rover::dds {

struct RoleAccess {
  std::string_view role;  ///< executable name ("dl-pose") or roverctl's participant ("recorder")
  std::string_view summary;
  bool service = true;    ///< a rover service: also kServiceWrites / kServiceReads
  std::vector<std::string_view> writes;  ///< catalog topics; "*" = every catalog topic
  std::vector<std::string_view> reads;
};

/// Topics the service harness (core/runtime service.cpp, fault_control.cpp) writes and reads in
/// every rover service.
inline constexpr std::string_view kServiceWrites[] = {"sys/health", "sys/event",
                                                      "sys/fault_event", "sim/clock_ack"};
inline constexpr std::string_view kServiceReads[] = {"sim/clock", "sys/fault_control"};

/// Every role, sorted by name.
const std::vector<RoleAccess>& RoleAccessTable();
/// The role's entry, or nullopt.
std::optional<RoleAccess> FindRole(std::string_view role);
/// The topics `role` writes (or reads), the harness's included for services and "*" expanded
/// to the catalog's names; sorted, unique. Empty for an unknown role.
std::vector<std::string> TopicsWritten(std::string_view role);
std::vector<std::string> TopicsRead(std::string_view role);

}  // namespace rover::dds
