// apl-sequencer: runs command sequences (see sequencer_service.hpp).
#include "sequencer_service.hpp"

int main(int argc, char** argv) {
  rover::apl::sequencer::SequencerService service;
  return rover::RunServiceMain(service, argc, argv);
}
