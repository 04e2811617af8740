// ddl-joints: encoder and potentiometer reader service. See joints_service.hpp and
// docs/services/ddl-joints.md.
#include "joints_service.hpp"

int main(int argc, char** argv) {
  rover::ddl::joints::JointsService service;
  return rover::RunServiceMain(service, argc, argv);
}
