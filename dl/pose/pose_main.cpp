// dl-pose: FIDO-style EKF pose estimator service (see pose_service.hpp).
#include "pose_service.hpp"

int main(int argc, char** argv) {
  rover::dl::pose::PoseService service;
  return rover::RunServiceMain(service, argc, argv);
}
