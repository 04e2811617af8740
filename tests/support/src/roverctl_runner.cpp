#include "rover/testing/roverctl_runner.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include "rover/testing/test_support.hpp"

namespace rover::testing {

RoverctlRunner::RoverctlRunner(std::string dir)
    : dir_(std::move(dir)), mark_(std::to_string(getpid()) + "-" + dir_) {}

Result<Process> RoverctlRunner::Start(const std::vector<std::string>& args,
                                      const std::string& log) {
  SpawnOptions o;
  o.argv = {BinDir() + "/roverctl"};
  o.argv.insert(o.argv.end(), args.begin(), args.end());
  o.env[kMarkVariable] = mark_;
  o.stdout_path = log;
  o.stderr_path = log;
  auto p = Process::Spawn(o);
  if (!p.ok()) ADD_FAILURE() << "roverctl did not start: " << p.status().message();
  return p;
}

std::pair<ExitInfo, std::string> RoverctlRunner::Run(const std::vector<std::string>& args,
                                                     std::chrono::seconds timeout) {
  const std::string log = dir_ + "/roverctl-" + std::to_string(n_++) + ".log";
  auto p = Start(args, log);
  if (!p.ok()) return {ExitInfo{false, 127, 0}, p.status().message()};  // as a shell would
  auto e = p->WaitFor(timeout);
  if (!e) e = p->Terminate(std::chrono::seconds(10));
  return {*e, ReadFile(log)};
}

std::vector<pid_t> RoverctlRunner::Leftovers() const {
  return ProcessesWithEnvironment(kMarkVariable, mark_);
}

void RoverctlRunner::KillLeftovers() const {
  for (pid_t pid : Leftovers()) kill(pid, SIGKILL);
}

}  // namespace rover::testing
