#include "ActionRun.h"

#include <ccMainAppInterface.h>
#include <ccPointCloud.h>

#include <QAction>
#include <QFileDialog>
#include <QFuture>
#include <QMainWindow>
#include <QProgressDialog>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <atomic>
#include <mutex>

#include "ActionCommon.h"
#include "RunDialog.h"
#include "common/error.h"
#include "common/progress.h"
#include "io/log_format.h"

namespace storey::plugin {

/// State shared between the GUI thread and the worker running the pipeline.
struct RunJob {
  RunRequest request;
  Config config;
  std::atomic<bool> cancel{false};
  std::mutex mutex;     ///< guards meter
  ProgressMeter meter;  ///< stage, fraction, elapsed, time left, speed
  // Set by the worker before it returns.
  bool ok = false;
  bool cancelled = false;
  std::string error;
  RunOutcome outcome;
};

ActionRun::ActionRun(QAction* action, QObject* parent) : QObject(parent), action_(action) {}

ActionRun::~ActionRun() {
  if (job_ && watcher_ != nullptr) {  // CloudCompare is closing during a run: stop it and wait
    job_->cancel = true;
    watcher_->waitForFinished();
  }
}

void ActionRun::chooseAndRun(ccMainAppInterface* app) {
  if (app == nullptr || job_) return;
  QWidget* parent = app->getMainWindow();
  // A rosbag2 folder is chosen by its metadata.yaml, a PCD folder by one of its scans.
  const QString chosen = QFileDialog::getOpenFileName(parent, "Storey: LiDAR + IMU log", QString(),
                                                      kLogFileDialogFilter);
  if (chosen.isEmpty()) return;
  const QString log = QString::fromStdString(logPathForChosenFile(chosen.toStdString()));
  RunDialog dialog(log, parent);
  if (dialog.exec() != QDialog::Accepted) return;
  start(app, dialog.request(), dialog.config());
}

void ActionRun::start(ccMainAppInterface* app, const RunRequest& request, const Config& config) {
  if (app == nullptr || job_) return;
  app_ = app;
  job_ = std::make_shared<RunJob>();
  job_->request = request;
  job_->config = config;
  action_->setEnabled(false);

  progress_ =
      new QProgressDialog("Storey SLAM: starting…", "Cancel", 0, 1000, app_->getMainWindow());
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
  connect(poll_, &QTimer::timeout, this, &ActionRun::pollProgress);
  poll_->start(100);

  app_->dispToConsole(QString("[Storey] mapping %1").arg(QString::fromStdString(request.log_path)));
  std::shared_ptr<RunJob> job = job_;
  watcher_ = new QFutureWatcher<void>(this);
  connect(watcher_, &QFutureWatcher<void>::finished, this, &ActionRun::finishRun);
  watcher_->setFuture(QtConcurrent::run([job] {
    try {
      job->outcome = runStorey(
          job->request, job->config,
          [job](double fraction, const std::string& stage) {
            {
              std::lock_guard<std::mutex> lock(job->mutex);
              job->meter.update(fraction, stage);
            }
            return !job->cancel.load();
          },
          [job](double log_seconds) {
            std::lock_guard<std::mutex> lock(job->mutex);
            job->meter.setLogTime(log_seconds);
          });
      job->ok = true;
    } catch (const Cancelled&) {
      job->cancelled = true;
    } catch (const std::exception& e) {
      job->error = e.what();
    }
  }));
}

void ActionRun::pollProgress() {
  if (!job_ || progress_ == nullptr || job_->cancel) return;
  ProgressReading r;
  {
    std::lock_guard<std::mutex> lock(job_->mutex);
    r = job_->meter.reading();
  }
  if (r.stage.empty()) return;  // nothing reported yet: "starting…" stays
  progress_->setLabelText(QString("Storey SLAM: %1, %2 %\n%3")
                              .arg(QString::fromStdString(r.stage))
                              .arg(static_cast<int>(r.fraction * 100.0))
                              .arg(QString::fromStdString(timingText(r))));
  progress_->setValue(static_cast<int>(r.fraction * 1000.0));
  emit progressed(r.fraction);
}

void ActionRun::reportError(const QString& message) {
  consoleError(app_, message,
               unattended_ ? ccMainAppInterface::WRN_CONSOLE_MESSAGE
                           : ccMainAppInterface::ERR_CONSOLE_MESSAGE);
}

void ActionRun::finishRun() {
  std::shared_ptr<RunJob> job = std::move(job_);
  watcher_->deleteLater();
  watcher_ = nullptr;
  poll_->stop();
  poll_->deleteLater();
  poll_ = nullptr;
  progress_->close();
  progress_->deleteLater();
  progress_ = nullptr;
  action_->setEnabled(true);

  RunCompletion completion;
  if (job->cancelled) {
    app_->dispToConsole("[Storey] run cancelled; nothing was written",
                        ccMainAppInterface::WRN_CONSOLE_MESSAGE);
    completion.status = RunCompletion::Status::kCancelled;
    emit finished(completion);
    return;
  }
  if (!job->ok) {
    completion.error = QString::fromStdString(job->error);
    reportError(completion.error);  // CloudCompare shows it in a message box too
    emit finished(completion);
    return;
  }

  try {
    completion.entities = toRunEntities(job->outcome);
  } catch (const std::exception& e) {
    completion.error = e.what();
    reportError(completion.error);
    emit finished(completion);
    return;
  }
  const RunEntities& entities = completion.entities;
  app_->addToDB(entities.group, true);
  const std::string srps = entities.planes
                               ? std::to_string(entities.planes->getChildrenNumber()) + " SRPs"
                               : std::string("no SRPs");
  completion.console = runConsoleLines(job->outcome, "results in the DB tree, " + srps);
  for (const ConsoleLine& line : completion.console)
    app_->dispToConsole(QString::fromStdString(line.text),
                        line.warning ? ccMainAppInterface::WRN_CONSOLE_MESSAGE
                                     : ccMainAppInterface::STD_CONSOLE_MESSAGE);
  app_->forceConsoleDisplay();
  app_->setView(CC_ISO_VIEW_1);
  app_->setGlobalZoom();
  app_->refreshAll();

  completion.status = RunCompletion::Status::kDone;
  completion.outcome = std::shared_ptr<const RunOutcome>(job, &job->outcome);
  emit finished(completion);
}

}  // namespace storey::plugin
