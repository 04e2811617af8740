// apl-rendezvous: FIDO's visual rendezvous with the lander (see rendezvous_service.hpp).
#include "rendezvous_service.hpp"

int main(int argc, char** argv) {
  rover::apl::rendezvous::RendezvousService service;
  return rover::RunServiceMain(service, argc, argv);
}
