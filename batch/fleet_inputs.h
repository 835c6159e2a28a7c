#pragma once
/// The logs of a `storey batch`: from log files and folders named on the
/// command line, folders searched for logs, and manifests (YAML: per log its
/// path, optional name, calibration and config overrides; docs/batch.md).
/// Every log gets a unique name: its output folder in FLEET_OUT/logs/.
#include <optional>
#include <string>
#include <vector>

namespace storey::cli {

/// Slurm settings of a manifest's `slurm:` section (the command line wins).
struct SlurmSettings {
  std::string partition;                ///< sbatch --partition; empty = the cluster's default
  std::string account;                  ///< sbatch --account; empty = none
  std::optional<int> cpus_per_task;     ///< sbatch --cpus-per-task; unset = 1
  std::string mem;                      ///< sbatch --mem (e.g. "4G"); empty = estimated per batch
  std::string time;                     ///< sbatch --time (e.g. "2:00:00"); empty = estimated
  std::vector<std::string> extra_args;  ///< more sbatch arguments, passed as given
  std::string prolog;  ///< shell lines each task runs before storey (e.g. "module load ...")
};

struct FleetLog {
  std::string name;              ///< unique in the batch: [A-Za-z0-9._-], the output folder's name
  std::string path;              ///< absolute path of the log (file, or PCD folder)
  std::string calibration;       ///< absolute path of its calibration file; empty = none
  std::string config_overrides;  ///< YAML applied over the base config; empty = none
  std::string source;            ///< where it was named, for messages
};

struct FleetInputs {
  std::vector<FleetLog> logs;
  std::string config_path;  ///< a manifest's `config:` (absolute); empty = none
  SlurmSettings slurm;      ///< a manifest's `slurm:`
};

/// The logs named by `inputs` (in order; a folder's logs sorted by path).
/// `calibration` (--calibration) applies to every log without its own.
/// A file ending in .yaml/.yml whose top level has `logs:` is a manifest;
/// another file is a log; a folder holding PCD files is a log, another folder
/// is searched (recursively) for *.bag, *.pcap, *.pcapng files and PCD
/// folders. Throws storey::Error for a missing input, a bad manifest (file,
/// line, key), a folder without logs, a log given twice, two logs of one name.
FleetInputs collectFleetInputs(const std::vector<std::string>& inputs,
                               const std::string& calibration);

/// Unique names from paths: the file name without extension, with as many
/// parent folders in front ("a-b-simulation") as it takes to tell logs
/// apart; characters other than [A-Za-z0-9._-] become '_'. Names in
/// `given` (non-empty entries) are kept as they are.
std::vector<std::string> uniqueLogNames(const std::vector<std::string>& paths,
                                        const std::vector<std::string>& given = {});

}  // namespace storey::cli
