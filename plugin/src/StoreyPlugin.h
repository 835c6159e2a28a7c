#pragma once
/// qStorey: Storey SLAM inside CloudCompare (docs/plugin.md). Thin: this
/// class only wires the menu actions to their files (ActionRun,
/// ActionInspect, ActionExport), the command-line command (StoreyCommand)
/// and the GUI test hook (AutorunHarness); conversions are in Entities, the
/// core call in StoreyRun.
#include <ccStdPluginInterface.h>

#include <QObject>

class QAction;

namespace storey::plugin {

class ActionRun;
class AutorunHarness;

class StoreyPlugin : public QObject, public ccStdPluginInterface {
  Q_OBJECT
  Q_INTERFACES(ccPluginInterface ccStdPluginInterface)
  Q_PLUGIN_METADATA(IID "org.storey.CloudCompare.qStorey" FILE "../resources/info.json")

 public:
  explicit StoreyPlugin(QObject* parent = nullptr);

  QList<QAction*> getActions() override;
  void onNewSelection(const ccHObject::Container& selected) override;
  void registerCommands(ccCommandLineInterface* cmd) override;
  void setMainAppInterface(ccMainAppInterface* app) override;

 private:
  ccHObject* selectedEntity() const;

  QAction* run_action_ = nullptr;       ///< "Run Storey SLAM on a log…"
  QAction* colour_action_ = nullptr;    ///< "Inspect SRPs: colour by SRP"
  QAction* keyframe_action_ = nullptr;  ///< "Inspect SRPs: planes seen from a keyframe…"
  QAction* export_action_ = nullptr;    ///< "Export storeys…"
  ActionRun* run_ = nullptr;            ///< the run action's state (worker, progress dialog)
  AutorunHarness* harness_ = nullptr;   ///< only with STOREY_PLUGIN_AUTORUN set
};

}  // namespace storey::plugin
