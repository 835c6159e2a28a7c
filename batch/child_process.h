#pragma once
/// Child processes of the `storey` program: `storey bench` and `storey batch`
/// run this program again (a step, a log) and the Slurm executor runs
/// sbatch/squeue/scontrol. A child started here is sent SIGTERM when the
/// thread that started it dies, so stopping the parent stops its children.
#include <sys/types.h>

#include <string>
#include <vector>

namespace storey::cli {

struct ChildResult {
  int exit_code = -1;    ///< exit status; 128 + signal when killed; -1 when it could not start
  double peak_mb = 0.0;  ///< peak resident memory of the child [MB]
  double wall_s = 0.0;   ///< wall time from start to exit [s]
  std::string output;    ///< stdout (runCommand only)
};

/// A started child: `program` with `args`, stdout and stderr appended to
/// `log_path` (or /dev/null when empty). The pid is known at once so that
/// another thread can signal it while wait() blocks.
class ChildProcess {
 public:
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               const std::string& log_path);
  pid_t pid() const { return pid_; }
  /// Blocks until the child exits (retrying on EINTR).
  ChildResult wait();

 private:
  pid_t pid_ = -1;
  double start_ = 0.0;
};

/// This program (/proc/self/exe) with `args`, output into `log_path`; blocks.
ChildResult runSelf(const std::vector<std::string>& args, const std::string& log_path);

/// Runs `program` (searched on PATH) with `args` and returns its stdout in
/// `output`; its stderr is appended to `output` too when `merge_stderr`.
ChildResult runCommand(const std::string& program, const std::vector<std::string>& args,
                       bool merge_stderr = true);

/// Whether `program` is an executable file on PATH.
bool onPath(const std::string& program);

/// The last non-empty line of a text file ("no output" when there is none):
/// the one-line error of a failed `storey` child.
std::string lastLine(const std::string& path);

}  // namespace storey::cli
