#include "executor_slurm.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "child_process.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "io/rosbag_structure.h"
#include "progress_bar.h"
#include "stop_signals.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

std::string shellQuoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs a Slurm client command; a missing command is an error naming it.
ChildResult slurmCommand(const std::string& program, const std::vector<std::string>& args) {
  if (!onPath(program))
    throw Error(program +
                ": not found on PATH (the Slurm client commands are needed for "
                "--executor slurm; Debian package slurm-client)");
  return runCommand(program, args);
}

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  std::size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

std::string durationText(double seconds) {
  const long s = static_cast<long>(std::ceil(seconds / 60.0)) * 60;
  char text[32];
  if (s >= 86400)
    std::snprintf(text, sizeof(text), "%ld-%ld:%02ld:00", s / 86400, s % 86400 / 3600,
                  s % 3600 / 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld:00", s / 3600, s % 3600 / 60);
  return text;
}

/// "key=value" of one `scontrol -o show job` line.
std::string scontrolField(const std::string& line, const std::string& key) {
  const std::string needle = " " + key + "=";
  const std::size_t at = (" " + line).find(needle);
  if (at == std::string::npos) return {};
  const std::size_t start = at + needle.size() - 1;
  return line.substr(start, line.find(' ', start) - start);
}

struct TaskEnd {
  std::string state;      ///< COMPLETED, FAILED, TIMEOUT, OUT_OF_MEMORY, CANCELLED, ...
  std::string exit_code;  ///< "exit:signal"
};

/// How the array's tasks ended, by task index: sacct when it answers, else scontrol.
std::map<int, TaskEnd> taskEnds(const std::string& job_id) {
  std::map<int, TaskEnd> ends;
  if (onPath("sacct")) {
    const ChildResult r = runCommand(
        "sacct", {"-n", "-P", "-X", "-j", job_id, "--format=JobID,State,ExitCode"}, false);
    std::istringstream lines(r.exit_code == 0 ? r.output : "");
    std::string line;
    while (std::getline(lines, line)) {
      std::istringstream fields(line);
      std::string id, state, code;
      if (!std::getline(fields, id, '|') || !std::getline(fields, state, '|')) continue;
      std::getline(fields, code, '|');
      const std::size_t underscore = id.find('_');
      if (underscore == std::string::npos) continue;
      try {
        ends[std::stoi(id.substr(underscore + 1))] = {state.substr(0, state.find(' ')), code};
      } catch (const std::exception&) {
      }
    }
    if (!ends.empty()) return ends;
  }
  const ChildResult r = runCommand("scontrol", {"-o", "show", "job", job_id}, false);
  std::istringstream lines(r.exit_code == 0 ? r.output : "");
  std::string line;
  while (std::getline(lines, line)) {
    const std::string task = scontrolField(line, "ArrayTaskId");
    if (task.empty() || task.find_first_not_of("0123456789") != std::string::npos) continue;
    ends[std::stoi(task)] = {scontrolField(line, "JobState"), scontrolField(line, "ExitCode")};
  }
  return ends;
}

/// Queue states of the array's tasks still queued (squeue), by task index.
std::optional<std::map<int, std::string>> queuedTasks(const std::string& job_id) {
  const ChildResult r = slurmCommand("squeue", {"-h", "-r", "-j", job_id, "-o", "%K %T"});
  std::map<int, std::string> tasks;
  if (r.exit_code != 0) {
    if (r.output.find("Invalid job id") != std::string::npos) return tasks;  // finished, purged
    return std::nullopt;  // squeue failed (controller busy): unknown
  }
  std::istringstream lines(r.output);
  int task;
  std::string state;
  while (lines >> task >> state) tasks[task] = state;
  return tasks;
}

std::string submit(const std::vector<std::string>& args, const std::string& what) {
  const ChildResult r = slurmCommand("sbatch", args);
  const std::string out = trimmed(r.output);
  const std::string id = out.substr(0, out.find(';'));
  if (r.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw Error("sbatch (" + what + ") failed: " + (out.empty() ? "no output" : out));
  return id;
}

}  // namespace

double estimateMemoryMb(std::uint64_t bytes, double duration_s) {
  // Peak memory of `storey run` with its renders grows with the map (the area
  // walked), for which the log's duration stands in, and the message buffers
  // with the scan size (bytes/s). Measured (docs/batch.md): 306 MB (25 s),
  // 843 MB (295 s), 1197 MB (695 s), 1228 MB (1073 s). Half as much again.
  const double mb_per_s = duration_s > 0.0 ? static_cast<double>(bytes) / duration_s / 1.0e6 : 0.0;
  return std::max(1024.0, 1.5 * (600.0 + 0.8 * duration_s + 10.0 * mb_per_s));
}

double estimateTimeSeconds(double duration_s) {
  // `storey run` maps a VLP-16 log at about 10x real time on one core; allow
  // real time plus the map and renders, and 15 minutes of queue-free slack.
  return 900.0 + 1.0 * duration_s;
}

double logDurationSeconds(const std::string& path, std::uint64_t bytes) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) {
    try {
      const RosbagStructure bag = checkRosbagStructure(path);
      if (bag.end_ns > bag.start_ns) return static_cast<double>(bag.end_ns - bag.start_ns) * 1e-9;
    } catch (const Error&) {
      // Not a bag (or a damaged one): guessed from the size below.
    }
  }
  return static_cast<double>(bytes) / 5.0e6;
}

SlurmResources slurmResources(const FleetPlan& plan, const SlurmSettings& settings) {
  SlurmResources r;
  r.cpus = settings.cpus_per_task.value_or(1);
  double mem_mb = 0.0, time_s = 0.0;
  for (std::size_t t : plan.tasks) {
    const PlannedLog& p = plan.logs[t];
    std::uint64_t bytes = 0;
    for (const auto& f : p.used["input"]["files"]) bytes += f[1].get<std::uint64_t>();
    const double duration = logDurationSeconds(p.log.path, bytes);
    mem_mb = std::max(mem_mb, estimateMemoryMb(bytes, duration));
    time_s = std::max(time_s, estimateTimeSeconds(duration));
  }
  r.mem = !settings.mem.empty()
              ? settings.mem
              : std::to_string(static_cast<long>(std::ceil(mem_mb / 256.0)) * 256) + "M";
  r.time = !settings.time.empty() ? settings.time : durationText(time_s);
  return r;
}

void submitSlurm(FleetPlan& plan, const SlurmOptions& options) {
  if (plan.tasks.empty()) return;
  const FleetPaths paths{plan.fleet_out};
  fs::create_directories(paths.slurmDir());
  const std::string storey = options.storey_binary.empty()
                                 ? fs::read_symlink("/proc/self/exe").string()
                                 : fs::absolute(options.storey_binary).string();
  const SlurmResources res = slurmResources(plan, options.settings);
  const std::string n = std::to_string(plan.submission);
  std::string array = "0-" + std::to_string(plan.tasks.size() - 1);
  if (options.max_running > 0) array += "%" + std::to_string(options.max_running);

  auto header = [&](std::ostringstream& s) {
    if (!options.settings.partition.empty())
      s << "#SBATCH --partition=" << options.settings.partition << '\n';
    if (!options.settings.account.empty())
      s << "#SBATCH --account=" << options.settings.account << '\n';
  };
  std::ostringstream script;
  script << "#!/bin/sh\n"
         << "# storey batch, submission " << n << " of " << plan.fleet_out << ":\n"
         << "# one array task per log of " << paths.planFile(plan.submission) << "\n"
         << "#SBATCH --job-name=storey-batch\n"
         << "#SBATCH --array=" << array << '\n'
         << "#SBATCH --cpus-per-task=" << res.cpus << '\n'
         << "#SBATCH --mem=" << res.mem << '\n'
         << "#SBATCH --time=" << res.time << '\n'
         << "#SBATCH --output=" << paths.slurmDir() << "/%A_%a.out\n";
  header(script);
  if (!options.settings.prolog.empty()) script << options.settings.prolog << '\n';
  script << "exec " << shellQuoted(storey) << " batch-task "
         << shellQuoted(paths.planFile(plan.submission)) << " \"$SLURM_ARRAY_TASK_ID\"\n";
  const std::string script_path = paths.slurmDir() + "/submission-" + n + ".sh";
  writeFileAtomically(script_path, script.str());

  std::vector<std::string> args{"--parsable"};
  args.insert(args.end(), options.settings.extra_args.begin(), options.settings.extra_args.end());
  args.push_back(script_path);
  plan.job_id = submit(args, "job array");
  std::cerr << "batch: submitted job array " << plan.job_id << " (" << plan.tasks.size()
            << " tasks, " << array << ", " << res.cpus << " CPU, " << res.mem << ", " << res.time
            << " each): " << script_path << '\n';

  if (options.submit_only) {
    std::ostringstream collect;
    collect << "#!/bin/sh\n"
            << "# storey batch, submission " << n << ": the fleet report once the array ended\n"
            << "#SBATCH --job-name=storey-collect\n"
            << "#SBATCH --dependency=afterany:" << plan.job_id << '\n'
            << "#SBATCH --kill-on-invalid-dep=yes\n"
            << "#SBATCH --cpus-per-task=1\n"
            << "#SBATCH --mem=1G\n"
            << "#SBATCH --time=0:15:00\n"
            << "#SBATCH --output=" << paths.slurmDir() << "/collect-%j.out\n";
    header(collect);
    if (!options.settings.prolog.empty()) collect << options.settings.prolog << '\n';
    collect << "exec " << shellQuoted(storey) << " batch --status " << shellQuoted(plan.fleet_out)
            << '\n';
    const std::string collect_path = paths.slurmDir() + "/collect-" + n + ".sh";
    writeFileAtomically(collect_path, collect.str());
    std::vector<std::string> cargs{"--parsable"};
    cargs.insert(cargs.end(), options.settings.extra_args.begin(),
                 options.settings.extra_args.end());
    cargs.push_back(collect_path);
    plan.collect_job_id = submit(cargs, "collect job");
    std::cerr << "batch: submitted collect job " << plan.collect_job_id << " (after " << plan.job_id
              << ")\n";
  }
  writePlan(plan);
}

bool slurmJobActive(const FleetPlan& plan) {
  if (plan.job_id.empty()) return false;
  const auto queued = queuedTasks(plan.job_id);
  if (!queued)
    throw Error("squeue -j " + plan.job_id +
                " failed: cannot tell whether the batch's Slurm job is still running");
  return !queued->empty();
}

bool followSlurm(const FleetPlan& plan, double poll_seconds) {
  if (plan.job_id.empty()) return true;
  const StopSignals signals;
  const FleetPaths paths{plan.fleet_out};
  const std::size_t total = plan.tasks.size();
  ProgressBar bar("batch");
  std::map<std::string, std::string> reported;  // name -> final status printed
  bool stopped = false;
  for (;;) {
    const auto queued = queuedTasks(plan.job_id);
    std::size_t done = 0, failed = 0, running = 0, pending = 0;
    for (std::size_t i = 0; i < total; ++i) {
      const PlannedLog& p = plan.logs[plan.tasks[i]];
      const auto state = readLogState(paths.stateFile(p.log.name));
      const bool ours = state && state->submission == plan.submission;
      if (ours && (state->status == "done" || state->status == "failed")) {
        (state->status == "done" ? done : failed)++;
        if (!reported.count(p.log.name)) {
          reported[p.log.name] = state->status;
          bar.print("batch: " + p.log.name + ": " + state->status +
                    (state->error.empty() ? "" : ": " + state->error));
        }
      } else if (queued && queued->count(static_cast<int>(i)) &&
                 queued->at(static_cast<int>(i)) == "PENDING") {
        ++pending;
      } else if (queued && queued->count(static_cast<int>(i))) {
        ++running;
      }
    }
    bar.setDetail(std::to_string(done) + " done, " + std::to_string(running) + " running, " +
                  std::to_string(failed) + " failed, " + std::to_string(pending) + " queued (job " +
                  plan.job_id + ")");
    bar.update(static_cast<double>(done + failed) / static_cast<double>(total), "logs");
    if (queued && queued->empty()) break;
    if (StopSignals::requested()) {
      bar.print("batch: stopping: scancel " + plan.job_id);
      runCommand("scancel", {plan.job_id});
      stopped = true;
      StopSignals::clear();
    }
    for (double waited = 0.0; waited < poll_seconds && !StopSignals::requested(); waited += 0.1)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  bar.done();
  return !stopped;
}

void collectSlurm(const FleetPlan& plan) {
  if (plan.job_id.empty()) return;
  const FleetPaths paths{plan.fleet_out};
  std::optional<std::map<int, TaskEnd>> ends;  // asked once, when needed
  for (std::size_t i = 0; i < plan.tasks.size(); ++i) {
    const PlannedLog& p = plan.logs[plan.tasks[i]];
    std::optional<LogState> state = readLogState(paths.stateFile(p.log.name));
    const bool ours = state && state->submission == plan.submission;
    if (ours &&
        (state->status == "done" || state->status == "failed" || state->status == "cancelled"))
      continue;
    if (!ends) ends = taskEnds(plan.job_id);
    const std::string out_file =
        paths.slurmDir() + "/" + plan.job_id + "_" + std::to_string(i) + ".out";
    LogState s = ours ? *state : LogState{};
    s.used = p.used;
    s.submission = plan.submission;
    s.executor = "slurm job " + plan.job_id + "_" + std::to_string(i);
    s.finished_at = utcNow();
    const auto end = ends->find(static_cast<int>(i));
    const std::string how =
        end != ends->end() ? end->second.state + " (exit " + end->second.exit_code + ")" : "";
    const bool never_ran = !ours && (how.empty() || end->second.state.rfind("CANCELLED", 0) == 0);
    if (never_ran) {
      s.status = "cancelled";
      s.error = "the Slurm task never ran" + (how.empty() ? std::string() : ": " + how) +
                "; re-run the batch";
    } else {  // it ended without recording its end: Slurm ended it, or storey never started
      s.status = "failed";
      s.error = "Slurm task ended " + (how.empty() ? std::string("(no record left)") : how) +
                (ours ? " before storey run finished" : " before storey started") + "; " +
                out_file + ": " + lastLine(out_file);
    }
    writeLogState(paths.stateFile(p.log.name), s);
  }
}

}  // namespace storey::cli
