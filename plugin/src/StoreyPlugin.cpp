#include "StoreyPlugin.h"

#include <ccCommandLineInterface.h>
#include <ccPointCloud.h>

#include <QAction>
#include <QApplication>
#include <QFile>
#include <QFileDialog>
#include <QFuture>
#include <QFutureWatcher>
#include <QIcon>
#include <QInputDialog>
#include <QPushButton>
#include <QMainWindow>
#include <QProgressDialog>
#include <QScreen>
#include <QTextStream>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <atomic>
#include <mutex>

#include "Entities.h"
#include "Inspect.h"
#include "RunDialog.h"
#include "StoreyCommand.h"
#include "StoreyRun.h"
#include "common/error.h"
#include "export/storey_files.h"

namespace storey::plugin {

/// State shared between the GUI thread and the worker running the pipeline.
struct RunJob {
  RunRequest request;
  Config config;
  std::atomic<bool> cancel{false};
  std::mutex mutex;  ///< guards fraction and stage
  double fraction = 0.0;
  std::string stage = "starting";
  // Set by the worker before it returns.
  bool ok = false;
  bool cancelled = false;
  std::string error;
  RunOutcome outcome;
};

namespace {

QString env(const char* name) { return QString::fromLocal8Bit(qgetenv(name)); }

}  // namespace

StoreyPlugin::StoreyPlugin(QObject* parent)
    : QObject(parent), ccStdPluginInterface(":/CC/plugin/qStorey/info.json") {}

StoreyPlugin::~StoreyPlugin() {
  if (job_ && watcher_ != nullptr) {  // CloudCompare is closing during a run: stop it and wait
    job_->cancel = true;
    watcher_->waitForFinished();
  }
}

QList<QAction*> StoreyPlugin::getActions() {
  if (run_action_ == nullptr) {
    run_action_ = new QAction("Run Storey SLAM on a log…", this);
    run_action_->setToolTip("Map a LiDAR + IMU log with Storey; the map, storeys, trajectory and SRPs come into the DB tree");
    run_action_->setIcon(getIcon());
    connect(run_action_, &QAction::triggered, this, &StoreyPlugin::runOnLog);

    colour_action_ = new QAction("Inspect SRPs: colour by SRP", this);
    colour_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/srp.png"));
    colour_action_->setToolTip("Colour the selected Storey cloud by the global SRP each point lies on (scalar field 'srp')");
    connect(colour_action_, &QAction::triggered, this, &StoreyPlugin::colourBySrp);

    keyframe_action_ = new QAction("Inspect SRPs: planes seen from a keyframe…", this);
    keyframe_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/keyframe.png"));
    keyframe_action_->setToolTip("Show only the SRP planes observed from a chosen keyframe of the selected Storey run");
    connect(keyframe_action_, &QAction::triggered, this, &StoreyPlugin::planesOfKeyframe);

    export_action_ = new QAction("Export storeys…", this);
    export_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/export.png"));
    export_action_->setToolTip("Write LAS/PLY per storey of the selected Storey cloud with Storey's exporters");
    connect(export_action_, &QAction::triggered, this, &StoreyPlugin::exportStoreys);
    onNewSelection({});
  }
  return {run_action_, colour_action_, keyframe_action_, export_action_};
}

void StoreyPlugin::onNewSelection(const ccHObject::Container& selected) {
  if (run_action_ == nullptr) return;
  bool in_run = false, storey_cloud = false;
  for (ccHObject* e : selected) {
    in_run = in_run || findRunGroup(e) != nullptr;
    storey_cloud = storey_cloud || findStoreyCloud(e) != nullptr;
  }
  colour_action_->setEnabled(storey_cloud && in_run);
  keyframe_action_->setEnabled(in_run);
  export_action_->setEnabled(storey_cloud);
}

void StoreyPlugin::registerCommands(ccCommandLineInterface* cmd) {
  cmd->registerCommand(ccCommandLineInterface::Command::Shared(new StoreyCommand));
}

void StoreyPlugin::setMainAppInterface(ccMainAppInterface* app) {
  ccStdPluginInterface::setMainAppInterface(app);
  if (app != nullptr && !env("STOREY_PLUGIN_AUTORUN").isEmpty() && !autorun_) {
    autorun_ = true;
    QTimer::singleShot(1500, this, &StoreyPlugin::autorun);
  }
}

ccHObject* StoreyPlugin::selectedEntity() const {
  if (m_app == nullptr || m_app->getSelectedEntities().empty()) return nullptr;
  return m_app->getSelectedEntities().front();
}

void StoreyPlugin::error(const QString& message) {
  if (m_app == nullptr) return;
  // CloudCompare shows errors in a modal message box too; the test hook
  // (no one to close it) logs them as warnings.
  m_app->dispToConsole("[Storey] " + message, autorun_ ? ccMainAppInterface::WRN_CONSOLE_MESSAGE
                                                      : ccMainAppInterface::ERR_CONSOLE_MESSAGE);
}

// ---- Run -------------------------------------------------------------------

void StoreyPlugin::runOnLog() {
  if (m_app == nullptr || job_) return;
  QWidget* parent = m_app->getMainWindow();
  const QString log = QFileDialog::getOpenFileName(
      parent, "Storey: LiDAR + IMU log", QString(),
      "Logs (*.bag *.pcap *.pcapng);;All files (*)");
  if (log.isEmpty()) return;
  RunDialog dialog(log, parent);
  if (dialog.exec() != QDialog::Accepted) return;
  startRun(dialog.request(), dialog.config());
}

void StoreyPlugin::startRun(const RunRequest& request, const Config& config) {
  job_ = std::make_shared<RunJob>();
  job_->request = request;
  job_->config = config;
  run_action_->setEnabled(false);

  progress_ = new QProgressDialog("Storey SLAM: starting…", "Cancel", 0, 1000, m_app->getMainWindow());
  progress_->setWindowTitle("Storey SLAM");
  progress_->setWindowModality(Qt::WindowModal);
  progress_->setAutoClose(false);
  progress_->setAutoReset(false);
  progress_->setMinimumDuration(0);
  progress_->setMinimumWidth(420);
  connect(progress_, &QProgressDialog::canceled, this, [this] {
    if (!job_) return;
    job_->cancel = true;
    progress_->setLabelText("Storey SLAM: cancelling…");
  });
  progress_->show();
  poll_ = new QTimer(this);
  connect(poll_, &QTimer::timeout, this, &StoreyPlugin::pollProgress);
  poll_->start(100);

  m_app->dispToConsole(QString("[Storey] mapping %1").arg(QString::fromStdString(request.log_path)));
  std::shared_ptr<RunJob> job = job_;
  watcher_ = new QFutureWatcher<void>(this);
  connect(watcher_, &QFutureWatcher<void>::finished, this, &StoreyPlugin::finishRun);
  watcher_->setFuture(QtConcurrent::run([job] {
    try {
      job->outcome = runStorey(job->request, job->config, [job](double fraction, const std::string& stage) {
        {
          std::lock_guard<std::mutex> lock(job->mutex);
          job->fraction = fraction;
          job->stage = stage;
        }
        return !job->cancel.load();
      });
      job->ok = true;
    } catch (const Cancelled&) {
      job->cancelled = true;
    } catch (const std::exception& e) {
      job->error = e.what();
    }
  }));
}

void StoreyPlugin::pollProgress() {
  if (!job_ || progress_ == nullptr || job_->cancel) return;
  double fraction;
  std::string stage;
  {
    std::lock_guard<std::mutex> lock(job_->mutex);
    fraction = job_->fraction;
    stage = job_->stage;
  }
  progress_->setLabelText(QString("Storey SLAM: %1").arg(QString::fromStdString(stage)));
  progress_->setValue(static_cast<int>(fraction * 1000.0));
  // Test hook: press the dialog's Cancel button part way through the log.
  if (autorun_ && env("STOREY_PLUGIN_AUTORUN_CANCEL") == "1" && fraction > 0.2) {
    if (auto* button = progress_->findChild<QPushButton*>()) button->click();
  }
}

void StoreyPlugin::finishRun() {
  std::shared_ptr<RunJob> job = std::move(job_);
  watcher_->deleteLater();
  watcher_ = nullptr;
  poll_->stop();
  poll_->deleteLater();
  poll_ = nullptr;
  progress_->close();
  progress_->deleteLater();
  progress_ = nullptr;
  run_action_->setEnabled(true);

  if (job->cancelled) {
    m_app->dispToConsole("[Storey] run cancelled; nothing was written",
                         ccMainAppInterface::WRN_CONSOLE_MESSAGE);
    if (autorun_) autorunFinish("cancelled", 1);
    return;
  }
  if (!job->ok) {
    error(QString::fromStdString(job->error));  // CloudCompare shows it in a message box too
    if (autorun_) autorunFinish("error: " + QString::fromStdString(job->error), 1);
    return;
  }

  RunEntities entities;
  try {
    entities = toRunEntities(job->outcome);
  } catch (const std::exception& e) {
    error(e.what());
    if (autorun_) autorunFinish(QString("error: ") + e.what(), 1);
    return;
  }
  m_app->addToDB(entities.group, true);
  const RunOutcome& o = job->outcome;
  m_app->dispToConsole(QString("[Storey] done in %1 s: %2 scans, %3 keyframes, %4 map points, %5 "
                               "storeys, %6; files in %7")
                           .arg(o.seconds, 0, 'f', 1)
                           .arg(o.result.trajectory.size())
                           .arg(o.result.keyframes.size())
                           .arg(o.result.map ? o.result.map->size() : 0)
                           .arg(o.result.storeys.size())
                           .arg(entities.planes ? QString("%1 SRPs").arg(entities.planes->getChildrenNumber())
                                                : QString("no SRPs"))
                           .arg(QString::fromStdString(o.out_dir)));
  for (const QString& line : reportText(o).split('\n', Qt::SkipEmptyParts))
    m_app->dispToConsole("[Storey] " + line);
  m_app->forceConsoleDisplay();
  m_app->setView(CC_ISO_VIEW_1);
  m_app->setGlobalZoom();
  m_app->refreshAll();

  if (autorun_) {
    QString summary;
    QTextStream out(&summary);
    out << "group " << entities.group->getName() << '\n';
    if (entities.map)
      out << "map " << entities.map->getName() << ' ' << entities.map->size() << '\n';
    for (ccPointCloud* c : entities.storeys) out << "storey " << c->getName() << ' ' << c->size() << '\n';
    out << "trajectory " << o.result.trajectory.size() << '\n';
    out << "planes " << (entities.planes ? entities.planes->getChildrenNumber() : 0) << '\n';
    // Optional steps of the hook: the inspect and export actions' functions.
    int exit_code = 0;
    try {
      if (env("STOREY_PLUGIN_AUTORUN_INSPECT") == "1" && entities.map && entities.planes) {
        out << "srp_points " << storey::plugin::colourBySrp(*entities.map) << '\n';
        entities.map->prepareDisplayForRefresh();
        m_app->refreshAll();
      }
      const QString keyframe = env("STOREY_PLUGIN_AUTORUN_KEYFRAME");
      if (!keyframe.isEmpty() && entities.planes) {
        const QStringList seen = showPlanesOfKeyframe(*entities.group, keyframe.toInt());
        unsigned visible = 0;
        for (unsigned i = 0; i < entities.planes->getChildrenNumber(); ++i)
          visible += entities.planes->getChild(i)->isVisible() ? 1 : 0;
        out << "keyframe_planes " << seen.size() << ' ' << visible << '\n';
        for (const QString& line : seen) m_app->dispToConsole("[Storey]   " + line);
        showPlanesOfKeyframe(*entities.group, -1);  // back to every SRP for the screenshot
      }
      const QString export_dir = env("STOREY_PLUGIN_AUTORUN_EXPORT");
      if (!export_dir.isEmpty() && entities.map) {
        StoreyFileFormats formats;
        formats.ply = true;
        out << "exported " << writeStoreyFiles(fromCloud(*entities.map), export_dir.toStdString(), formats).size() << '\n';
      }
    } catch (const std::exception& e) {
      out << "error: " << e.what() << '\n';
      exit_code = 1;
    }
    autorunFinish(summary, exit_code);
  }
}

// ---- Test hook ---------------------------------------------------------------

void StoreyPlugin::autorun() {
  if (m_app == nullptr) return;
  if (env("STOREY_PLUGIN_AUTORUN_QUIT") == "1") {
    // Watchdog: a modal box nobody can close must not hang a test (timers
    // also fire inside a modal dialog's event loop).
    const int seconds = env("STOREY_PLUGIN_AUTORUN_TIMEOUT").isEmpty() ? 600 : env("STOREY_PLUGIN_AUTORUN_TIMEOUT").toInt();
    QTimer::singleShot(seconds * 1000, this, [] {
      QFile file(env("STOREY_PLUGIN_AUTORUN_DONE"));
      if (file.open(QIODevice::WriteOnly | QIODevice::Text)) file.write("error: watchdog: the run did not finish\n");
      QCoreApplication::exit(2);
    });
  }
  getActions();  // the actions exist before a run
  // No window manager under Xvfb: fill the screen so the screenshot shows a usable view.
  if (QScreen* screen = QGuiApplication::primaryScreen()) m_app->getMainWindow()->setGeometry(screen->availableGeometry());
  // The run action's parameters dialog, filled in but not shown: its request
  // and config are what "Run" would start.
  RunDialog dialog(env("STOREY_PLUGIN_AUTORUN"), m_app->getMainWindow());
  dialog.setConfigFile(env("STOREY_PLUGIN_AUTORUN_CONFIG"));
  dialog.setOutputFolder(env("STOREY_PLUGIN_AUTORUN_OUT"));
  Config config;
  try {
    if (!dialog.loadError().isEmpty()) throw Error(dialog.loadError().toStdString());
    config = dialog.config();
    config.validate();
  } catch (const std::exception& e) {
    error(e.what());
    autorunFinish(QString("error: ") + e.what(), 1);
    return;
  }
  startRun(dialog.request(), config);
}

void StoreyPlugin::autorunFinish(const QString& summary, int exit_code) {
  // Let the 3D view draw the new entities, then take the screenshot (the
  // whole X screen: what a user would see), write the summary and quit when asked.
  QTimer::singleShot(2500, this, [this, summary, exit_code] {
    const QString shot = env("STOREY_PLUGIN_SCREENSHOT");
    if (!shot.isEmpty()) {
      if (QScreen* screen = QGuiApplication::primaryScreen()) screen->grabWindow(0).save(shot, "PNG");
    }
    const QString done = env("STOREY_PLUGIN_AUTORUN_DONE");
    if (!done.isEmpty()) {
      QFile file(done);
      if (file.open(QIODevice::WriteOnly | QIODevice::Text)) file.write(summary.toUtf8());
    }
    if (env("STOREY_PLUGIN_AUTORUN_QUIT") == "1") QCoreApplication::exit(exit_code);
  });
}

// ---- Inspect and export ------------------------------------------------------

void StoreyPlugin::colourBySrp() {
  ccPointCloud* cloud = findStoreyCloud(selectedEntity());
  if (cloud == nullptr) return error("select a Storey cloud");
  try {
    QApplication::setOverrideCursor(Qt::WaitCursor);
    const std::size_t labelled = storey::plugin::colourBySrp(*cloud);
    QApplication::restoreOverrideCursor();
    m_app->dispToConsole(QString("[Storey] %1 of %2 points of '%3' lie on an SRP (scalar field 'srp')")
                             .arg(labelled)
                             .arg(cloud->size())
                             .arg(cloud->getName()));
    cloud->prepareDisplayForRefresh();
    m_app->refreshAll();
    m_app->updateUI();
  } catch (const std::exception& e) {
    QApplication::restoreOverrideCursor();
    error(e.what());
  }
}

void StoreyPlugin::planesOfKeyframe() {
  ccHObject* group = findRunGroup(selectedEntity());
  if (group == nullptr) return error("select an entity of a Storey run");
  const int count = keyframeCount(*group);
  bool ok = false;
  const int keyframe = QInputDialog::getInt(m_app->getMainWindow(), "Storey: planes seen from a keyframe",
                                            QString("Keyframe (0 to %1; -1 shows every SRP):").arg(count - 1),
                                            0, -1, std::max(0, count - 1), 1, &ok);
  if (!ok) return;
  try {
    const QStringList lines = showPlanesOfKeyframe(*group, keyframe);
    m_app->dispToConsole(keyframe < 0 ? QString("[Storey] showing every SRP")
                                      : QString("[Storey] keyframe %1 observed %2 SRP(s):")
                                            .arg(keyframe)
                                            .arg(lines.size()));
    for (const QString& line : lines) m_app->dispToConsole("[Storey]   " + line);
    m_app->refreshAll();
  } catch (const std::exception& e) {
    error(e.what());
  }
}

void StoreyPlugin::exportStoreys() {
  ccPointCloud* cloud = findStoreyCloud(selectedEntity());
  if (cloud == nullptr) return error("select a Storey cloud");
  QWidget* parent = m_app->getMainWindow();
  const QString dir = QFileDialog::getExistingDirectory(parent, "Storey: export storeys into");
  if (dir.isEmpty()) return;
  bool ok = false;
  const QString format = QInputDialog::getItem(parent, "Storey: export storeys", "Format:",
                                               {"LAS 1.4", "PLY", "LAS 1.4 and PLY"}, 0, false, &ok);
  if (!ok) return;
  StoreyFileFormats formats;
  formats.las = format.startsWith("LAS");
  formats.ply = format.contains("PLY");
  try {
    QApplication::setOverrideCursor(Qt::WaitCursor);
    const MapCloud map = fromCloud(*cloud);
    const std::vector<std::string> files = writeStoreyFiles(map, dir.toStdString(), formats);
    QApplication::restoreOverrideCursor();
    for (const std::string& f : files) m_app->dispToConsole("[Storey] wrote " + QString::fromStdString(f));
  } catch (const std::exception& e) {
    QApplication::restoreOverrideCursor();
    error(e.what());
  }
}

}  // namespace storey::plugin
