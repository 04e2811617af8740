// ddl-camera: the stereo camera driver service. See camera_service.hpp and
// docs/services/ddl-camera.md.
#include "camera_service.hpp"

int main(int argc, char** argv) {
  rover::ddl::camera::CameraService service;
  return rover::RunServiceMain(service, argc, argv);
}
