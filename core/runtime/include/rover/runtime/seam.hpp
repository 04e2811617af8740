#pragma once
/// @file
/// The fault-injection seam. Every typed Writer and Reader passes its samples through a
/// TopicSeam if one is installed for its topic, so faults (drop, delay, duplicate, corrupt, ...)
/// can be injected per topic without any change to a service. The runtime installs no seam by
/// default: samples then go straight to DDS.

#include <dds/dds.h>

#include <functional>
#include <memory>
#include <string>

namespace rover::dds {

enum class Direction { kWrite, kRead };

/// Intercepts the samples of one topic in one process.
class TopicSeam {
 public:
  virtual ~TopicSeam() = default;
  /// Called for each sample a writer is asked to send. The seam sends it (or a modified copy,
  /// or several copies, or none, now or later) with dds_write(writer, ...). Returns the DDS
  /// return code to report to the caller (DDS_RETCODE_OK when it chose to drop).
  virtual dds_return_t OnWrite(dds_entity_t writer, const void* sample,
                               const dds_topic_descriptor_t* type) = 0;
  /// Called for each valid sample a reader took, before the service sees it. May modify the
  /// sample in place; returns false to drop it.
  virtual bool OnRead(void* sample, const dds_topic_descriptor_t* type) = 0;
};

/// Returns the seam for (topic, direction), or nullptr for none.
using SeamFactory =
    std::function<std::shared_ptr<TopicSeam>(const std::string& topic, Direction direction)>;

/// Installs the process-wide seam factory; readers and writers created afterwards use it.
void InstallSeamFactory(SeamFactory factory);
/// The seam for a new reader or writer (nullptr when no factory is installed).
std::shared_ptr<TopicSeam> SeamFor(const std::string& topic, Direction direction);

}  // namespace rover::dds
