#include "rover/runtime/raw_sample.hpp"

#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include <cstring>

namespace rover::dds {
namespace {

// ---- the carrier: a serdata that only holds bytes ---------------------------------------------
//
// dds_writecdr accepts a serdata of another sertype than the writer's and converts it through
// its serialised form (ddsi_serdata_ref_as_type: to_ser_ref on ours, from_ser_iov on the
// writer's type, which validates the bytes as it does network input). So a serdata needs only
// to expose its bytes: size, to_ser, to_ser_ref/unref. It lives on the stack for one call.

struct Carrier {
  ddsi_serdata c;  // first member: Cyclone sees a ddsi_serdata*
  const std::uint8_t* data;
  std::uint32_t size;
};

const Carrier* AsCarrier(const ddsi_serdata* d) { return reinterpret_cast<const Carrier*>(d); }

uint32_t CarrierSize(const ddsi_serdata* d) { return AsCarrier(d)->size; }
void CarrierFree(ddsi_serdata*) {}  // owned by the caller's stack frame
void CarrierToSer(const ddsi_serdata* d, size_t off, size_t sz, void* buf) {
  const Carrier* c = AsCarrier(d);
  const size_t n = off < c->size ? std::min(sz, c->size - off) : 0;
  std::memcpy(buf, c->data + off, n);
  if (n < sz) std::memset(static_cast<char*>(buf) + n, 0, sz - n);
}
ddsi_serdata* CarrierToSerRef(const ddsi_serdata* d, size_t off, size_t sz, ddsrt_iovec_t* ref) {
  const Carrier* c = AsCarrier(d);
  ref->iov_base = const_cast<std::uint8_t*>(c->data + off);
  ref->iov_len = static_cast<ddsrt_iov_len_t>(sz);
  return ddsi_serdata_ref(d);
}
void CarrierToSerUnref(ddsi_serdata* d, const ddsrt_iovec_t*) { ddsi_serdata_unref(d); }
bool CarrierEqKey(const ddsi_serdata*, const ddsi_serdata*) { return false; }
size_t CarrierPrint(const ddsi_sertype*, const ddsi_serdata*, char* buf, size_t size) {
  if (size > 0) buf[0] = '\0';
  return 0;
}
void CarrierKeyhash(const ddsi_serdata*, ddsi_keyhash* buf, bool) { std::memset(buf, 0, 16); }

const ddsi_serdata_ops kCarrierSerdataOps = [] {
  ddsi_serdata_ops ops{};
  ops.eqkey = CarrierEqKey;
  ops.get_size = CarrierSize;
  ops.to_ser = CarrierToSer;
  ops.to_ser_ref = CarrierToSerRef;
  ops.to_ser_unref = CarrierToSerUnref;
  ops.free = CarrierFree;
  ops.print = CarrierPrint;
  ops.get_keyhash = CarrierKeyhash;
  return ops;
}();

void CarrierTypeFree(ddsi_sertype*) {}

const ddsi_sertype_ops kCarrierTypeOps = [] {
  ddsi_sertype_ops ops{};
  ops.version = ddsi_sertype_v0;
  ops.free = CarrierTypeFree;
  return ops;
}();

// Never registered with a domain and never freed: it only labels carriers.
const ddsi_sertype* CarrierType() {
  static ddsi_sertype* type = [] {
    auto* t = new ddsi_sertype{};
    ddsi_sertype_init(t, "rover::recording::carrier", &kCarrierTypeOps, &kCarrierSerdataOps,
                      true);
    return t;
  }();
  return type;
}

Result<dds_entity_t> MakeReader(const Participant& p, dds_entity_t topic, QosProfile profile,
                                const RawReaderOptions& options) {
  QosPtr qos = MakeQos(profile);
  if (options.keep_all) dds_qset_history(qos.get(), DDS_HISTORY_KEEP_ALL, 0);
  const dds_entity_t r = dds_create_reader(p.handle(), topic, qos.get(), nullptr);
  if (r < 0) return DdsError("creating a raw reader", r);
  const dds_return_t rc = dds_set_status_mask(r, DDS_DATA_AVAILABLE_STATUS);
  if (rc < 0) {
    dds_delete(r);
    return DdsError("setting the reader status mask", rc);
  }
  return r;
}

}  // namespace

Result<RawReader> RawReader::Create(const Participant& p, const std::string& topic,
                                    const dds_topic_descriptor_t* descriptor, QosProfile profile,
                                    const RawReaderOptions& options) {
  ROVER_DEMAND(descriptor != nullptr);
  ROVER_ASSIGN_OR_RETURN(const dds_entity_t t,
                         internal::CreateTopic(p, topic, descriptor, profile));
  RawReader out;
  out.topic_ = Entity(t);
  ROVER_ASSIGN_OR_RETURN(const dds_entity_t r, MakeReader(p, t, profile, options));
  out.reader_ = Entity(r);
  out.name_ = topic;
  return out;
}

std::size_t RawReader::TakeEach(
    const std::function<void(std::span<const std::uint8_t>, const dds_sample_info_t&)>& fn) {
  ROVER_DEMAND(reader_.valid());
  constexpr std::uint32_t kBatch = 32;
  ddsi_serdata* samples[kBatch];
  dds_sample_info_t infos[kBatch];
  std::size_t delivered = 0;
  while (true) {
    const dds_return_t n = dds_takecdr(reader_.handle(), samples, kBatch, infos, DDS_ANY_STATE);
    if (n <= 0) break;
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data) {
        const std::uint32_t size = ddsi_serdata_size(samples[i]);
        scratch_.resize(size);
        ddsi_serdata_to_ser(samples[i], 0, size, scratch_.data());
        ++delivered;
        fn(std::span<const std::uint8_t>(scratch_.data(), size), infos[i]);
      }
      ddsi_serdata_unref(samples[i]);
    }
    if (static_cast<std::uint32_t>(n) < kBatch) break;
  }
  return delivered;
}

std::uint64_t RawReader::LostSamples() const {
  dds_sample_lost_status_t lost{};
  dds_sample_rejected_status_t rejected{};
  std::uint64_t n = 0;
  if (dds_get_sample_lost_status(reader_.handle(), &lost) >= 0) n += lost.total_count;
  if (dds_get_sample_rejected_status(reader_.handle(), &rejected) >= 0) n += rejected.total_count;
  return n;
}

int RawReader::MatchedWriters() const {
  dds_subscription_matched_status_t st{};
  if (dds_get_subscription_matched_status(reader_.handle(), &st) < 0) return 0;
  return static_cast<int>(st.current_count);
}

Result<RawWriter> RawWriter::Create(const Participant& p, const std::string& topic,
                                    const dds_topic_descriptor_t* descriptor, QosProfile profile) {
  ROVER_DEMAND(descriptor != nullptr);
  ROVER_ASSIGN_OR_RETURN(const dds_entity_t t,
                         internal::CreateTopic(p, topic, descriptor, profile));
  RawWriter out;
  out.topic_ = Entity(t);
  ROVER_ASSIGN_OR_RETURN(const dds_entity_t w, internal::CreateEndpoint(p, t, profile, true));
  out.writer_ = Entity(w);
  out.name_ = topic;
  return out;
}

Status RawWriter::Write(std::span<const std::uint8_t> sample) {
  ROVER_DEMAND(writer_.valid());
  if (sample.size() < 4) {
    return InvalidArgument("a serialised sample on " + name_ + " of " +
                           std::to_string(sample.size()) + " bytes has no encapsulation header");
  }
  Carrier carrier{};
  ddsi_serdata_init(&carrier.c, CarrierType(), SDK_DATA);
  carrier.data = sample.data();
  carrier.size = static_cast<std::uint32_t>(sample.size());
  // dds_writecdr consumes the one reference ddsi_serdata_init gave the carrier.
  const dds_return_t rc = dds_writecdr(writer_.handle(), &carrier.c);
  if (rc == DDS_RETCODE_ERROR) {
    return InvalidArgument("a serialised sample on " + name_ + " (" +
                           std::to_string(sample.size()) + " bytes) is not a valid sample of " +
                           "its type; nothing was published");
  }
  if (rc < 0) return DdsError("raw write on " + name_, rc);
  return Status::Ok();
}

int RawWriter::MatchedReaders() const {
  dds_publication_matched_status_t st{};
  if (dds_get_publication_matched_status(writer_.handle(), &st) < 0) return 0;
  return static_cast<int>(st.current_count);
}

}  // namespace rover::dds
