#include "rover/testing/test_support.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace rover::testing {

std::string SourceDir() {
  if (const char* s = std::getenv("ROVER_SOURCE_DIR")) return s;
  return ROVER_SOURCE_DIR;
}
std::string BinaryDir() { return ROVER_BINARY_DIR; }
std::string BinDir() {
  if (const char* s = std::getenv("ROVER_BIN_DIR")) return s;
  return BinaryDir() + "/bin";
}

void UseLoopbackDds() { setenv("CYCLONEDDS_URI", dds::LoopbackConfigUri(SourceDir()).c_str(), 1); }

dds::DomainLease IsolatedDomain() {
  UseLoopbackDds();
  auto lease = dds::DomainLease::AcquireFree();
  if (!lease.ok()) {
    ADD_FAILURE() << lease.status().message();
    return {};
  }
  return std::move(*lease);
}

Result<dds::Participant> JoinDomain(int domain) {
  UseLoopbackDds();
  return dds::Participant::Create(domain);
}

std::string MakeTempDir(const std::string& prefix) {
  std::string templ = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  char* p = mkdtemp(templ.data());
  return p ? std::string(p) : std::string();
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string CaptureStdout(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  ::pclose(pipe);
  return out;
}

bool WaitFor(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return condition();
}

}  // namespace rover::testing
