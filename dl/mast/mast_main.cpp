// dl-mast: mast pointing by angles or look-at point (see mast_service.hpp).
#include "mast_service.hpp"

int main(int argc, char** argv) {
  rover::dl::mast::MastService service;
  return rover::RunServiceMain(service, argc, argv);
}
