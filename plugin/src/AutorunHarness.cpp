#include "AutorunHarness.h"

#include <ccMainAppInterface.h>
#include <ccPointCloud.h>

#include <QCoreApplication>
#include <QFile>
#include <QGuiApplication>
#include <QMainWindow>
#include <QProgressDialog>
#include <QPushButton>
#include <QScreen>
#include <QTextStream>
#include <QTimer>

#include "ActionCommon.h"
#include "ActionRun.h"
#include "Entities.h"
#include "Inspect.h"
#include "RunDialog.h"
#include "common/error.h"
#include "export/storey_files.h"

namespace storey::plugin {

namespace {

QString env(const char* name) {
  return QString::fromLocal8Bit(qgetenv(name));
}

AutorunHarness::Settings settingsFromEnvironment() {
  AutorunHarness::Settings s;
  s.log = env("STOREY_PLUGIN_AUTORUN");
  s.config = env("STOREY_PLUGIN_AUTORUN_CONFIG");
  s.out = env("STOREY_PLUGIN_AUTORUN_OUT");
  s.inspect = env("STOREY_PLUGIN_AUTORUN_INSPECT") == "1";
  s.keyframe = env("STOREY_PLUGIN_AUTORUN_KEYFRAME");
  s.export_dir = env("STOREY_PLUGIN_AUTORUN_EXPORT");
  s.cancel = env("STOREY_PLUGIN_AUTORUN_CANCEL") == "1";
  s.screenshot = env("STOREY_PLUGIN_SCREENSHOT");
  s.done = env("STOREY_PLUGIN_AUTORUN_DONE");
  s.quit = env("STOREY_PLUGIN_AUTORUN_QUIT") == "1";
  const QString timeout = env("STOREY_PLUGIN_AUTORUN_TIMEOUT");
  if (!timeout.isEmpty()) s.timeout = timeout.toInt();
  return s;
}

void writeFile(const QString& path, const QString& text) {
  QFile file(path);
  if (file.open(QIODevice::WriteOnly | QIODevice::Text)) file.write(text.toUtf8());
}

}  // namespace

bool AutorunHarness::requested() {
  return !env("STOREY_PLUGIN_AUTORUN").isEmpty();
}

AutorunHarness::AutorunHarness(ccMainAppInterface* app, ActionRun* run, QObject* parent)
    : QObject(parent), app_(app), run_(run), settings_(settingsFromEnvironment()) {
  run_->setUnattended(true);
  connect(run_, &ActionRun::progressed, this, &AutorunHarness::runProgressed);
  connect(run_, &ActionRun::finished, this, &AutorunHarness::runFinished);
  QTimer::singleShot(1500, this, &AutorunHarness::begin);
}

void AutorunHarness::begin() {
  if (settings_.quit) {
    // Watchdog: a modal box nobody can close must not hang a test (timers
    // also fire inside a modal dialog's event loop).
    QTimer::singleShot(settings_.timeout * 1000, this, [this] {
      writeFile(settings_.done, "error: watchdog: the run did not finish\n");
      QCoreApplication::exit(2);
    });
  }
  // No window manager under Xvfb: fill the screen so the screenshot shows a usable view.
  if (QScreen* screen = QGuiApplication::primaryScreen())
    app_->getMainWindow()->setGeometry(screen->availableGeometry());
  // The run action's parameters dialog, filled in but not shown: its request
  // and config are what "Run" would start.
  RunDialog dialog(settings_.log, app_->getMainWindow());
  dialog.setConfigFile(settings_.config);
  dialog.setOutputFolder(settings_.out);
  Config config;
  try {
    if (!dialog.loadError().isEmpty()) throw Error(dialog.loadError().toStdString());
    config = dialog.config();
    config.validate();
  } catch (const std::exception& e) {
    consoleError(app_, e.what(), ccMainAppInterface::WRN_CONSOLE_MESSAGE);
    finish(QString("error: ") + e.what(), 1);
    return;
  }
  run_->start(app_, dialog.request(), config);
}

void AutorunHarness::runProgressed(double fraction) {
  QProgressDialog* progress = run_->progressDialog();
  if (progress == nullptr) return;
  // The dialog's text for the summary: the last one with a time-left
  // estimate, else the last one.
  const QString label = progress->labelText();
  if (!label.contains("? left") || progress_label_.isEmpty() || progress_label_.contains("? left"))
    progress_label_ = label;
  // The progress dialog's own Cancel button, part way through the log.
  if (!settings_.cancel || cancel_pressed_ || fraction <= 0.2) return;
  if (auto* button = progress->findChild<QPushButton*>()) {
    cancel_pressed_ = true;
    button->click();
  }
}

void AutorunHarness::runFinished(const RunCompletion& completion) {
  if (completion.status == RunCompletion::Status::kCancelled) return finish("cancelled", 1);
  if (completion.status == RunCompletion::Status::kFailed)
    return finish("error: " + completion.error, 1);

  const RunEntities& entities = completion.entities;
  QString summary;
  QTextStream out(&summary);
  out << "group " << entities.group->getName() << '\n';
  if (entities.map) out << "map " << entities.map->getName() << ' ' << entities.map->size() << '\n';
  for (ccPointCloud* c : entities.storeys)
    out << "storey " << c->getName() << ' ' << c->size() << '\n';
  out << "trajectory " << completion.outcome->result.trajectory.size() << '\n';
  out << "planes " << (entities.planes ? entities.planes->getChildrenNumber() : 0) << '\n';
  // What the console and the progress dialog showed.
  for (const ConsoleLine& line : completion.console)
    out << (line.warning ? "console_warning " : "console ") << QString::fromStdString(line.text)
        << '\n';
  if (!progress_label_.isEmpty())
    out << "progress " << QString(progress_label_).replace('\n', " | ") << '\n';
  // Optional steps: the inspect and export actions' functions.
  int exit_code = 0;
  try {
    if (settings_.inspect && entities.map && entities.planes) {
      out << "srp_points " << colourBySrp(*entities.map) << '\n';
      entities.map->prepareDisplayForRefresh();
      app_->refreshAll();
    }
    if (!settings_.keyframe.isEmpty() && entities.planes) {
      const QStringList seen = showPlanesOfKeyframe(*entities.group, settings_.keyframe.toInt());
      unsigned visible = 0;
      for (unsigned i = 0; i < entities.planes->getChildrenNumber(); ++i)
        visible += entities.planes->getChild(i)->isVisible() ? 1 : 0;
      out << "keyframe_planes " << seen.size() << ' ' << visible << '\n';
      for (const QString& line : seen) app_->dispToConsole("[Storey]   " + line);
      showPlanesOfKeyframe(*entities.group, -1);  // back to every SRP for the screenshot
    }
    if (!settings_.export_dir.isEmpty() && entities.map) {
      StoreyFileFormats formats;
      formats.ply = true;
      out << "exported "
          << writeStoreyFiles(fromCloud(*entities.map), settings_.export_dir.toStdString(), formats)
                 .size()
          << '\n';
    }
  } catch (const std::exception& e) {
    out << "error: " << e.what() << '\n';
    exit_code = 1;
  }
  out.flush();
  finish(summary, exit_code);
}

void AutorunHarness::finish(const QString& summary, int exit_code) {
  // Let the 3D view draw the new entities, then take the screenshot (the
  // whole X screen: what a user would see), write the summary and quit when asked.
  QTimer::singleShot(2500, this, [this, summary, exit_code] {
    if (!settings_.screenshot.isEmpty()) {
      if (QScreen* screen = QGuiApplication::primaryScreen())
        screen->grabWindow(0).save(settings_.screenshot, "PNG");
    }
    if (!settings_.done.isEmpty()) writeFile(settings_.done, summary);
    if (settings_.quit) QCoreApplication::exit(exit_code);
  });
}

}  // namespace storey::plugin
