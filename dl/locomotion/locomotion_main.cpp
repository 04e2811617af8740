// dl-locomotion: MER-style drive primitives on the rover (see locomotion_service.hpp).
#include "locomotion_service.hpp"

int main(int argc, char** argv) {
  rover::dl::locomotion::LocomotionService service;
  return rover::RunServiceMain(service, argc, argv);
}
