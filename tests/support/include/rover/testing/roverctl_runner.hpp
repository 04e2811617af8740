#pragma once
/// @file
/// RoverctlRunner: runs the built `roverctl` from an end-to-end test and cleans up after it.
///
/// Every process it starts (and everything those start) inherits ROVER_E2E_TEST_RUN with a value
/// unique to the runner (pid and folder), so that Leftovers() / KillLeftovers() find only what
/// this test started, never another engineer's run of the same scenario on this machine. Logs go
/// to `<dir>/roverctl-<n>.log` (stdout and stderr together).

#include <sys/types.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/process.hpp"

namespace rover::testing {

class RoverctlRunner {
 public:
  static constexpr const char* kMarkVariable = "ROVER_E2E_TEST_RUN";

  /// `dir`: the test's own folder, for the logs.
  explicit RoverctlRunner(std::string dir);

  /// Starts `roverctl args...` with its output in `log`. A spawn failure fails the test (gtest
  /// ADD_FAILURE) and returns an error.
  Result<Process> Start(const std::vector<std::string>& args, const std::string& log);
  /// Runs `roverctl args...` to its end (terminated after `timeout`): exit and its output.
  std::pair<ExitInfo, std::string> Run(const std::vector<std::string>& args,
                                       std::chrono::seconds timeout = std::chrono::minutes(10));
  /// The processes this runner's runs started that are still alive.
  std::vector<pid_t> Leftovers() const;
  /// SIGKILLs whatever this runner's runs left behind.
  void KillLeftovers() const;

  const std::string& mark() const { return mark_; }

 private:
  std::string dir_;
  std::string mark_;
  int n_ = 0;
};

}  // namespace rover::testing
