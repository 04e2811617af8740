#pragma once
/// @file
/// apl/mobility_command and apl/mobility_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include <vector>

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/mobility.hpp"

namespace rover::msg {

/// An apl/mobility_command C struct and the storage its sequences point at. Keep it alive until
/// the write returns; copying it re-points the copy's sequences at the copy's storage.
struct MobilityCommandMessage {
  rover_apl_MobilityCommand msg{};
  std::vector<rover_apl_MobilityPrimitive> primitives;
  std::vector<rover_apl_KeepOutZone> zones;
  std::vector<std::vector<rover_apl_Point2>> vertices;  ///< one per zone

  MobilityCommandMessage() = default;
  MobilityCommandMessage(const MobilityCommandMessage& o) { *this = o; }
  MobilityCommandMessage& operator=(const MobilityCommandMessage& o);
  /// Points msg's sequences at this holder's vectors (after changing them).
  void Repoint();
};

/// A command: mode, think and primitive values are kept as they are (the mobility manager
/// rejects an unknown one BAD_COMMAND, naming the field); numbers are copied as they are.
MobilityCommand MobilityCommandFromIdl(const rover_apl_MobilityCommand& in);
/// Fills `out` (which owns the sequences' storage). Names are truncated to 31 characters,
/// max_steps clamped to 0..65535; an unknown primitive value is sent as it is. Longer
/// primitive, zone or vertex lists than the IDL bounds are sent whole (the writer refuses them).
void MobilityCommandToIdl(const MobilityCommand& in, MobilityCommandMessage* out);

/// Errors: a mode, state, fault class or fault value no enumerator has (naming the field).
Result<MobilityStatus> MobilityStatusFromIdl(const rover_apl_MobilityStatus& in);
/// The message is truncated to 127 characters.
void MobilityStatusToIdl(const MobilityStatus& in, rover_apl_MobilityStatus* out);

}  // namespace rover::msg
