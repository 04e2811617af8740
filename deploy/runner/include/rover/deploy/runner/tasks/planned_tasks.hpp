#pragma once
/// @file
/// The task types scenarios may already name but this stack cannot run yet, because the services
/// they command do not exist: long_traverse (a `goal` is required) and
/// science_target (`goal` optional). Each parses and validates its section
/// (keys `type` and `goal`) like a real task, so a scenario written for them is checked today;
/// a run of one starts the set, then fails saying which services are missing. The application
/// layer replaces each of these with its real task (apl/mobility_command, apl/rendezvous_command,
/// ...): register the real factory instead of the entry here.

#include "rover/deploy/runner/task.hpp"

namespace rover::deploy::runner {

/// Registers long_traverse and science_target (autonav and goto_waypoint are real
/// tasks now: tasks/mobility_task.hpp).
void RegisterPlannedTasks(TaskRegistry& registry);

}  // namespace rover::deploy::runner
