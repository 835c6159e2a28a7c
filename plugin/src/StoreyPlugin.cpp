#include "StoreyPlugin.h"

#include <ccCommandLineInterface.h>

#include <QAction>
#include <QIcon>

#include "ActionExport.h"
#include "ActionInspect.h"
#include "ActionRun.h"
#include "AutorunHarness.h"
#include "Entities.h"
#include "StoreyCommand.h"

namespace storey::plugin {

StoreyPlugin::StoreyPlugin(QObject* parent)
    : QObject(parent), ccStdPluginInterface(":/CC/plugin/qStorey/info.json") {}

QList<QAction*> StoreyPlugin::getActions() {
  if (run_action_ == nullptr) {
    run_action_ = new QAction("Run Storey SLAM on a log…", this);
    run_action_->setToolTip(
        "Map a LiDAR + IMU log with Storey; the map, storeys, trajectory and SRPs come into the DB "
        "tree");
    run_action_->setIcon(getIcon());
    run_ = new ActionRun(run_action_, this);
    connect(run_action_, &QAction::triggered, this, [this] { run_->chooseAndRun(m_app); });

    colour_action_ = new QAction("Inspect SRPs: colour by SRP", this);
    colour_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/srp.png"));
    colour_action_->setToolTip(
        "Colour the selected Storey cloud by the global SRP each point lies on (scalar field "
        "'srp')");
    connect(colour_action_, &QAction::triggered, this,
            [this] { performColourBySrp(m_app, selectedEntity()); });

    keyframe_action_ = new QAction("Inspect SRPs: planes seen from a keyframe…", this);
    keyframe_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/keyframe.png"));
    keyframe_action_->setToolTip(
        "Show only the SRP planes observed from a chosen keyframe of the selected Storey run");
    connect(keyframe_action_, &QAction::triggered, this,
            [this] { performPlanesOfKeyframe(m_app, selectedEntity()); });

    export_action_ = new QAction("Export storeys…", this);
    export_action_->setIcon(QIcon(":/CC/plugin/qStorey/images/export.png"));
    export_action_->setToolTip(
        "Write LAS/PLY per storey of the selected Storey cloud with Storey's exporters");
    connect(export_action_, &QAction::triggered, this,
            [this] { performExportStoreys(m_app, selectedEntity()); });
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
  if (app != nullptr && harness_ == nullptr && AutorunHarness::requested()) {
    getActions();  // the run action exists before the harness drives it
    harness_ = new AutorunHarness(app, run_, this);
  }
}

ccHObject* StoreyPlugin::selectedEntity() const {
  if (m_app == nullptr || m_app->getSelectedEntities().empty()) return nullptr;
  return m_app->getSelectedEntities().front();
}

}  // namespace storey::plugin
