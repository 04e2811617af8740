// ddl-motor: the motor driver service. See motor_service.hpp and docs/services/ddl-motor.md.
#include "motor_service.hpp"

int main(int argc, char** argv) {
  rover::ddl::motor::MotorService service;
  return rover::RunServiceMain(service, argc, argv);
}
