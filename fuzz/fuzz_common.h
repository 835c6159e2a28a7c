#pragma once
/// Shared by every fuzz target (fuzz/targets/*.cpp, docs/testing.md).
///
/// A target feeds one input to the entry point the program uses. A
/// storey::Error is the expected answer to bad input; anything else (a crash,
/// a sanitizer report, another exception such as std::bad_alloc, a hang) is
/// a finding: other exceptions are left to escape, so libFuzzer reports them.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "common/error.h"
#include "common/log.h"

namespace storey::fuzz {

/// Writes the input to a file of this process named `name` (e.g. "input.bag")
/// in a folder of this process and returns its path; for readers that take a path.
inline std::string writeInputFile(const std::uint8_t* data, std::size_t size,
                                  const std::string& name) {
  static const std::string dir = [] {
    // $TMPDIR, else /dev/shm (memory: many thousand files a second), else /tmp.
    const char* tmp = std::getenv("TMPDIR");
    const bool shm = access("/dev/shm", W_OK) == 0;
    std::string d = std::string(tmp && *tmp ? tmp
                                : shm       ? "/dev/shm"
                                            : "/tmp") +
                    "/storey-fuzz-" + std::to_string(static_cast<long>(getpid()));
    std::filesystem::create_directories(d);
    static std::string to_remove;  // removed when the process exits normally
    to_remove = d;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(to_remove, ec);
    });
    return d;
  }();
  const std::string path = dir + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

/// Runs `f`; a storey::Error is an expected outcome.
template <class F>
void expectOnlyStoreyErrors(F&& f) {
  try {
    f();
  } catch (const storey::Error& e) {
    // The one-line message a user would see must say something.
    if (std::string(e.what()).empty()) std::abort();
  }
}

/// Quiet logging: warnings about bad input are expected and would flood the output.
inline void quietLogs() {
  static const bool once = [] {
    setLogSink([](LogLevel, const std::string&) {});
    return true;
  }();
  (void)once;
}

}  // namespace storey::fuzz
