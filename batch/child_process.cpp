#include "child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/progress.h"

namespace storey::cli {
namespace {

std::vector<char*> argvOf(std::vector<std::string>& storage) {
  std::vector<char*> argv;
  for (std::string& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  return argv;
}

/// wait4 that retries on EINTR; fills exit code and peak memory.
void waitFor(pid_t pid, ChildResult& result) {
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) return;
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss in KiB
}

}  // namespace

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& args,
                           const std::string& log_path) {
  std::vector<std::string> storage{program};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv = argvOf(storage);
  // fork + exec rather than posix_spawn: the child asks to be sent SIGTERM
  // when the thread that started it dies, so stopping the parent (Ctrl-C,
  // kill) stops its children too. Only async-signal-safe calls before exec.
  const pid_t parent = getpid();
  const char* log = log_path.empty() ? "/dev/null" : log_path.c_str();
  const int flags = log_path.empty() ? O_WRONLY : O_WRONLY | O_CREAT | O_APPEND;
  start_ = ProgressMeter::steadySeconds();
  pid_ = fork();
  if (pid_ == 0) {
    if (prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || getppid() != parent) _exit(127);
    const int fd = open(log, flags, 0644);
    if (fd < 0 || dup2(fd, 1) < 0 || dup2(fd, 2) < 0) _exit(127);
    execv(argv[0], argv.data());
    _exit(127);
  }
}

ChildResult ChildProcess::wait() {
  ChildResult result;
  if (pid_ <= 0) return result;
  waitFor(pid_, result);
  result.wall_s = ProgressMeter::steadySeconds() - start_;
  pid_ = -1;
  return result;
}

ChildResult runSelf(const std::vector<std::string>& args, const std::string& log_path) {
  std::error_code ec;
  std::filesystem::remove(log_path, ec);  // one run's output per log file
  ChildProcess child("/proc/self/exe", args, log_path);
  return child.wait();
}

bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && access((dir + "/" + program).c_str(), X_OK) == 0) return true;
  return false;
}

ChildResult runCommand(const std::string& program, const std::vector<std::string>& args,
                       bool merge_stderr) {
  ChildResult result;
  std::vector<std::string> storage{program};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv = argvOf(storage);
  int fds[2];
  if (pipe(fds) != 0) return result;
  const pid_t parent = getpid();
  const double start = ProgressMeter::steadySeconds();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return result;
  }
  if (pid == 0) {
    if (prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || getppid() != parent) _exit(127);
    const int null = open("/dev/null", O_RDONLY);
    if (null < 0 || dup2(null, 0) < 0 || dup2(fds[1], 1) < 0) _exit(127);
    if (merge_stderr ? dup2(fds[1], 2) < 0 : dup2(open("/dev/null", O_WRONLY), 2) < 0) _exit(127);
    close(fds[0]);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  close(fds[1]);
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n > 0) {
      result.output.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(fds[0]);
  waitFor(pid, result);
  result.wall_s = ProgressMeter::steadySeconds() - start;
  return result;
}

std::string lastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last.empty() ? "no output" : last;
}

}  // namespace storey::cli
