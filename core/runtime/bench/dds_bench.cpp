// rover-dds-bench: latency and throughput of the typed DDS wrappers (rover::dds::Writer/Reader),
// printed beside Cyclone's own ddsperf measured in the same run on the same machine, as ratios.
//
//   rover-dds-bench [--seconds S]      run everything and print the table
//
// Workloads (payload sizes matched for ddsperf's KS topic):
//   small  rover_dl_PoseEstimate (a state sample, ~430 bytes serialised)
//   stereo rover_hw_CameraFrame with a 512x512 8-bit stereo pair (2 x 256 KiB)
// Latency: ping-pong round trip between two processes, reliable keep-last 1 (our `state`
// profile; ddsperf's ping/pong QoS), median and 90th percentile.
// Throughput: one publisher writing as fast as it can, one subscriber in another process,
// reliable keep-all (our `command` profile; ddsperf -k all), samples and bytes per second.
// Fault seam (--cases seam): the cost of fault injection per sample, in one process (write one
// rover_dl_PoseEstimate on dl/pose, take it), plain wrappers vs the fault engine installed with
// no fault vs with a 10 % drop; interleaved rounds, medians, ratios to the plain wrappers.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/process.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/domain.hpp"
#include "rover/runtime/fault_engine.hpp"

namespace {
using rover::dds::QosProfile;
namespace dds = rover::dds;

constexpr int kStereoSide = 512;

struct Payload {
  rover_dl_PoseEstimate small{};
  rover_hw_CameraFrame stereo{};
  rover_hw_CameraFrame octets{};  // ddsperf-like: a small sample that is mostly an octet sequence
  std::vector<uint8_t> left, right, small_left, small_right;
  Payload()
      : left(kStereoSide * kStereoSide, 7), right(kStereoSide * kStereoSide, 9),
        small_left(180, 1), small_right(180, 2) {
    dds::BorrowSequence(octets.left, small_left);
    dds::BorrowSequence(octets.right, small_right);
    for (int i = 0; i < 36; ++i) small.covariance[i] = 0.01 * i;
    dds::CopyString(small.header.frame_id, "site");
    stereo.width = stereo.height = kStereoSide;
    dds::CopyString(stereo.header.frame_id, "navcam_left");
    dds::BorrowSequence(stereo.left, left);
    dds::BorrowSequence(stereo.right, right);
  }
};

// The octets workload shares the CameraFrame type; `g_octets` picks its payload.
bool g_octets = false;

template <class T>
T& PayloadFor(Payload& p) {
  if constexpr (std::is_same_v<T, rover_hw_CameraFrame>) {
    return g_octets ? p.octets : p.stereo;
  } else {
    return p.small;
  }
}

void SetSeq(rover_dl_PoseEstimate& s, uint32_t n) { s.header.seq = n; }
void SetSeq(rover_hw_CameraFrame& s, uint32_t n) { s.header.seq = n; }

// Waits on a reader with a waitset; returns samples taken.
template <class T>
std::size_t WaitTake(dds::Reader<T>& r, dds::WaitSet& ws, std::int64_t timeout_ns) {
  ws.Wait(timeout_ns);
  return r.TakeEach([](const dds::Sample<T>&) {});
}

template <class T>
int Pong(int domain, double seconds) {
  auto p = dds::Participant::Create(domain);
  auto r = dds::Reader<T>::Create(*p, "bench/ping", QosProfile::kState);
  auto w = dds::Writer<T>::Create(*p, "bench/pong", QosProfile::kState);
  auto ws = dds::WaitSet::Create(*p);
  if (!p.ok() || !r.ok() || !w.ok() || !ws.ok()) return 1;
  (void)ws->Attach(r->handle(), 1);
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds);
  while (rover::MonotonicNow() < end) {
    ws->Wait(DDS_MSECS(100));
    r->TakeEach([&](const dds::Sample<T>& s) { (void)w->Write(s.data()); });
  }
  return 0;
}

template <class T>
int Sub(int domain, double seconds, const std::string& out) {
  auto p = dds::Participant::Create(domain);
  auto r = dds::Reader<T>::Create(*p, "bench/data", QosProfile::kCommand);
  auto ws = dds::WaitSet::Create(*p);
  if (!p.ok() || !r.ok() || !ws.ok()) return 1;
  (void)ws->Attach(r->handle(), 1);
  // Count from the first sample for `seconds`.
  std::size_t n = 0;
  while (n == 0) n += WaitTake(*r, *ws, DDS_SECS(10));
  const rover::Time start = rover::MonotonicNow();
  n = 0;
  while (rover::MonotonicNow() - start < rover::Seconds(seconds)) n += WaitTake(*r, *ws, DDS_MSECS(100));
  const double rate = n / rover::ToSeconds(rover::MonotonicNow() - start);
  std::ofstream(out) << rate << "\n";
  return 0;
}

struct Latency {
  double p50_us = 0, p90_us = 0;
  std::size_t count = 0;
};

template <class T>
Latency Ping(int domain, double seconds, Payload& payload) {
  auto p = dds::Participant::Create(domain);
  auto w = dds::Writer<T>::Create(*p, "bench/ping", QosProfile::kState);
  auto r = dds::Reader<T>::Create(*p, "bench/pong", QosProfile::kState);
  auto ws = dds::WaitSet::Create(*p);
  Latency out;
  if (!p.ok() || !w.ok() || !r.ok() || !ws.ok()) return out;
  (void)ws->Attach(r->handle(), 1);
  const rover::Time wait_end = rover::MonotonicNow() + rover::Seconds(20);
  while ((w->MatchedReaders() < 1 || r->MatchedWriters() < 1) && rover::MonotonicNow() < wait_end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::vector<double> rtt;
  T& s = PayloadFor<T>(payload);
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds);
  uint32_t seq = 0;
  while (rover::MonotonicNow() < end) {
    SetSeq(s, ++seq);
    const rover::Time t0 = rover::MonotonicNow();
    (void)w->Write(s);
    std::size_t got = 0;
    while (got == 0 && rover::MonotonicNow() < end) got = WaitTake(*r, *ws, DDS_MSECS(500));
    if (got) rtt.push_back(rover::ToSeconds(rover::MonotonicNow() - t0) * 1e6);
  }
  if (rtt.empty()) return out;
  std::sort(rtt.begin(), rtt.end());
  out.p50_us = rtt[rtt.size() / 2];
  out.p90_us = rtt[rtt.size() * 9 / 10];
  out.count = rtt.size();
  return out;
}

template <class T>
double Pub(int domain, double seconds, Payload& payload) {
  auto p = dds::Participant::Create(domain);
  auto w = dds::Writer<T>::Create(*p, "bench/data", QosProfile::kCommand);
  if (!p.ok() || !w.ok()) return 0;
  while (w->MatchedReaders() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  T& s = PayloadFor<T>(payload);
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds + 2.0);
  uint32_t seq = 0;
  while (rover::MonotonicNow() < end) {
    SetSeq(s, ++seq);
    (void)w->Write(s);
  }
  return 0;
}

// ---- the same workloads on the raw Cyclone C API (no wrappers), same QoS and types ----------
struct Raw {
  dds_entity_t participant = 0, writer = 0, reader = 0, waitset = 0;
  ~Raw() {
    if (participant > 0) dds_delete(participant);
  }
};

template <class T>
bool MakeRaw(Raw& r, int domain, const char* wtopic, const char* rtopic, QosProfile profile) {
  r.participant = dds_create_participant(domain, nullptr, nullptr);
  if (r.participant < 0) return false;
  dds::QosPtr q = dds::MakeQos(profile);
  if (wtopic) {
    const dds_entity_t t = dds_create_topic(r.participant, dds::TopicType<T>::Descriptor(), wtopic, q.get(), nullptr);
    r.writer = dds_create_writer(r.participant, t, q.get(), nullptr);
  }
  if (rtopic) {
    const dds_entity_t t = dds_create_topic(r.participant, dds::TopicType<T>::Descriptor(), rtopic, q.get(), nullptr);
    r.reader = dds_create_reader(r.participant, t, q.get(), nullptr);
    dds_set_status_mask(r.reader, DDS_DATA_AVAILABLE_STATUS);
    r.waitset = dds_create_waitset(r.participant);
    dds_waitset_attach(r.waitset, r.reader, 1);
  }
  return true;
}

// Waits, then takes with loans; returns the count. Calls `fn(const T*)` on each valid sample.
template <class T, class F>
std::size_t RawWaitTake(const Raw& r, std::int64_t timeout_ns, F&& fn) {
  dds_attach_t x;
  dds_waitset_wait(r.waitset, &x, 1, timeout_ns);
  void* ptrs[32];
  dds_sample_info_t infos[32];
  std::size_t total = 0;
  while (true) {
    ptrs[0] = nullptr;
    const dds_return_t n = dds_take(r.reader, ptrs, infos, 32, 32);
    if (n <= 0) break;
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data) {
        fn(static_cast<const T*>(ptrs[i]));
        ++total;
      }
    }
    dds_return_loan(r.reader, ptrs, n);
    if (n < 32) break;
  }
  return total;
}

template <class T>
int RawPong(int domain, double seconds) {
  Raw r;
  if (!MakeRaw<T>(r, domain, "bench/pong", "bench/ping", QosProfile::kState)) return 1;
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds);
  while (rover::MonotonicNow() < end) {
    RawWaitTake<T>(r, DDS_MSECS(100), [&](const T* s) { dds_write(r.writer, s); });
  }
  return 0;
}

template <class T>
int RawSub(int domain, double seconds, const std::string& out) {
  Raw r;
  if (!MakeRaw<T>(r, domain, nullptr, "bench/data", QosProfile::kCommand)) return 1;
  auto none = [](const T*) {};
  std::size_t n = 0;
  while (n == 0) n += RawWaitTake<T>(r, DDS_SECS(10), none);
  const rover::Time start = rover::MonotonicNow();
  n = 0;
  while (rover::MonotonicNow() - start < rover::Seconds(seconds)) n += RawWaitTake<T>(r, DDS_MSECS(100), none);
  std::ofstream(out) << n / rover::ToSeconds(rover::MonotonicNow() - start) << "\n";
  return 0;
}

template <class T>
Latency RawPing(int domain, double seconds, Payload& payload) {
  Raw r;
  Latency out;
  if (!MakeRaw<T>(r, domain, "bench/ping", "bench/pong", QosProfile::kState)) return out;
  dds_publication_matched_status_t pm{};
  const rover::Time wait_end = rover::MonotonicNow() + rover::Seconds(20);
  while (rover::MonotonicNow() < wait_end) {
    dds_get_publication_matched_status(r.writer, &pm);
    if (pm.current_count > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::vector<double> rtt;
  T& s = PayloadFor<T>(payload);
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds);
  uint32_t seq = 0;
  auto none = [](const T*) {};
  while (rover::MonotonicNow() < end) {
    SetSeq(s, ++seq);
    const rover::Time t0 = rover::MonotonicNow();
    dds_write(r.writer, &s);
    std::size_t got = 0;
    while (got == 0 && rover::MonotonicNow() < end) got = RawWaitTake<T>(r, DDS_MSECS(500), none);
    if (got) rtt.push_back(rover::ToSeconds(rover::MonotonicNow() - t0) * 1e6);
  }
  if (rtt.empty()) return out;
  std::sort(rtt.begin(), rtt.end());
  out.p50_us = rtt[rtt.size() / 2];
  out.p90_us = rtt[rtt.size() * 9 / 10];
  out.count = rtt.size();
  return out;
}

template <class T>
void RawPub(int domain, double seconds, Payload& payload) {
  Raw r;
  if (!MakeRaw<T>(r, domain, "bench/data", nullptr, QosProfile::kCommand)) return;
  dds_publication_matched_status_t pm{};
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    dds_get_publication_matched_status(r.writer, &pm);
  } while (pm.current_count < 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  T& s = PayloadFor<T>(payload);
  const rover::Time end = rover::MonotonicNow() + rover::Seconds(seconds + 2.0);
  uint32_t seq = 0;
  while (rover::MonotonicNow() < end) {
    SetSeq(s, ++seq);
    dds_write(r.writer, &s);
  }
}

std::string Self() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  return std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
}

rover::Process SpawnSelf(const std::vector<std::string>& args) {
  rover::SpawnOptions o;
  o.argv = {Self()};
  o.argv.insert(o.argv.end(), args.begin(), args.end());
  auto p = rover::Process::Spawn(o);
  if (!p.ok()) {
    std::fprintf(stderr, "cannot start helper: %s\n", p.status().message().c_str());
    std::exit(1);
  }
  return std::move(*p);
}

// Runs ddsperf with `args`, returns its stdout.
std::string RunDdsperf(const std::vector<std::string>& args, const std::string& out_path,
                       rover::Process* background = nullptr) {
  std::remove(out_path.c_str());  // Spawn appends; each run needs its own output
  rover::SpawnOptions o;
  o.argv = {"ddsperf"};
  o.argv.insert(o.argv.end(), args.begin(), args.end());
  if (std::getenv("ROVER_BENCH_VERBOSE")) {
    std::string cmd;
    for (const auto& a : o.argv) cmd += a + " ";
    std::fprintf(stderr, "  $ %s\n", cmd.c_str());
  }
  o.stdout_path = out_path;
  o.stderr_path = out_path;
  auto p = rover::Process::Spawn(o);
  if (!p.ok()) {
    std::fprintf(stderr, "ddsperf: %s\n", p.status().message().c_str());
    return "";
  }
  if (background) {
    *background = std::move(*p);
    return "";
  }
  p->WaitFor(std::chrono::seconds(120));
  std::ifstream in(out_path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Median of ddsperf's per-second "50%" round-trip figures (skipping the first second).
Latency ParseDdsperfPing(const std::string& text) {
  std::regex re(R"(size \d+ mean [\d.]+us min [\d.]+us 50% ([\d.]+)us 90% ([\d.]+)us .* cnt (\d+))");
  std::vector<double> p50, p90;
  std::size_t count = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    p50.push_back(std::stod((*it)[1]));
    p90.push_back(std::stod((*it)[2]));
    count += std::stoul((*it)[3]);
  }
  Latency l;
  if (p50.size() > 1) {
    p50.erase(p50.begin());
    p90.erase(p90.begin());
  }
  if (p50.empty()) return l;
  std::sort(p50.begin(), p50.end());
  std::sort(p90.begin(), p90.end());
  l.p50_us = p50[p50.size() / 2];
  l.p90_us = p90[p90.size() / 2];
  l.count = count;
  return l;
}

// Median of ddsperf sub's per-second "rate X kS/s" figures.
double ParseDdsperfRate(const std::string& text) {
  std::regex re(R"(rate ([\d.]+) (k?)S/s)");
  std::vector<double> rates;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    rates.push_back(std::stod((*it)[1]) * ((*it)[2] == "k" ? 1000.0 : 1.0));
  }
  if (rates.size() > 2) rates.erase(rates.begin());  // first second includes start-up
  if (rates.empty()) return 0;
  std::sort(rates.begin(), rates.end());
  return rates[rates.size() / 2];
}

double ReadNumber(const std::string& path) {
  std::ifstream in(path);
  double v = 0;
  in >> v;
  return v;
}

// ---- the fault seam's cost ------------------------------------------------------------------

double ThreadCpuNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

struct PerSample {
  double cpu_ns = 0, wall_ns = 0;
};

// Writes `samples` poses on dl/pose and takes each, in one process; cost per written sample.
PerSample WriteTake(const dds::Participant& p, int samples, Payload& payload) {
  auto w = dds::Writer<rover_dl_PoseEstimate>::Create(p, "dl/pose");
  auto r = dds::Reader<rover_dl_PoseEstimate>::Create(p, "dl/pose");
  PerSample out;
  if (!w.ok() || !r.ok()) return out;
  rover_dl_PoseEstimate& s = payload.small;
  std::size_t taken = 0;
  auto loop = [&](int n) {
    for (int i = 0; i < n; ++i) {
      SetSeq(s, static_cast<uint32_t>(i));
      (void)w->Write(s);
      taken += r->TakeEach([](const dds::Sample<rover_dl_PoseEstimate>&) {});
    }
  };
  loop(std::max(200, samples / 10));  // warm up
  const double cpu0 = ThreadCpuNs();
  const rover::Time wall0 = rover::MonotonicNow();
  loop(samples);
  out.cpu_ns = (ThreadCpuNs() - cpu0) / samples;
  out.wall_ns = static_cast<double>((rover::MonotonicNow() - wall0).count()) / samples;
  return out;
}

int SeamBench(int domain, int rounds, int samples, Payload& payload) {
  auto p = dds::Participant::Create(domain);
  if (!p.ok()) {
    std::fprintf(stderr, "%s\n", p.status().message().c_str());
    return 1;
  }
  rover::WallClock clock;
  rover::faults::FaultEngine engine({"rover-dds-bench", &clock, rover::Time{0}});
  auto drop = rover::faults::ParseFault("{kind: drop, topic: dl/pose, probability: 0.1, id: 1}", "bench");
  if (!drop.ok()) {
    std::fprintf(stderr, "%s\n", drop.status().message().c_str());
    return 1;
  }
  // Case 3 repeats case 0: its ratio is the noise floor of this machine and run.
  const char* names[] = {"plain wrappers", "seam, no fault", "seam, 10% drop", "plain, again"};
  constexpr int kCases = 4;
  std::vector<double> cpu[kCases], wall[kCases];
  std::mt19937 shuffle(12345);  // a fixed seed: the same order on every run
  for (int round = 0; round < rounds; ++round) {
    int order[kCases] = {0, 1, 2, 3};
    std::shuffle(order, order + kCases, shuffle);  // no case always runs first or after another
    for (int k = 0; k < kCases; ++k) {
      const int c = order[k];
      engine.Uninstall();
      engine.Clear();
      if (c == 1 || c == 2) engine.Install();
      if (c == 2) (void)engine.Add(*drop);
      const PerSample ps = WriteTake(*p, samples, payload);
      cpu[c].push_back(ps.cpu_ns);
      wall[c].push_back(ps.wall_ns);
    }
  }
  engine.Uninstall();
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  const double base_cpu = median(cpu[0]), base_wall = median(wall[0]);
  std::printf("\nrover-dds-bench: fault seam cost, write + take of rover_dl_PoseEstimate in one process\n");
  std::printf("%d samples per case, medians of %d interleaved rounds\n\n", samples, rounds);
  std::printf("%-18s %14s %14s %10s %10s\n", "case", "cpu ns/sample", "wall ns/sample", "cpu ratio",
              "wall ratio");
  for (int c = 0; c < kCases; ++c) {
    const double mc = median(cpu[c]), mw = median(wall[c]);
    std::printf("%-18s %14.0f %14.0f %10.3f %10.3f\n", names[c], mc, mw,
                base_cpu > 0 ? mc / base_cpu : 0, base_wall > 0 ? mw / base_wall : 0);
  }
  std::printf("\nratio = case / plain wrappers in the same run (thread CPU time and wall time);\n"
              "'plain, again' measures the plain wrappers a second time: its distance from 1 is the\n"
              "noise. goal: seam with no fault <= 1.02. A 10%% drop also saves the dropped samples'\n"
              "delivery, so it can come out below 1.\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rover-dds-bench: typed DDS wrappers vs ddsperf, same run, same machine"};
  std::string role = "main", size = "small", out;
  int domain = -1;
  double seconds = 4.0;
  app.add_option("--role", role, "main | pong | sub (internal)");
  app.add_option("--size", size, "small | stereo (internal)");
  app.add_option("--domain", domain, "DDS domain (internal)");
  app.add_option("--out", out, "result file (internal)");
  app.add_option("--seconds", seconds, "measurement time per case")->check(CLI::Range(1.0, 600.0));
  int rounds = 3;
  app.add_option("--rounds", rounds, "interleaved repetitions (median reported)")->check(CLI::Range(1, 20));
  std::string cases = "all";
  std::string security_dir;
  app.add_option("--security-dir", security_dir,
                 "DDS Security keys (`roverctl security init`) for --cases security");
  app.add_option("--cases", cases, "all | wrappers | seam | security")
      ->check(CLI::IsMember({"all", "wrappers", "seam", "security"}));
  int seam_samples = 20000, seam_rounds = 15;
  app.add_option("--seam-samples", seam_samples, "samples per seam case")->check(CLI::Range(1000, 10000000));
  app.add_option("--seam-rounds", seam_rounds, "interleaved seam rounds")->check(CLI::Range(1, 200));
  CLI11_PARSE(app, argc, argv);

  g_octets = size == "octets";
  if (std::getenv("CYCLONEDDS_URI") == nullptr) {
    setenv("CYCLONEDDS_URI", rover::dds::LoopbackConfigUri(ROVER_SOURCE_DIR).c_str(), 1);
  }
  if (role == "pong") {
    return size == "small" ? Pong<rover_dl_PoseEstimate>(domain, seconds)
                           : Pong<rover_hw_CameraFrame>(domain, seconds);
  }
  if (role == "sub") {
    return size == "small" ? Sub<rover_dl_PoseEstimate>(domain, seconds, out)
                           : Sub<rover_hw_CameraFrame>(domain, seconds, out);
  }
  if (role == "rawpong") {
    return size == "small" ? RawPong<rover_dl_PoseEstimate>(domain, seconds)
                           : RawPong<rover_hw_CameraFrame>(domain, seconds);
  }
  if (role == "rawsub") {
    return size == "small" ? RawSub<rover_dl_PoseEstimate>(domain, seconds, out)
                           : RawSub<rover_hw_CameraFrame>(domain, seconds, out);
  }

  // Every measurement gets a fresh domain, so leftovers of one cannot disturb the next.
  rover::dds::DomainLease lease;
  int d = 0;
  std::string dstr;
  auto next_domain = [&] {
    lease = rover::dds::DomainLease();
    auto l = rover::dds::DomainLease::AcquireFree();
    if (!l.ok()) {
      std::fprintf(stderr, "%s\n", l.status().message().c_str());
      std::exit(1);
    }
    lease = std::move(*l);
    d = lease.domain();
    dstr = std::to_string(d);
  };
  const std::string tmp = "/tmp/rover-dds-bench-" + std::to_string(getpid());
  Payload payload;
  if (cases == "seam" || cases == "all") {
    next_domain();
    const int rc = SeamBench(d, seam_rounds, seam_samples, payload);
    if (rc != 0 || cases == "seam") return rc;
  }
  // Serialised sizes, for ddsperf's KS topic ("size" includes its 12-byte fixed part).
  const std::size_t small_bytes = 432, stereo_bytes = 2 * kStereoSide * kStereoSide + 64;

  const double helper_s = seconds + 4.0;
  const std::string hs = std::to_string(helper_s), ss = std::to_string(seconds);

  // One measurement of each kind; `impl` is "ours", "raw" or "ddsperf".
  auto bytes_of = [&](const std::string& which) { return which == "stereo" ? stereo_bytes : small_bytes; };
  auto latency = [&](const std::string& impl, const std::string& which) -> Latency {
    next_domain();
    g_octets = which == "octets";
    const std::size_t bytes = bytes_of(which);
    if (impl == "ddsperf") {
      rover::Process pong;
      RunDdsperf({"-i", dstr, "-D", std::to_string(static_cast<int>(helper_s)), "pong", "waitset"},
                 tmp + "-pong.txt", &pong);
      const std::string text = RunDdsperf({"-i", dstr, "-D", std::to_string(static_cast<int>(seconds) + 1),
                                           "ping", "size", std::to_string(bytes), "waitset"},
                                          tmp + "-ping.txt");
      pong.Terminate(std::chrono::seconds(2));
      return ParseDdsperfPing(text);
    }
    rover::Process pong = SpawnSelf({"--role", impl == "raw" ? "rawpong" : "pong", "--size", which,
                                     "--domain", dstr, "--seconds", hs});
    Latency l;
    if (impl == "raw") {
      l = which == "small" ? RawPing<rover_dl_PoseEstimate>(d, seconds, payload)
                           : RawPing<rover_hw_CameraFrame>(d, seconds, payload);
    } else {
      l = which == "small" ? Ping<rover_dl_PoseEstimate>(d, seconds, payload)
                           : Ping<rover_hw_CameraFrame>(d, seconds, payload);
    }
    pong.Terminate(std::chrono::seconds(2));
    return l;
  };
  auto throughput = [&](const std::string& impl, const std::string& which) -> double {
    next_domain();
    g_octets = which == "octets";
    const std::size_t bytes = bytes_of(which);
    if (impl == "ddsperf") {
      rover::Process sub;
      RunDdsperf({"-i", dstr, "-k", "all", "-D", std::to_string(static_cast<int>(helper_s)), "sub", "waitset"},
                 tmp + "-dsub.txt", &sub);
      RunDdsperf({"-i", dstr, "-k", "all", "-D", std::to_string(static_cast<int>(seconds) + 2), "pub",
                  "size", std::to_string(bytes)},
                 tmp + "-dpub.txt");
      sub.Terminate(std::chrono::seconds(2));
      std::ifstream in(tmp + "-dsub.txt");
      std::stringstream text;
      text << in.rdbuf();
      return ParseDdsperfRate(text.str());
    }
    std::remove((tmp + "-sub.txt").c_str());
    rover::Process sub = SpawnSelf({"--role", impl == "raw" ? "rawsub" : "sub", "--size", which, "--domain",
                                    dstr, "--seconds", ss, "--out", tmp + "-sub.txt"});
    if (impl == "raw") {
      if (which == "small") RawPub<rover_dl_PoseEstimate>(d, seconds, payload);
      else RawPub<rover_hw_CameraFrame>(d, seconds, payload);
    } else {
      if (which == "small") Pub<rover_dl_PoseEstimate>(d, seconds, payload);
      else Pub<rover_hw_CameraFrame>(d, seconds, payload);
    }
    sub.WaitFor(std::chrono::seconds(30));
    sub.Terminate(std::chrono::seconds(1));
    return ReadNumber(tmp + "-sub.txt");
  };
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };

  if (cases == "security") {
    // DDS Security's cost: the typed wrappers open and secured (sign + encrypt, the governance
    // `roverctl security init` writes), interleaved rounds, medians, ratios secured / open.
    if (security_dir.empty()) {
      std::fprintf(stderr, "--cases security needs --security-dir (keys from `roverctl security "
                           "init`)\n");
      return 2;
    }
    auto secured = [&](bool on) {
      if (on) {
        setenv("ROVER_SECURITY_DIR", security_dir.c_str(), 1);
        setenv("ROVER_SECURITY_IDENTITY", "rover-dds-bench", 1);
      } else {
        unsetenv("ROVER_SECURITY_DIR");
        unsetenv("ROVER_SECURITY_IDENTITY");
      }
    };
    std::printf("\nrover-dds-bench: DDS Security's cost, typed wrappers, %.0f s per case, "
                "loopback, medians of %d interleaved rounds\n", seconds, rounds);
    std::printf("%-24s %-10s %11s %11s %9s\n", "case", "unit", "open", "secured", "sec/open");
    for (const std::string which : {"small", "stereo"}) {
      std::map<bool, std::vector<double>> p50, p90, rate;
      for (int round = 0; round < rounds; ++round) {
        for (bool on : {false, true}) {
          secured(on);
          const Latency l = latency("ours", which);
          p50[on].push_back(l.p50_us);
          p90[on].push_back(l.p90_us);
          rate[on].push_back(throughput("ours", which));
          secured(false);
          std::fprintf(stderr, "  %s %s round %d: p50 %.1f us, %.0f samples/s\n", which.c_str(),
                       on ? "secured" : "open", round + 1, l.p50_us, rate[on].back());
        }
      }
      auto row = [&](const std::string& name, const char* unit, double open, double sec) {
        std::printf("%-24s %-10s %11.1f %11.1f %9.3f\n", name.c_str(), unit, open, sec,
                    open > 0 ? sec / open : 0.0);
      };
      row(which + " round trip p50", "us", median(p50[false]), median(p50[true]));
      row(which + " round trip p90", "us", median(p90[false]), median(p90[true]));
      row(which + " throughput", "samples/s", median(rate[false]), median(rate[true]));
      row(which + " throughput", "MB/s", median(rate[false]) * bytes_of(which) / 1e6,
          median(rate[true]) * bytes_of(which) / 1e6);
    }
    std::printf("\nsecured = governance ENCRYPT for discovery, liveliness and every topic's data; "
                "the\nratios are what DDS Security costs on this machine (2 cores, shared).\n");
    return 0;
  }

  struct Row {
    std::string name, unit;
    double ours, raw, theirs;
    bool lower_is_better;
  };
  std::vector<Row> rows;
  const std::vector<std::string> impls = {"ours", "raw", "ddsperf"};
  for (const std::string which : {"small", "octets", "stereo"}) {
    const std::size_t bytes = bytes_of(which);
    std::map<std::string, std::vector<double>> p50, p90, rate;
    for (int round = 0; round < rounds; ++round) {  // interleaved, to share the machine's noise
      for (const auto& impl : impls) {
        const Latency l = latency(impl, which);
        p50[impl].push_back(l.p50_us);
        p90[impl].push_back(l.p90_us);
        rate[impl].push_back(throughput(impl, which));
        std::fprintf(stderr, "  %s %s round %d: p50 %.1f us, %.0f samples/s\n", which.c_str(),
                     impl.c_str(), round + 1, l.p50_us, rate[impl].back());
      }
    }
    rows.push_back({which + " round trip p50", "us", median(p50["ours"]), median(p50["raw"]),
                    median(p50["ddsperf"]), true});
    rows.push_back({which + " round trip p90", "us", median(p90["ours"]), median(p90["raw"]),
                    median(p90["ddsperf"]), true});
    rows.push_back({which + " throughput", "samples/s", median(rate["ours"]), median(rate["raw"]),
                    median(rate["ddsperf"]), false});
    rows.push_back({which + " throughput", "MB/s", median(rate["ours"]) * bytes / 1e6,
                    median(rate["raw"]) * bytes / 1e6, median(rate["ddsperf"]) * bytes / 1e6, false});
  }
  for (const char* f : {"-pong.txt", "-ping.txt", "-sub.txt", "-dsub.txt", "-dpub.txt"}) {
    std::remove((tmp + f).c_str());
  }

  std::printf("\nrover-dds-bench: typed wrappers vs raw C API vs ddsperf, %.0f s per case, loopback\n",
              seconds);
  std::printf("small = rover_dl_PoseEstimate (%zu B serialised); octets = rover_hw_CameraFrame with\n"
              "two 180-byte images (%zu B, shaped like ddsperf's KS); stereo = 512x512 pair (%zu B)\n\n",
              small_bytes, small_bytes, stereo_bytes);
  std::printf("%-24s %-10s %11s %11s %11s %9s %9s\n", "case", "unit", "ours", "raw C API",
              "ddsperf", "ours/raw", "ours/ddsperf");
  for (const auto& r : rows) {
    std::printf("%-24s %-10s %11.1f %11.1f %11.1f %9.3f %9.3f\n", r.name.c_str(), r.unit.c_str(),
                r.ours, r.raw, r.theirs, r.raw > 0 ? r.ours / r.raw : 0,
                r.theirs > 0 ? r.ours / r.theirs : 0);
  }
  std::printf("\nmedians of %d interleaved rounds. ours/raw isolates the wrappers (same type, same\n"
              "QoS, same process layout); ours/ddsperf adds the difference between our IDL types and\n"
              "ddsperf's KS type of the same serialised size. Latency: lower is better (ratio > 1 =\n"
              "slower); throughput: higher is better (ratio < 1 = slower).\n", rounds);
  std::printf("\ngoal: wrappers cost at most +10%% over raw ddsperf (positive = slower).\n");
  std::printf("note: 2-core shared machine; rerun for spread, compare ratios not absolutes.\n");
  return 0;
}
