#pragma once
/// The GUI test hook (docs/plugin.md "Test hook"): with STOREY_PLUGIN_AUTORUN
/// set, runs the run action on a log without dialogs, then optionally the
/// inspect and export steps, and writes a summary (with the console's lines
/// and the progress dialog's text), a screenshot and quits.
/// Every STOREY_PLUGIN_* environment variable is read in AutorunHarness.cpp
/// and nowhere else; nothing happens when they are unset.
#include <QObject>
#include <QString>

class ccMainAppInterface;

namespace storey::plugin {

class ActionRun;
struct RunCompletion;

class AutorunHarness : public QObject {
  Q_OBJECT
 public:
  /// The STOREY_PLUGIN_* variables.
  struct Settings {
    QString log;           ///< STOREY_PLUGIN_AUTORUN: the log to map
    QString config;        ///< STOREY_PLUGIN_AUTORUN_CONFIG
    QString out;           ///< STOREY_PLUGIN_AUTORUN_OUT
    bool inspect = false;  ///< STOREY_PLUGIN_AUTORUN_INSPECT=1: "colour by SRP"
    QString keyframe;      ///< STOREY_PLUGIN_AUTORUN_KEYFRAME: "planes seen from a keyframe"
    QString export_dir;    ///< STOREY_PLUGIN_AUTORUN_EXPORT: "Export storeys" (LAS + PLY)
    bool cancel = false;   ///< STOREY_PLUGIN_AUTORUN_CANCEL=1: Cancel after 20 %
    QString screenshot;    ///< STOREY_PLUGIN_SCREENSHOT: PNG of the whole screen
    QString done;          ///< STOREY_PLUGIN_AUTORUN_DONE: the summary file
    bool quit = false;     ///< STOREY_PLUGIN_AUTORUN_QUIT=1: quit when done
    int timeout = 600;     ///< STOREY_PLUGIN_AUTORUN_TIMEOUT: the watchdog, with quit [s]
  };

  /// Whether STOREY_PLUGIN_AUTORUN is set.
  static bool requested();
  /// Reads the variables and, 1.5 s later, starts `run` on the log.
  AutorunHarness(ccMainAppInterface* app, ActionRun* run, QObject* parent = nullptr);

 private:
  void begin();
  void runProgressed(double fraction);
  void runFinished(const RunCompletion& completion);
  void finish(const QString& summary, int exit_code);

  ccMainAppInterface* app_;
  ActionRun* run_;
  Settings settings_;
  bool cancel_pressed_ = false;
  QString progress_label_;  ///< the progress dialog's last text (with an estimate, if any)
};

}  // namespace storey::plugin
