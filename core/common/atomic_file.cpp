#include "common/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/error.h"

namespace storey {

std::string temporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void commitTemporary(const std::string& temporary_path, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(temporary_path, path, ec);
  if (ec) {
    std::filesystem::remove(temporary_path, ec);
    throw Error(path + ": cannot move the finished file into place: " + ec.message());
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = temporaryPathFor(path);
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw Error(path + ": cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw Error(path + ": write failed (disk full?)");
    }
    commitTemporary(temporary, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw;
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  writeFileAtomically(path, [&](std::ostream& out) { out << content; });
}

namespace {

bool allDigits(const std::string& text, std::size_t from, std::size_t to) {
  if (from >= to) return false;
  for (std::size_t i = from; i < to; ++i)
    if (text[i] < '0' || text[i] > '9') return false;
  return true;
}

/// The writer's pid when `name` is a temporary of temporaryPath(): NAME.tmp-PID-N
/// (PID of 1-9 digits); 0 otherwise.
pid_t temporaryWriter(const std::string& name) {
  const std::size_t tag = name.rfind(".tmp-");
  if (tag == std::string::npos) return 0;
  const std::size_t pid_start = tag + 5;
  const std::size_t dash = name.find('-', pid_start);
  if (dash == std::string::npos || dash - pid_start > 9 || !allDigits(name, pid_start, dash) ||
      !allDigits(name, dash + 1, name.size()))
    return 0;
  return static_cast<pid_t>(std::stol(name.substr(pid_start, dash - pid_start)));
}

}  // namespace

std::size_t removeStaleTemporaries(const std::string& dir) {
  std::error_code ec;
  std::vector<std::filesystem::path> stale;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const pid_t pid = temporaryWriter(it->path().filename().string());
    if (pid <= 0) continue;
    // Its writer is gone when no process has its pid (a reused pid leaves it).
    if (pid != ::getpid() && ::kill(pid, 0) == -1 && errno == ESRCH) stale.push_back(it->path());
  }
  std::size_t removed = 0;
  for (const auto& path : stale) removed += std::filesystem::remove(path, ec) ? 1 : 0;
  return removed;
}

}  // namespace storey
