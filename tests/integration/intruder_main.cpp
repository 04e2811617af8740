// rover-intruder: a participant that tries to command a drive and to read the rover's pose on a
// set's domain, for the DDS Security intruder test (security_test.cpp). It joins with whatever
// identity its environment gives (ROVER_SECURITY_DIR / ROVER_SECURITY_IDENTITY, or none) and
// reports, as one JSON line, what DDS let it do:
//
//   rover-intruder --domain D --seconds S [--command-id N] [--observe 101,102]
//
//   {"participant": "ok" | "refused: ...", "writer": ..., "pose_reader": ..., "status_reader": ...,
//    "written": 12, "pose_samples": 0, "statuses": {"101": 0, ...}}
//
// With --command-id it writes a 1 m straight dl/drive_command with that id every 0.2 s; every
// dl/drive_status it reads for its own id or an --observe id is counted (a trusted observer
// counts the intruders' ids this way).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/drive_idl.hpp"
#include "rover/runtime/dds.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rover-intruder: try to command a drive and read dl/pose on a domain"};
  int domain = -1;
  double seconds = 3;
  std::uint32_t command_id = 0;
  std::string observe;
  app.add_option("--domain", domain, "DDS domain")->required()->check(CLI::Range(0, 232));
  app.add_option("--seconds", seconds, "how long to try [s]")->check(CLI::Range(0.1, 600.0));
  app.add_option("--command-id", command_id, "write drive commands with this id (0: none)");
  app.add_option("--observe", observe, "other command ids whose drive statuses are counted");
  CLI11_PARSE(app, argc, argv);

  nlohmann::json out;
  std::map<std::uint32_t, int> statuses;
  if (command_id > 0) statuses[command_id] = 0;
  std::stringstream ids(observe);
  for (std::string id; std::getline(ids, id, ',');) {
    if (!id.empty()) statuses[static_cast<std::uint32_t>(std::stoul(id))] = 0;
  }
  auto p = rover::dds::Participant::Create(static_cast<dds_domainid_t>(domain));
  if (!p.ok()) {
    out["participant"] = "refused: " + p.status().message();
    std::cout << out.dump() << std::endl;
    return 0;
  }
  out["participant"] = "ok";
  std::optional<rover::dds::Writer<rover_dl_DriveCommand>> writer;
  if (command_id > 0) {
    auto w = rover::dds::Writer<rover_dl_DriveCommand>::Create(*p, "dl/drive_command");
    out["writer"] = w.ok() ? "ok" : "refused: " + w.status().message();
    if (w.ok()) writer.emplace(std::move(*w));
  }
  auto pose = rover::dds::Reader<rover_dl_PoseEstimate>::Create(*p, "dl/pose");
  out["pose_reader"] = pose.ok() ? "ok" : "refused: " + pose.status().message();
  auto status = rover::dds::Reader<rover_dl_DriveStatus>::Create(*p, "dl/drive_status");
  out["status_reader"] = status.ok() ? "ok" : "refused: " + status.status().message();

  int written = 0;
  int pose_samples = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  auto next_write = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() < end) {
    if (writer && std::chrono::steady_clock::now() >= next_write) {
      rover::msg::DriveCommand c;
      c.stamp = rover::WallNow();
      c.command_id = command_id;
      c.primitive = rover::msg::DrivePrimitive::kStraight;
      c.distance = 1.0;
      rover_dl_DriveCommand wire{};
      rover::msg::DriveCommandToIdl(c, &wire);
      if (writer->Write(wire).ok()) ++written;
      next_write += std::chrono::milliseconds(200);
    }
    if (pose.ok()) {
      pose->TakeEach([&](const rover::dds::Sample<rover_dl_PoseEstimate>&) { ++pose_samples; });
    }
    if (status.ok()) {
      status->TakeEach([&](const rover::dds::Sample<rover_dl_DriveStatus>& s) {
        auto it = statuses.find(s->command_id);
        if (it != statuses.end()) ++it->second;
      });
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  out["written"] = written;
  out["pose_samples"] = pose_samples;
  nlohmann::json st = nlohmann::json::object();
  for (const auto& [id, n] : statuses) st[std::to_string(id)] = n;
  out["statuses"] = st;
  std::cout << out.dump() << std::endl;
  return 0;
}
