#include "rover/recording/session.hpp"

#include <algorithm>

#include "rover/base/check.hpp"
#include "rover/base/clock.hpp"
#include "rover/recording/schema.hpp"

namespace rover::recording {

Result<std::unique_ptr<RecordingSession>> RecordingSession::Create(
    const std::string& path, const mcap::WriterOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  auto w = mcap::Writer::Create(path, options);
  if (!w.ok()) return w.status().WithPrefix("cannot record to " + path);
  return std::unique_ptr<RecordingSession>(new RecordingSession(std::move(*w)));
}

Result<std::unique_ptr<RecordingSession>> RecordingSession::Create(
    std::unique_ptr<mcap::Sink> sink, const mcap::WriterOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  ROVER_ASSIGN_OR_RETURN(auto w, mcap::Writer::Create(std::move(sink), options));
  return std::unique_ptr<RecordingSession>(new RecordingSession(std::move(w)));
}

Result<std::size_t> RecordingSession::AddTopic(const std::string& topic,
                                               const std::string& c_type_name,
                                               const mcap::StringMap& metadata) {
  auto schema = SchemaForType(c_type_name);
  if (!schema.ok()) return schema.status().WithPrefix("topic '" + topic + "'");
  topics_.push_back({topic, schema->name, std::move(schema->text), metadata, 0, 0});
  TopicStats st;
  st.topic = topic;
  st.type = topics_.back().schema_name;
  stats_.topics.push_back(std::move(st));
  return topics_.size() - 1;
}

Status RecordingSession::Write(std::size_t index, std::int64_t log_time_ns, ByteSpan sample) {
  ROVER_DEMAND(index < topics_.size());
  if (!failure_.ok()) return failure_;
  if (closed_) return FailedPrecondition(name() + ": the recording is closed");
  Topic& t = topics_[index];
  TopicStats& st = stats_.topics[index];
  const std::int64_t log_ns = std::max<std::int64_t>(0, log_time_ns);
  if (writer_->capped()) {
    ++st.dropped;
    ++stats_.dropped;
    return Status::Ok();
  }
  if (t.channel == 0) {
    auto schema = writer_->AddSchema(t.schema_name, kOmgIdl, mcap::AsBytes(t.schema_text));
    if (schema.ok()) {
      auto channel = writer_->AddChannel(t.name, mcap::kMessageEncodingCdr, *schema, t.metadata);
      if (channel.ok()) t.channel = *channel;
      else schema = channel.status();
    }
    if (!schema.ok()) {
      if (schema.status().code() == StatusCode::kOutOfRange) {  // the cap: no room for it
        ++st.dropped;
        ++stats_.dropped;
        stats_.capped = true;
        return Status::Ok();
      }
      failure_ = schema.status();
      return failure_;
    }
  }
  std::int64_t publish_ns = log_ns;
  if (auto h = ReadSampleHeader(sample); h.ok()) {
    if (h->stamp_ns > 0) publish_ns = h->stamp_ns;
  } else {
    ++st.header_errors;
  }
  const mcap::MessageView m{t.channel, t.sequence + 1, static_cast<mcap::Timestamp>(log_ns),
                            static_cast<mcap::Timestamp>(publish_ns), sample};
  const Status s = writer_->WriteMessage(m);
  stats_.file_bytes = writer_->stats().bytes_written;
  if (s.code() == StatusCode::kOutOfRange) {
    ++st.dropped;
    ++stats_.dropped;
    stats_.capped = true;
    return Status::Ok();
  }
  if (!s.ok()) {
    failure_ = s;
    return s;
  }
  ++t.sequence;
  ++st.messages;
  st.bytes += sample.size();
  ++stats_.messages;
  stats_.bytes += sample.size();
  if (stats_.first_log_time_ns < 0 || log_ns < stats_.first_log_time_ns) {
    stats_.first_log_time_ns = log_ns;
  }
  stats_.last_log_time_ns = std::max(stats_.last_log_time_ns, log_ns);
  return Status::Ok();
}

void RecordingSession::CountLost(std::size_t index, std::uint64_t count) {
  ROVER_DEMAND(index < topics_.size());
  stats_.topics[index].lost += count;
  stats_.lost += count;
}

Status RecordingSession::Close(mcap::StringMap metadata) {
  if (closed_) return close_status_;
  closed_ = true;
  if (failure_.ok()) {
    metadata["messages"] = std::to_string(stats_.messages);
    metadata["samples_lost"] = std::to_string(stats_.lost);
    metadata["dropped_after_size_cap"] = std::to_string(stats_.dropped);
    // Refused only under the cap; the recording is complete without it.
    (void)writer_->WriteMetadata({kRecorderMetadataName, metadata});
  }
  close_status_ = writer_->Close();
  if (close_status_.ok() && !failure_.ok()) close_status_ = failure_;
  if (failure_.ok()) failure_ = close_status_;
  stats_.capped = stats_.capped || writer_->capped();
  stats_.file_bytes = writer_->stats().bytes_written;
  return close_status_;
}

void LogClock::OnClockSample(ByteSpan sample) {
  if (mode_ != Mode::kSim) return;
  auto c = ReadClockSample(sample);
  if (!c.ok()) {
    ++unreadable_;
    return;
  }
  sim_ns_ = c->sim_time_ns;
  heard_ = true;
}

std::int64_t LogClock::Now() const { return mode_ == Mode::kSim ? sim_ns_ : WallNow().ns; }

}  // namespace rover::recording
