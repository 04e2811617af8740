// dl-arm: the instrument arm: joint moves, guarded placements, stowing (see arm_service.hpp).
#include "arm_service.hpp"

int main(int argc, char** argv) {
  rover::dl::arm::ArmService service;
  return rover::RunServiceMain(service, argc, argv);
}
