// dl-stereo: stereo ranging service (see stereo_service.hpp and docs/services/dl-stereo.md).
#include "stereo_service.hpp"

int main(int argc, char** argv) {
  rover::dl::stereo::StereoService service;
  return rover::RunServiceMain(service, argc, argv);
}
