#include "fleet_state.h"

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/version.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string fnv1a64(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return std::string("fnv1a64:") + hex;
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the file");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

Json fileIdentity(const fs::path& file, const std::string& name) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec) throw Error(file.string() + ": cannot read the file: " + ec.message());
  const auto mtime = fs::last_write_time(file, ec).time_since_epoch();
  return Json::array(
      {name, size, std::chrono::duration_cast<std::chrono::nanoseconds>(mtime).count()});
}

}  // namespace

std::string FleetPaths::logOut(const std::string& name) const {
  return (fs::path(root) / "logs" / name).string();
}
std::string FleetPaths::stateDir(const std::string& name) const {
  return (fs::path(root) / "state" / name).string();
}
std::string FleetPaths::stateFile(const std::string& name) const {
  return (fs::path(stateDir(name)) / "state.json").string();
}
std::string FleetPaths::configFile(const std::string& name) const {
  return (fs::path(stateDir(name)) / "config.yaml").string();
}
std::string FleetPaths::runLog(const std::string& name) const {
  return (fs::path(stateDir(name)) / "run.log").string();
}
std::string FleetPaths::planFile(int submission) const {
  return (fs::path(root) / "state" / ("plan-" + std::to_string(submission) + ".json")).string();
}
std::string FleetPaths::slurmDir() const {
  return (fs::path(root) / "state" / "slurm").string();
}

Json usedBy(const FleetLog& log, const std::string& effective_config_yaml) {
  Json files = Json::array();
  if (fs::is_directory(log.path)) {
    std::vector<fs::path> entries;
    for (const auto& e : fs::recursive_directory_iterator(log.path))
      if (e.is_regular_file()) entries.push_back(e.path());
    std::sort(entries.begin(), entries.end());
    for (const fs::path& e : entries)
      files.push_back(fileIdentity(e, e.lexically_relative(log.path).string()));
  } else {
    files.push_back(fileIdentity(log.path, fs::path(log.path).filename().string()));
  }
  Json used = {{"storey_version", storeyVersion()},
               {"input", {{"path", log.path}, {"files", files}}},
               {"calibration", nullptr},
               {"config_hash", fnv1a64(effective_config_yaml)}};
  if (!log.calibration.empty())
    used["calibration"] = {{"path", log.calibration}, {"hash", fnv1a64(fileText(log.calibration))}};
  return used;
}

std::optional<LogState> readLogState(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  const Json j = Json::parse(in, nullptr, false);
  if (!j.is_object()) return std::nullopt;
  LogState s;
  s.status = j.value("status", "");
  s.used = j.value("used", Json());
  s.attempts = j.value("attempts", 0);
  s.error = j.value("error", "");
  s.wall_time_s = j.value("wall_time_s", 0.0);
  s.peak_memory_mb = j.value("peak_memory_mb", 0.0);
  s.started_at = j.value("started_at", "");
  s.finished_at = j.value("finished_at", "");
  s.executor = j.value("executor", "");
  s.submission = j.value("submission", 0);
  return s;
}

void writeLogState(const std::string& path, const LogState& s) {
  const Json j = {{"status", s.status},           {"used", s.used},
                  {"attempts", s.attempts},       {"error", s.error},
                  {"wall_time_s", s.wall_time_s}, {"peak_memory_mb", s.peak_memory_mb},
                  {"started_at", s.started_at},   {"finished_at", s.finished_at},
                  {"executor", s.executor},       {"submission", s.submission}};
  fs::create_directories(fs::path(path).parent_path());
  writeFileAtomically(path, j.dump(2) + "\n");
}

std::string whyRun(const std::optional<LogState>& previous, const Json& used, bool only_failed,
                   bool force) {
  if (force) return "--force";
  if (only_failed) return previous && previous->status == "failed" ? "failed before" : "";
  if (!previous) return "new";
  if (previous->status != "done" && previous->status != "failed")
    return "not finished (" + previous->status + ")";
  const Json& was = previous->used;
  if (!was.is_object()) return "no record of its last run";
  if (was.value("storey_version", "") != used["storey_version"]) return "Storey version changed";
  if (was.value("input", Json()) != used["input"]) return "input changed";
  if (was.value("calibration", Json()) != used["calibration"]) return "calibration changed";
  if (was.value("config_hash", "") != used["config_hash"]) return "config changed";
  return "";
}

void writePlan(const FleetPlan& plan) {
  Json logs = Json::array();
  for (const PlannedLog& p : plan.logs)
    logs.push_back({{"name", p.log.name},
                    {"path", p.log.path},
                    {"calibration", p.log.calibration},
                    {"source", p.log.source},
                    {"used", p.used},
                    {"reason", p.reason}});
  const Json j = {{"format", "storey-batch-plan"},
                  {"version", 1},
                  {"fleet_out", plan.fleet_out},
                  {"submission", plan.submission},
                  {"retries", plan.retries},
                  {"executor", plan.executor},
                  {"logs", logs},
                  {"tasks", plan.tasks},
                  {"job_id", plan.job_id},
                  {"collect_job_id", plan.collect_job_id}};
  const FleetPaths paths{plan.fleet_out};
  fs::create_directories(fs::path(paths.planFile(plan.submission)).parent_path());
  writeFileAtomically(paths.planFile(plan.submission), j.dump(1) + "\n");
}

FleetPlan readPlan(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot read the batch plan");
  const Json j = Json::parse(in, nullptr, false);
  if (!j.is_object() || j.value("format", "") != "storey-batch-plan")
    throw Error(path + ": not a storey batch plan");
  FleetPlan plan;
  try {
    plan.fleet_out = j.at("fleet_out").get<std::string>();
    plan.submission = j.at("submission").get<int>();
    plan.retries = j.at("retries").get<int>();
    plan.executor = j.at("executor").get<std::string>();
    for (const Json& l : j.at("logs")) {
      PlannedLog p;
      p.log.name = l.at("name").get<std::string>();
      p.log.path = l.at("path").get<std::string>();
      p.log.calibration = l.at("calibration").get<std::string>();
      p.log.source = l.at("source").get<std::string>();
      p.used = l.at("used");
      p.reason = l.at("reason").get<std::string>();
      plan.logs.push_back(std::move(p));
    }
    plan.tasks = j.at("tasks").get<std::vector<std::size_t>>();
    plan.job_id = j.value("job_id", "");
    plan.collect_job_id = j.value("collect_job_id", "");
  } catch (const Json::exception& e) {
    throw Error(path + ": damaged batch plan: " + e.what());
  }
  for (std::size_t t : plan.tasks)
    if (t >= plan.logs.size()) throw Error(path + ": damaged batch plan: task out of range");
  return plan;
}

std::optional<FleetPlan> latestPlan(const std::string& fleet_out) {
  const fs::path dir = fs::path(fleet_out) / "state";
  int newest = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("plan-", 0) == 0 && e.path().extension() == ".json") {
      try {
        newest = std::max(newest, std::stoi(name.substr(5)));
      } catch (const std::exception&) {
      }
    }
  }
  if (newest == 0) return std::nullopt;
  return readPlan(FleetPaths{fs::absolute(fleet_out).string()}.planFile(newest));
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace storey::cli
