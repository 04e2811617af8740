// apl-mobility: MER's Mobility Manager with GESTALT (see mobility_service.hpp).
#include "mobility_service.hpp"

int main(int argc, char** argv) {
  rover::apl::mobility::MobilityService service;
  return rover::RunServiceMain(service, argc, argv);
}
