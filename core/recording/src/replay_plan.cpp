#include "rover/recording/replay_plan.hpp"

#include <cmath>

#include "rover/base/check.hpp"
#include "rover/recording/schema.hpp"

namespace rover::recording {
namespace {

const CatalogTopic* FindCatalog(const std::string& topic, std::span<const CatalogTopic> catalog) {
  for (const auto& t : catalog) {
    if (t.name == topic) return &t;
  }
  return nullptr;
}

Status CheckChannel(const mcap::Reader& reader, const mcap::Channel& channel,
                    const CatalogTopic* entry, bool accept_schema_changes, ReplayTopic* out) {
  const std::string where = reader.name() + ": topic '" + channel.topic + "'";
  if (entry == nullptr) {
    return InvalidArgument(where + " is not in this build's topic catalog; leave it out with "
                                   "--topics");
  }
  if (channel.message_encoding != mcap::kMessageEncodingCdr) {
    return InvalidArgument(where + ": message encoding '" + channel.message_encoding +
                           "', not cdr (serialised DDS samples)");
  }
  const auto s = reader.schemas().find(channel.schema_id);
  if (channel.schema_id == 0 || s == reader.schemas().end()) {
    return InvalidArgument(where + " has no schema, so its type is unknown");
  }
  const mcap::Schema& schema = s->second;
  auto expected = SchemaForType(entry->c_type_name);
  if (!expected.ok()) return expected.status().WithPrefix(where);
  if (schema.encoding != kOmgIdl) {
    return InvalidArgument(where + ": schema '" + schema.name + "' has encoding '" +
                           schema.encoding + "', not omgidl (an unknown schema)");
  }
  if (schema.name != expected->name) {
    return InvalidArgument(where + ": the recording's type is " + schema.name +
                           ", the catalog's is " + expected->name);
  }
  const std::string recorded(schema.data.begin(), schema.data.end());
  if (!accept_schema_changes && NormalizeIdl(recorded) != NormalizeIdl(expected->text)) {
    return InvalidArgument(where + ": the recording's IDL of " + schema.name +
                           " differs from this build's (recorded by another version of the "
                           "stack, its messages may not decode); --accept-schema-changes to "
                           "replay it anyway");
  }
  out->name = channel.topic;
  out->c_type_name = entry->c_type_name;
  out->type = expected->name;
  return Status::Ok();
}

}  // namespace

Result<ReplayPlan> PlanReplay(const mcap::Reader& reader, const ReplaySelection& selection,
                              std::span<const CatalogTopic> catalog) {
  ROVER_RETURN_IF_ERROR(selection.topics.Validate());
  ReplayPlan plan;
  std::map<std::string, std::size_t> index;
  const auto& stats = reader.statistics();
  for (const auto& [id, channel] : reader.channels()) {
    const bool is_clock = channel.topic == kClockTopic;
    const bool wanted = is_clock ? selection.clock : selection.topics.Selects(channel.topic);
    if (!wanted) continue;
    ReplayTopic topic;
    ROVER_RETURN_IF_ERROR(CheckChannel(reader, channel, FindCatalog(channel.topic, catalog),
                                       selection.accept_schema_changes, &topic));
    auto [it, fresh] = index.emplace(channel.topic, plan.topics.size());
    if (fresh) plan.topics.push_back(std::move(topic));
    ReplayTopic& t = plan.topics[it->second];
    t.channels.push_back(id);
    plan.topic_of_channel[id] = it->second;
    if (stats) {
      const auto c = stats->channel_message_counts.find(id);
      if (c != stats->channel_message_counts.end()) {
        t.messages += c->second;
        plan.messages += c->second;
      }
    }
    if (is_clock) plan.clock_recorded = true;
  }
  const bool only_clock = plan.topics.size() == (plan.clock_recorded ? 1u : 0u);
  if (only_clock) {
    return InvalidArgument(reader.name() + ": " + selection.topics.Describe() +
                           " selects no topic of the recording");
  }
  plan.synthesize_clock = selection.clock && !plan.clock_recorded;
  if (stats) {
    plan.start_time = stats->message_start_time;
    plan.end_time = stats->message_end_time;
  }
  return plan;
}

ReplayPacer::ReplayPacer(double rate) : rate_(rate) {
  ROVER_DEMAND(rate >= 0 && std::isfinite(rate));
}

std::int64_t ReplayPacer::DueAfterNs(mcap::Timestamp log_time) {
  if (!first_) first_ = log_time;
  if (rate_ == 0 || log_time <= *first_) return 0;
  return static_cast<std::int64_t>(static_cast<double>(log_time - *first_) / rate_);
}

ClockTicks::ClockTicks(std::int64_t period_ns) : period_ns_(period_ns) {
  ROVER_DEMAND(period_ns > 0);
}

std::vector<mcap::Timestamp> ClockTicks::Before(mcap::Timestamp log_time) {
  std::vector<mcap::Timestamp> out;
  const auto period = static_cast<mcap::Timestamp>(period_ns_);
  if (!last_ || log_time < *last_) {  // the first message, or the log went back (a reset)
    out.push_back(log_time);
    last_ = log_time;
    return out;
  }
  for (mcap::Timestamp t = (*last_ / period + 1) * period; t <= log_time; t += period) {
    out.push_back(t);
    last_ = t;
  }
  return out;
}

}  // namespace rover::recording
