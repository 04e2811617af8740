#pragma once
/// @file
/// sim/truth <-> TruthSample, field by field (rover_sim.idl). The header's stamp is the
/// sample's time (time_s <-> header.stamp_ns); the sender sets frame and sequence number.

#include "rover/idl/types.hpp"
#include "rover/sim/rover_sim/sim_engine.hpp"

namespace rover::sim::rover_sim {

void TruthToIdl(const TruthSample& in, rover_sim_Truth* out);
TruthSample TruthFromIdl(const rover_sim_Truth& in);

}  // namespace rover::sim::rover_sim
