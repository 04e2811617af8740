#include "rover/base/check.hpp"

#include <cstdio>
#include <cstdlib>

namespace rover::internal {

void DemandFailed(const char* condition, const char* file, int line, const char* message) {
  std::fprintf(stderr, "%s:%d: invariant broken: %s%s%s\n", file, line, condition,
               (message && *message) ? ": " : "", message ? message : "");
  std::fflush(stderr);
  std::abort();
}

}  // namespace rover::internal
