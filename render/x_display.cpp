#include "render/x_display.h"

#include <X11/Xlib.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/log.h"

namespace storey::render {
namespace {

bool canOpen(const char* name) {
  if (name == nullptr || *name == '\0') return false;
  Display* display = XOpenDisplay(name);
  if (display == nullptr) return false;
  XCloseDisplay(display);
  return true;
}

std::string findInPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::stringstream ss(dirs);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

std::string readSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  std::string s = os.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  if (s.size() > 400) s = "..." + s.substr(s.size() - 400);
  return s;
}

void stopProcess(pid_t pid) {
  if (pid <= 0) return;
  ::kill(pid, SIGTERM);
  for (int i = 0; i < 200; ++i) {  // up to 2 s, then SIGKILL
    int status = 0;
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) return;
    ::usleep(10000);
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

}  // namespace

bool displayUsable() {
  return canOpen(std::getenv("DISPLAY"));
}

XDisplayGuard::XDisplayGuard(int screen_width, int screen_height) {
  const char* current = std::getenv("DISPLAY");
  had_display_env_ = current != nullptr;
  if (current) old_display_ = current;
  if (current != nullptr && *current != '\0') {
    connection_ = XOpenDisplay(current);  // held open: the server cannot reset under VTK
    if (connection_ != nullptr) {
      display_ = current;
      return;
    }
  }
  const std::string xvfb = findInPath("Xvfb");
  if (xvfb.empty()) {
    throw Error(std::string("off-screen rendering needs an X server: ") +
                (current && *current
                     ? "DISPLAY=" + std::string(current) + " does not accept a connection"
                     : "DISPLAY is not set") +
                " and Xvfb is not installed (Debian: apt-get install xvfb xauth, or run "
                "scripts/setup.sh)");
  }
  int fds[2];
  if (::pipe(fds) != 0)
    throw Error("cannot start Xvfb: pipe() failed: " + std::string(std::strerror(errno)));
  const std::string log_path = (std::filesystem::temp_directory_path() /
                                ("storey-xvfb-" + std::to_string(::getpid()) + ".log"))
                                   .string();
  const std::string screen = std::to_string(std::max(screen_width, 640)) + "x" +
                             std::to_string(std::max(screen_height, 480)) + "x24";
  const std::string fd_text = std::to_string(fds[1]);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot start Xvfb: fork() failed: " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    // Child: Xvfb dies with us; its output goes to a log kept for errors.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    ::close(fds[0]);
    const int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) ::dup2(devnull, 0);
    const int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (log >= 0) {
      ::dup2(log, 1);
      ::dup2(log, 2);
    }
    ::execl(xvfb.c_str(), "Xvfb", "-displayfd", fd_text.c_str(), "-screen", "0", screen.c_str(),
            "-nolisten", "tcp", "-noreset", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(fds[1]);
  pid_ = pid;
  // Xvfb writes the display number it chose, then a newline, once it accepts connections.
  std::string number;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool done = false;
  while (!done && std::chrono::steady_clock::now() < deadline) {
    pollfd p{fds[0], POLLIN, 0};
    const int r = ::poll(&p, 1, 200);
    if (r < 0 && errno == EINTR) continue;
    if (r > 0) {
      char c;
      const ssize_t n = ::read(fds[0], &c, 1);
      if (n <= 0) break;  // Xvfb exited
      if (c == '\n')
        done = true;
      else
        number.push_back(c);
    }
  }
  ::close(fds[0]);
  if (!done || number.empty()) {
    stopProcess(pid_);
    pid_ = -1;
    const std::string log = readSmallFile(log_path);
    std::remove(log_path.c_str());
    throw Error("off-screen rendering: no X display and the private Xvfb (" + xvfb +
                ") did not start" + (log.empty() ? std::string() : ": " + log));
  }
  std::remove(log_path.c_str());
  display_ = ":" + number;
  ::setenv("DISPLAY", display_.c_str(), 1);
  // Held open until the guard goes: the server never sees its last client
  // leave (with -noreset it would not reset anyway).
  connection_ = XOpenDisplay(display_.c_str());
  if (connection_ == nullptr) {
    stopProcess(pid_);
    pid_ = -1;
    if (had_display_env_)
      ::setenv("DISPLAY", old_display_.c_str(), 1);
    else
      ::unsetenv("DISPLAY");
    throw Error("off-screen rendering: the private Xvfb on " + display_ +
                " does not accept a connection");
  }
  logDebug("render: started Xvfb on " + display_);
}

XDisplayGuard::~XDisplayGuard() {
  if (connection_) XCloseDisplay(static_cast<Display*>(connection_));
  if (pid_ <= 0) return;
  stopProcess(pid_);
  if (had_display_env_)
    ::setenv("DISPLAY", old_display_.c_str(), 1);
  else
    ::unsetenv("DISPLAY");
}

}  // namespace storey::render
