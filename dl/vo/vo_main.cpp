// dl-vo: MER visual-odometry service (see vo_service.hpp and docs/services/dl-vo.md).
#include "vo_service.hpp"

int main(int argc, char** argv) {
  rover::dl::vo::VoService service;
  return rover::RunServiceMain(service, argc, argv);
}
