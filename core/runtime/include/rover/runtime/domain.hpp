#pragma once
/// @file
/// Choosing DDS domains so that service sets started at the same time on one machine (parallel
/// scenario runs, concurrent tests) never see each other.

#include <string>

#include "rover/base/status.hpp"

namespace rover::dds {

/// Holds an exclusive lock on one DDS domain id for the lifetime of the object (flock on
/// $ROVER_LOCK_DIR or /tmp/rover-domains/<id>.lock; the kernel releases it if the process dies).
class DomainLease {
 public:
  DomainLease() = default;
  DomainLease(DomainLease&& o) noexcept;
  DomainLease& operator=(DomainLease&& o) noexcept;
  DomainLease(const DomainLease&) = delete;
  DomainLease& operator=(const DomainLease&) = delete;
  ~DomainLease();

  /// Leases a free domain in [lo, hi], starting at a pseudo-random place.
  static Result<DomainLease> AcquireFree(int lo = 100, int hi = 230);
  /// Leases exactly `domain`; Busy if another process holds it.
  static Result<DomainLease> Acquire(int domain);

  int domain() const { return domain_; }
  bool valid() const { return fd_ >= 0; }

 private:
  int domain_ = -1;
  int fd_ = -1;
};

/// Path of the loopback Cyclone configuration shipped in deploy/cyclonedds, given the source or
/// install tree root.
std::string LoopbackConfigUri(const std::string& root);

}  // namespace rover::dds
