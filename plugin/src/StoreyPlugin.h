#pragma once
/// qStorey: Storey SLAM inside CloudCompare (docs/plugin.md). Thin: actions
/// and dialogs here, conversions in Entities, the core call in StoreyRun.
#include <ccStdPluginInterface.h>

#include <QFutureWatcher>
#include <QObject>
#include <memory>

#include "StoreyRun.h"

class QAction;
class QProgressDialog;
class QTimer;

namespace storey::plugin {

struct RunJob;

class StoreyPlugin : public QObject, public ccStdPluginInterface {
  Q_OBJECT
  Q_INTERFACES(ccPluginInterface ccStdPluginInterface)
  Q_PLUGIN_METADATA(IID "org.storey.CloudCompare.qStorey" FILE "../resources/info.json")

 public:
  explicit StoreyPlugin(QObject* parent = nullptr);
  ~StoreyPlugin() override;

  QList<QAction*> getActions() override;
  void onNewSelection(const ccHObject::Container& selected) override;
  void registerCommands(ccCommandLineInterface* cmd) override;
  void setMainAppInterface(ccMainAppInterface* app) override;

 private:
  void runOnLog();          ///< "Run Storey SLAM on a log…"
  void colourBySrp();       ///< "Inspect SRPs: colour by SRP"
  void planesOfKeyframe();  ///< "Inspect SRPs: planes seen from a keyframe…"
  void exportStoreys();     ///< "Export storeys…"

  /// Runs on a worker thread with a progress dialog; results reach the DB tree in finishRun().
  void startRun(const RunRequest& request, const Config& config);
  void pollProgress();
  void finishRun();
  void autorun();  ///< test hook: STOREY_PLUGIN_AUTORUN=LOG (docs/plugin.md)
  void autorunFinish(const QString& summary, int exit_code);
  void error(const QString& message);
  ccHObject* selectedEntity() const;

  QAction* run_action_ = nullptr;
  QAction* colour_action_ = nullptr;
  QAction* keyframe_action_ = nullptr;
  QAction* export_action_ = nullptr;
  std::shared_ptr<RunJob> job_;
  QFutureWatcher<void>* watcher_ = nullptr;
  QProgressDialog* progress_ = nullptr;
  QTimer* poll_ = nullptr;
  bool autorun_ = false;
};

}  // namespace storey::plugin
