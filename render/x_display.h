#pragma once
/// An X display for VTK's off-screen rendering. Debian's VTK 9.1 is built
/// for X only (no EGL, no OSMesa) and aborts the process when it cannot
/// reach an X server, so a display is checked before any VTK window exists:
/// the one in $DISPLAY when it accepts a connection, otherwise a private
/// Xvfb started here (display number chosen by Xvfb itself with -displayfd,
/// -noreset: an X server resets when its last client leaves and refuses
/// connections meanwhile, which VTK would not survive) and stopped when the
/// guard goes away.
#include <sys/types.h>
#include <string>

namespace storey::render {

/// True when $DISPLAY names an X server that accepts a connection.
bool displayUsable();

class XDisplayGuard {
 public:
  /// Uses $DISPLAY when usable, else starts `Xvfb :N -screen 0 WxHx24
  /// -nolisten tcp` and points $DISPLAY at it. Throws storey::Error when no
  /// display can be had (Xvfb missing or failing; the message says what to install).
  XDisplayGuard(int screen_width, int screen_height);
  ~XDisplayGuard();
  XDisplayGuard(const XDisplayGuard&) = delete;
  XDisplayGuard& operator=(const XDisplayGuard&) = delete;

  const std::string& display() const { return display_; }
  bool startedXvfb() const { return pid_ > 0; }

 private:
  std::string display_;
  pid_t pid_ = -1;
  void* connection_ = nullptr;  ///< our own X connection to the private server
  bool had_display_env_ = false;
  std::string old_display_;
};

}  // namespace storey::render
