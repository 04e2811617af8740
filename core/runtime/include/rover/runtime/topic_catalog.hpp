#pragma once
/// @file
/// The topic catalog in code: for every topic of the stack, its IDL type and QoS profile. The
/// typed readers and writers take the profile from here, so a topic's QoS is defined once;
/// docs/topics.md lists the same table with publishers, subscribers and rates (a test keeps the
/// two in step).

#include <dds/dds.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rover/runtime/qos.hpp"

namespace rover::dds {

struct TopicInfo {
  std::string_view name;       ///< "layer/noun"
  std::string_view type_name;  ///< idlc C type, e.g. "rover_dl_PoseEstimate"
  QosProfile profile;
};

/// Every catalog topic.
const std::vector<TopicInfo>& TopicCatalog();
/// The catalog entry for `name`, if any.
std::optional<TopicInfo> FindTopic(std::string_view name);
/// The descriptor of an @topic type by its idlc C name ("rover_dl_PoseEstimate"), or nullptr.
const dds_topic_descriptor_t* DescriptorForType(std::string_view type_name);

}  // namespace rover::dds
