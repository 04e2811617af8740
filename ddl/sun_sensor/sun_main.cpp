// ddl-sun-sensor: the sun-sensor driver service. See sun_service.hpp and
// docs/services/ddl-sun-sensor.md.
#include "sun_service.hpp"

int main(int argc, char** argv) {
  rover::ddl::sun_sensor::SunService service;
  return rover::RunServiceMain(service, argc, argv);
}
