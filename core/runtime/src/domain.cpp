#include "rover/runtime/domain.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <random>
#include <utility>

namespace rover::dds {
namespace {
std::string LockDir() {
  const char* d = std::getenv("ROVER_LOCK_DIR");
  std::string dir = d ? d : "/tmp/rover-domains";
  mkdir(dir.c_str(), 01777);
  return dir;
}

int TryLock(int domain) {
  const std::string path = LockDir() + "/" + std::to_string(domain) + ".lock";
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return -1;
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}
}  // namespace

DomainLease::DomainLease(DomainLease&& o) noexcept
    : domain_(std::exchange(o.domain_, -1)), fd_(std::exchange(o.fd_, -1)) {}

DomainLease& DomainLease::operator=(DomainLease&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) close(fd_);
    domain_ = std::exchange(o.domain_, -1);
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

DomainLease::~DomainLease() {
  if (fd_ >= 0) close(fd_);
}

Result<DomainLease> DomainLease::AcquireFree(int lo, int hi) {
  if (lo < 0 || hi > 232 || lo > hi) {
    return InvalidArgument("domain range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                           "] is not within [0, 232]");
  }
  std::random_device rd;
  const int n = hi - lo + 1;
  const int start = static_cast<int>(rd() % static_cast<unsigned>(n));
  for (int i = 0; i < n; ++i) {
    const int d = lo + (start + i) % n;
    const int fd = TryLock(d);
    if (fd >= 0) {
      DomainLease l;
      l.domain_ = d;
      l.fd_ = fd;
      return l;
    }
  }
  return Busy("every DDS domain in [" + std::to_string(lo) + ", " + std::to_string(hi) +
              "] is leased by another run");
}

Result<DomainLease> DomainLease::Acquire(int domain) {
  if (domain < 0 || domain > 232) {
    return InvalidArgument("DDS domain " + std::to_string(domain) + " is out of range [0, 232]");
  }
  const int fd = TryLock(domain);
  if (fd < 0) {
    return Busy("DDS domain " + std::to_string(domain) +
                " is in use by another run on this machine");
  }
  DomainLease l;
  l.domain_ = domain;
  l.fd_ = fd;
  return l;
}

std::string LoopbackConfigUri(const std::string& root) {
  return "file://" + root + "/deploy/cyclonedds/loopback.xml";
}

}  // namespace rover::dds
