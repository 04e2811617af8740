#include "rover/deploy/campaign.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <unistd.h>

#include "rover/base/clock.hpp"

namespace rover::deploy {
namespace fs = std::filesystem;

namespace {

struct Slot {
  std::uint32_t seed = 0;
  std::string note = "idle";
  double sim_s = 0;
  bool busy = false;
};

std::string Eta(double s) {
  if (s < 0 || !std::isfinite(s)) return "--:--";
  char b[32];
  std::snprintf(b, sizeof b, "%02d:%02d", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  return b;
}

}  // namespace

bool CampaignResult::all_passed() const {
  if (interrupted || !errors.empty() || !missing.empty() || runs.empty()) return false;
  return std::all_of(runs.begin(), runs.end(), [](const RunResult& r) { return r.pass; });
}

Status CheckOutputFolder(const std::string& dir, const std::string& scenario) {
  if (!fs::exists(dir)) return Status::Ok();
  if (!fs::is_directory(dir)) return InvalidArgument("--out " + dir + ": exists and is not a folder");
  if (fs::is_empty(dir)) return Status::Ok();
  if (IsRunFolder(dir)) {
    std::string earlier;
    try {
      std::ifstream in(dir + "/campaign.json");
      const nlohmann::json c = nlohmann::json::parse(in);
      if (c.value("type", "") == "fault_campaign") {
        return InvalidArgument("--out " + dir +
                               ": holds a fault campaign (roverctl run --faults); choose another "
                               "folder");
      }
      earlier = c.value("scenario", "");
    } catch (const nlohmann::json::exception&) {
    }
    if (!scenario.empty() && !earlier.empty() && earlier != scenario) {
      return InvalidArgument("--out " + dir + ": holds a campaign of scenario '" + earlier +
                             "', not '" + scenario + "'; choose another folder");
    }
    return Status::Ok();
  }
  return InvalidArgument("--out " + dir +
                         ": exists and is not a run folder (no campaign.json); choose another "
                         "folder so nothing of yours is overwritten");
}

Result<CampaignResult> RunCampaign(const Scenario& scenario, const CampaignOptions& options) {
  ROVER_RETURN_IF_ERROR(CheckOutputFolder(options.out_dir, scenario.name));
  if (options.seeds.empty()) return InvalidArgument("no seeds to run");
  if (options.jobs < 1 || options.jobs > 16) return InvalidArgument("--jobs must be in [1, 16]");
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) return Unavailable("cannot create " + options.out_dir + ": " + ec.message());
  {
    nlohmann::json c;
    c["scenario"] = scenario.name;
    c["scenario_file"] = fs::absolute(scenario.file).string();
    c["seeds"] = options.seeds;
    c["jobs"] = options.jobs;
    c["pid"] = static_cast<int>(getpid());  // a report on a running campaign says so
    std::ofstream(options.out_dir + "/campaign.json") << c.dump(2) << "\n";
  }

  const Time start = MonotonicNow();
  std::mutex mu;
  std::size_t next = 0;
  std::vector<RunResult> done;
  std::vector<std::string> errors;
  std::vector<Slot> slots(static_cast<std::size_t>(options.jobs));
  const std::size_t total = options.seeds.size();

  auto draw = [&](bool final_draw) {
    // Callers hold `mu`.
    const double elapsed = ToSeconds(MonotonicNow() - start);
    const std::size_t finished = done.size() + errors.size();
    const double eta = finished ? elapsed / finished * (total - finished) : -1;
    int passed = 0;
    for (const auto& r : done) passed += r.pass;
    if (options.tty) {
      const int width = 30;
      const int fill = static_cast<int>(width * static_cast<double>(finished) / total);
      std::string bar(static_cast<std::size_t>(fill), '#');
      bar += std::string(static_cast<std::size_t>(width - fill), '.');
      std::fprintf(stderr, "\r\033[K%s [%s] %zu/%zu  pass %d  fail %zu  elapsed %s  eta %s\n",
                   scenario.name.c_str(), bar.c_str(), finished, total, passed,
                   finished - static_cast<std::size_t>(passed), Eta(elapsed).c_str(), Eta(eta).c_str());
      for (const auto& s : slots) {
        if (s.busy) {
          std::fprintf(stderr, "\033[K  seed %-6u %-28s sim %7.1f s\n", s.seed, s.note.c_str(), s.sim_s);
        } else {
          std::fprintf(stderr, "\033[K  %s\n", "(idle)");
        }
      }
      if (!final_draw) std::fprintf(stderr, "\033[%zuA", slots.size() + 1);
      std::fflush(stderr);
    }
  };

  auto worker = [&](std::size_t slot_index) {
    while (true) {
      std::uint32_t seed = 0;
      {
        std::lock_guard lock(mu);
        if (next >= total || (options.abort && options.abort->load())) return;
        seed = options.seeds[next++];
        slots[slot_index] = {seed, "starting", 0, true};
        draw(false);
      }
      RunOptions ro;
      ro.out_dir = options.out_dir;
      ro.bin_dir = options.bin_dir;
      ro.dds_config_uri = options.dds_config_uri;
      ro.security = options.security;
      ro.security_dir = options.security_dir;
      ro.abort = options.abort;
      ro.progress = [&, slot_index](const std::string& note, double sim_s) {
        std::lock_guard lock(mu);
        slots[slot_index].note = note;
        slots[slot_index].sim_s = sim_s;
        draw(false);
      };
      auto r =
          options.run_one ? options.run_one(scenario, seed, ro) : RunScenario(scenario, seed, ro);
      std::lock_guard lock(mu);
      slots[slot_index].busy = false;
      if (!r.ok()) {
        errors.push_back("seed " + std::to_string(seed) + ": " + r.status().message());
        if (!options.tty) std::printf("seed %u: ERROR %s\n", seed, r.status().message().c_str());
      } else {
        done.push_back(std::move(*r));
        if (!options.tty) {
          // One line per finished run, with what is left: a campaign without a terminal (nohup,
          // CI) is followed in its log.
          const RunResult& d = done.back();
          const std::size_t finished = done.size() + errors.size();
          const double elapsed = ToSeconds(MonotonicNow() - start);
          const std::size_t left = total - finished;
          const double eta = finished > 0 ? elapsed / static_cast<double>(finished) *
                                                static_cast<double>(left)
                                          : 0.0;
          std::printf("seed %u: %s  %.2f m  %.1f sim s  %.1f wall s  [%zu/%zu done, %zu left, "
                      "about %s to go]%s%s\n",
                      seed, d.pass ? "PASS" : Interrupted(d) ? "INTERRUPTED" : "FAIL",
                      d.distance_driven, d.sim_time_s, d.wall_time_s, finished, total, left,
                      Eta(eta).c_str(), d.failure.empty() ? "" : "  ", d.failure.c_str());
          std::fflush(stdout);
        }
      }
      draw(false);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < options.jobs; ++j) threads.emplace_back(worker, static_cast<std::size_t>(j));
  for (auto& t : threads) t.join();
  {
    std::lock_guard lock(mu);
    if (options.tty) draw(true);
  }

  CampaignResult out;
  out.interrupted = options.abort && options.abort->load();
  std::sort(done.begin(), done.end(), [](const RunResult& a, const RunResult& b) { return a.seed < b.seed; });
  out.runs = std::move(done);
  out.errors = std::move(errors);
  WriteCampaignFiles(options.out_dir, scenario.name, options.seeds,
                     ToSeconds(MonotonicNow() - start), &out);
  return out;
}

void WriteCampaignFiles(const std::string& dir, const std::string& scenario,
                        const std::vector<std::uint32_t>& seeds, double wall_s,
                        CampaignResult* out) {
  out->summary = Summarize(out->runs, wall_s);
  out->summary.scenario = scenario;
  out->missing = MissingRuns(dir, scenario, seeds, out->runs);
  nlohmann::json sj = ToJson(out->summary);
  sj["interrupted"] = out->interrupted;
  sj["errors"] = out->errors;
  sj["seeds"] = seeds.size();
  sj["missing"] = nlohmann::json::array();
  for (const auto& m : out->missing) sj["missing"].push_back({{"seed", m.seed}, {"started", m.started}});
  std::ofstream(dir + "/summary.json") << sj.dump(2) << "\n";
  std::ofstream(dir + "/junit.xml") << ToJunitXml(out->runs, scenario);
  std::ofstream(dir + "/summary.txt") << FormatSummaryTable(out->runs, out->summary, out->missing);
}

}  // namespace rover::deploy
