#include "rover/deploy/set_faults.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "rover/runtime/fault_yaml.hpp"

namespace rover::deploy {

std::string FlowYaml(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

namespace {

bool SetsId(const faults::FaultSpec& s) { return s.key_lines.count("id") > 0; }

}  // namespace

Result<std::vector<SetFault>> ParseSetFaults(const YAML::Node& list, const std::string& file) {
  if (!list.IsSequence()) {
    return InvalidArgument(file + ":" + std::to_string(list.Mark().line + 1) +
                           ": expected a list of faults");
  }
  ROVER_ASSIGN_OR_RETURN(std::vector<faults::FaultSpec> specs, faults::ParseFaults(list, file));
  std::vector<SetFault> out;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    out.push_back({std::move(specs[i]), FlowYaml(list[i])});
  }
  return out;
}

Status AppendSetFaults(std::vector<SetFault> more, std::vector<SetFault>* faults) {
  std::uint32_t next = 1;
  for (const auto& f : *faults) next = std::max(next, f.spec.id + 1);
  for (const auto& m : more) {
    if (SetsId(m.spec)) next = std::max(next, m.spec.id + 1);
  }
  for (auto& m : more) {
    if (!SetsId(m.spec)) {
      m.spec.id = next++;
      continue;
    }
    for (const auto& f : *faults) {
      if (f.spec.id == m.spec.id) {
        return InvalidArgument(m.spec.source + ":" + std::to_string(m.spec.key_lines.at("id")) +
                               ": key 'id': fault id " + std::to_string(m.spec.id) +
                               " is already used by the fault of " + f.spec.source + ":" +
                               std::to_string(f.spec.line));
      }
    }
  }
  for (auto& m : more) faults->push_back(std::move(m));
  return Status::Ok();
}

std::string SetFaultsFileText(const std::vector<SetFault>& faults) {
  std::string out =
      "# the set's faults (x-rover.faults, a scenario's faults:), written by roverctl\n";
  for (const auto& f : faults) {
    YAML::Node n = YAML::Load(f.yaml);
    n["id"] = f.spec.id;
    out += "- " + FlowYaml(n) + "\n";
  }
  return out;
}

bool AppliesInService(const faults::FaultRecord& r) {
  static constexpr std::string_view kNotHere = " (not for this service)";
  const std::string_view d = r.detail;
  return d.size() < kNotHere.size() || d.substr(d.size() - kNotHere.size()) != kNotHere;
}

std::string SetFaultsPath(const std::string& state_dir) { return state_dir + "/faults.yaml"; }

Status WriteSetFaults(const std::vector<SetFault>& faults, const std::string& state_dir) {
  std::error_code ec;
  std::filesystem::create_directories(state_dir, ec);
  const std::string path = SetFaultsPath(state_dir);
  std::ofstream out(path);
  out << SetFaultsFileText(faults);
  if (!out) return Unavailable("cannot write " + path);
  return Status::Ok();
}

}  // namespace rover::deploy
