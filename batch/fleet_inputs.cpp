#include "fleet_inputs.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "common/error.h"
#include "common/yaml_section.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool hasPcdFiles(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file() && lower(entry.path().extension().string()) == ".pcd") return true;
  return false;
}

/// A rosbag2 folder: metadata.yaml beside its .db3 or .mcap files (one log).
bool isRosbag2Folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "metadata.yaml", ec);
}

bool isLogFileName(const fs::path& path) {
  const std::string ext = lower(path.extension().string());
  return ext == ".bag" || ext == ".pcap" || ext == ".pcapng" || ext == ".db3" || ext == ".mcap";
}

/// The logs under `root`: log files by name, rosbag2 and PCD folders (not entered).
void searchFolder(const fs::path& root, std::vector<fs::path>& found) {
  std::error_code ec;
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(root, ec)) entries.push_back(entry.path());
  if (ec) throw Error(root.string() + ": cannot list the folder: " + ec.message());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& p : entries) {
    if (fs::is_directory(p, ec)) {
      if (hasPcdFiles(p) || isRosbag2Folder(p))
        found.push_back(p);
      else
        searchFolder(p, found);
    } else if (isLogFileName(p)) {
      found.push_back(p);
    }
  }
}

std::string sanitised(const std::string& text) {
  std::string name = text;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  while (!name.empty() && name.front() == '.') name.erase(name.begin());
  return name.empty() ? "log" : name;
}

/// The path's components, the last without its extension.
std::vector<std::string> nameParts(const std::string& path) {
  fs::path p = fs::path(path).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  std::vector<std::string> parts;
  for (const auto& part : p.parent_path())
    if (part != "/" && !part.empty()) parts.push_back(part.string());
  parts.push_back(p.stem().string());
  return parts;
}

std::string scalarOf(const YAML::Node& node, const std::string& source, const std::string& key) {
  if (!node.IsScalar())
    throw Error(source + ": key '" + key + "' (line " + std::to_string(node.Mark().line + 1) +
                ") must be a text");
  return node.as<std::string>();
}

void checkKeys(const YAML::Node& map, const std::string& source, const std::string& where,
               const std::set<std::string>& allowed) {
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    if (!allowed.count(key)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw Error(source + ": unknown key '" + where + key + "' (line " +
                  std::to_string(kv.first.Mark().line + 1) + "); expected one of " + list);
    }
  }
}

SlurmSettings readSlurm(const YAML::Node& node, const std::string& source) {
  SlurmSettings s;
  if (!node || node.IsNull()) return s;
  if (!node.IsMap()) throw Error(source + ": 'slurm' must be a mapping");
  checkKeys(node, source, "slurm.",
            {"partition", "account", "cpus_per_task", "mem", "time", "extra_args", "prolog"});
  if (node["partition"]) s.partition = scalarOf(node["partition"], source, "slurm.partition");
  if (node["account"]) s.account = scalarOf(node["account"], source, "slurm.account");
  if (node["mem"]) s.mem = scalarOf(node["mem"], source, "slurm.mem");
  if (node["time"]) s.time = scalarOf(node["time"], source, "slurm.time");
  if (node["prolog"]) s.prolog = scalarOf(node["prolog"], source, "slurm.prolog");
  if (node["cpus_per_task"]) {
    try {
      s.cpus_per_task = node["cpus_per_task"].as<int>();
    } catch (const YAML::Exception&) {
      throw Error(source + ": 'slurm.cpus_per_task' must be a whole number");
    }
    if (*s.cpus_per_task < 1) throw Error(source + ": 'slurm.cpus_per_task' must be at least 1");
  }
  if (const YAML::Node extra = node["extra_args"]) {
    if (!extra.IsSequence()) throw Error(source + ": 'slurm.extra_args' must be a list");
    for (const YAML::Node& a : extra)
      s.extra_args.push_back(scalarOf(a, source, "slurm.extra_args"));
  }
  return s;
}

bool isManifest(const fs::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext != ".yaml" && ext != ".yml") return false;
  try {
    const YAML::Node root = YAML::LoadFile(path.string());
    return root.IsMap() && root["logs"];
  } catch (const YAML::Exception&) {
    return false;
  }
}

struct Named {
  FleetLog log;
  std::string given_name;
};

void readManifest(const fs::path& path, const std::string& default_calibration,
                  std::vector<Named>& logs, FleetInputs& inputs) {
  const std::string source = path.string();
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const YAML::Node root = parseYaml(text.str(), source);
  checkKeys(root, source, "", {"config", "calibration", "slurm", "logs"});
  const fs::path base = fs::absolute(path).parent_path();
  auto resolve = [&base](const std::string& p) { return (base / p).lexically_normal().string(); };
  if (root["config"]) {
    if (!inputs.config_path.empty())
      throw Error(source + ": 'config' given by a second manifest (one base config per batch)");
    inputs.config_path = resolve(scalarOf(root["config"], source, "config"));
  }
  const std::string calibration =
      root["calibration"] ? resolve(scalarOf(root["calibration"], source, "calibration"))
                          : default_calibration;
  if (root["slurm"]) inputs.slurm = readSlurm(root["slurm"], source);
  const YAML::Node list = root["logs"];
  if (!list.IsSequence() || list.size() == 0)
    throw Error(source +
                ": 'logs' must be a list of logs (each a path, or path/name/calibration/"
                "config)");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    const std::string where = "logs[" + std::to_string(i) + "]";
    Named named;
    named.log.source =
        source + " " + where + " (line " + std::to_string(entry.Mark().line + 1) + ")";
    named.log.calibration = calibration;
    if (entry.IsScalar()) {
      named.log.path = resolve(entry.as<std::string>());
    } else if (entry.IsMap()) {
      checkKeys(entry, source, where + ".", {"path", "name", "calibration", "config"});
      if (!entry["path"]) throw Error(named.log.source + ": 'path' is required");
      named.log.path = resolve(scalarOf(entry["path"], source, where + ".path"));
      if (entry["name"]) {
        named.given_name = scalarOf(entry["name"], source, where + ".name");
        if (named.given_name != sanitised(named.given_name))
          throw Error(named.log.source + ": name '" + named.given_name +
                      "' may hold only letters, digits, '.', '_' and '-' (not first '.')");
      }
      if (entry["calibration"])
        named.log.calibration =
            resolve(scalarOf(entry["calibration"], source, where + ".calibration"));
      if (const YAML::Node config = entry["config"]; config && !config.IsNull()) {
        if (!config.IsMap())
          throw Error(named.log.source + ": 'config' must be a mapping of config keys");
        YAML::Emitter out;
        out << config;
        named.log.config_overrides = out.c_str();
      }
    } else {
      throw Error(named.log.source + ": expected a path or a mapping with 'path'");
    }
    if (!fs::exists(named.log.path))
      throw Error(named.log.source + ": log '" + named.log.path + "' does not exist");
    logs.push_back(std::move(named));
  }
}

}  // namespace

std::vector<std::string> uniqueLogNames(const std::vector<std::string>& paths,
                                        const std::vector<std::string>& given) {
  const std::size_t n = paths.size();
  std::vector<std::vector<std::string>> parts(n);
  std::vector<std::size_t> depth(n, 1);
  std::vector<std::string> names(n);
  for (std::size_t i = 0; i < n; ++i) parts[i] = nameParts(paths[i]);
  auto nameAt = [&](std::size_t i) {
    if (i < given.size() && !given[i].empty()) return given[i];
    const auto& p = parts[i];
    const std::size_t k = std::min(depth[i], p.size());
    std::string name;
    for (std::size_t j = p.size() - k; j < p.size(); ++j) name += (name.empty() ? "" : "-") + p[j];
    return sanitised(name);
  };
  for (bool changed = true; changed;) {
    changed = false;
    std::map<std::string, std::vector<std::size_t>> by_name;
    for (std::size_t i = 0; i < n; ++i) by_name[names[i] = nameAt(i)].push_back(i);
    for (const auto& [name, members] : by_name) {
      if (members.size() < 2) continue;
      for (std::size_t i : members) {
        const bool fixed = i < given.size() && !given[i].empty();
        if (!fixed && depth[i] < parts[i].size()) {
          ++depth[i];
          changed = true;
        }
      }
    }
  }
  return names;
}

FleetInputs collectFleetInputs(const std::vector<std::string>& input_args,
                               const std::string& calibration) {
  if (input_args.empty()) throw Error("storey batch: no INPUTS given (logs, folders or manifests)");
  FleetInputs inputs;
  std::vector<Named> logs;
  const std::string default_calibration =
      calibration.empty() ? std::string() : fs::absolute(calibration).lexically_normal().string();
  for (const std::string& arg : input_args) {
    const fs::path path(arg);
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(arg + ": no such log, folder or manifest");
    if (fs::is_directory(path, ec) && !hasPcdFiles(path) && !isRosbag2Folder(path)) {
      std::vector<fs::path> found;
      searchFolder(path, found);
      if (found.empty())
        throw Error(arg +
                    ": no logs found in the folder (*.bag, *.pcap, *.pcapng, *.db3, *.mcap, "
                    "rosbag2 and PCD folders)");
      for (const fs::path& p : found) {
        Named named;
        named.log.path = fs::absolute(p).lexically_normal().string();
        named.log.calibration = default_calibration;
        named.log.source = "found in " + arg;
        logs.push_back(std::move(named));
      }
    } else if (isManifest(path)) {
      readManifest(path, default_calibration, logs, inputs);
    } else {
      Named named;
      named.log.path = fs::absolute(path).lexically_normal().string();
      named.log.calibration = default_calibration;
      named.log.source = "command line";
      logs.push_back(std::move(named));
    }
  }
  std::map<std::string, std::string> seen;  // path -> source
  std::vector<std::string> paths, given;
  for (const Named& n : logs) {
    const auto [it, inserted] = seen.emplace(n.log.path, n.log.source);
    if (!inserted)
      throw Error(n.log.path + ": the log is given twice (" + it->second + "; " + n.log.source +
                  ")");
    if (!n.log.calibration.empty() && !fs::is_regular_file(n.log.calibration))
      throw Error(n.log.source + ": calibration file '" + n.log.calibration + "' does not exist");
    paths.push_back(n.log.path);
    given.push_back(n.given_name);
  }
  const std::vector<std::string> names = uniqueLogNames(paths, given);
  std::map<std::string, std::size_t> by_name;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const auto [it, inserted] = by_name.emplace(names[i], i);
    if (!inserted)
      throw Error("two logs named '" + names[i] + "': " + logs[it->second].log.path + " and " +
                  logs[i].log.path + " (give them names in a manifest)");
    logs[i].log.name = names[i];
    inputs.logs.push_back(logs[i].log);
  }
  return inputs;
}

}  // namespace storey::cli
