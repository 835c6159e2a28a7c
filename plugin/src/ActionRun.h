#pragma once
/// "Run Storey SLAM on a log…": the log's file dialog, the parameters dialog
/// (RunDialog), the pipeline on a worker thread behind a progress dialog with
/// Cancel (stage, percent, elapsed, time left, speed), then the results into
/// the DB tree (toRunEntities) and the run's summary and warnings into the
/// console. Reports how each run ended through
/// finished().
#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <memory>
#include <vector>

#include "Entities.h"
#include "StoreyRun.h"

class QAction;
class QProgressDialog;
class QTimer;
class ccMainAppInterface;

namespace storey::plugin {

/// How a run ended (ActionRun::finished).
struct RunCompletion {
  enum class Status { kDone, kCancelled, kFailed };
  Status status = Status::kFailed;
  QString error;                              ///< kFailed: what went wrong
  RunEntities entities;                       ///< kDone: what was added to the DB tree
  std::shared_ptr<const RunOutcome> outcome;  ///< kDone: the pipeline's result
  std::vector<ConsoleLine> console;           ///< kDone: the lines shown in the console
};

struct RunJob;

class ActionRun : public QObject {
  Q_OBJECT
 public:
  /// `action` (the menu entry) is disabled while a run works.
  ActionRun(QAction* action, QObject* parent = nullptr);
  /// Cancels a run still working and waits for its thread.
  ~ActionRun() override;

  /// The menu action: asks for the log and the parameters, then start().
  void chooseAndRun(ccMainAppInterface* app);
  /// Runs the pipeline with `config` on a worker thread; one run at a time.
  void start(ccMainAppInterface* app, const RunRequest& request, const Config& config);
  /// The progress dialog of the run working now (null between runs).
  QProgressDialog* progressDialog() const { return progress_; }
  /// Errors go to the console as warnings instead of errors: CloudCompare
  /// shows errors in a modal box, which nobody closes in an unattended session.
  void setUnattended(bool unattended) { unattended_ = unattended; }

 signals:
  /// The progress dialog was updated with the run's fraction done [0, 1].
  void progressed(double fraction);
  /// The run ended; its entities (if any) are in the DB tree.
  void finished(const storey::plugin::RunCompletion& completion);

 private:
  void pollProgress();
  void finishRun();
  void reportError(const QString& message);

  QAction* action_;
  ccMainAppInterface* app_ = nullptr;  ///< of the run working now
  std::shared_ptr<RunJob> job_;
  QFutureWatcher<void>* watcher_ = nullptr;
  QProgressDialog* progress_ = nullptr;
  QTimer* poll_ = nullptr;
  bool unattended_ = false;
};

}  // namespace storey::plugin
