// ddl-imu: the IMU driver service. See imu_service.hpp and docs/services/ddl-imu.md.
#include "imu_service.hpp"

int main(int argc, char** argv) {
  rover::ddl::imu::ImuService service;
  return rover::RunServiceMain(service, argc, argv);
}
