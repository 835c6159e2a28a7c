#pragma once
/// Runs the built `storey` binary (compile definition STOREY_BINARY) with
/// arguments and captures its exit status, stdout and stderr.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace storey::test {

struct RunResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

inline std::string shellQuoted(const std::string& s) { return "'" + s + "'"; }

/// `scratch_dir` receives the stderr capture file; `wrapper` (e.g. "timeout
/// -s INT 2 ") is put before the binary in the shell command.
inline RunResult runStorey(const std::string& args, const std::string& scratch_dir,
                           const std::string& wrapper = "") {
  const std::string err_file = scratch_dir + "/stderr.txt";
  const std::string command =
      wrapper + shellQuoted(STOREY_BINARY) + " " + args + " 2>" + shellQuoted(err_file);
  RunResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  result.err = os.str();
  return result;
}

}  // namespace storey::test
