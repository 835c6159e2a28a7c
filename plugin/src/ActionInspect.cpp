#include "ActionInspect.h"

#include <ccPointCloud.h>

#include <QInputDialog>
#include <QMainWindow>
#include <algorithm>

#include "ActionCommon.h"
#include "Entities.h"
#include "Inspect.h"

namespace storey::plugin {

void performColourBySrp(ccMainAppInterface* app, ccHObject* selected) {
  ccPointCloud* cloud = findStoreyCloud(selected);
  if (app == nullptr || cloud == nullptr) return consoleError(app, "select a Storey cloud");
  try {
    std::size_t labelled = 0;
    {
      WaitCursor wait;
      labelled = colourBySrp(*cloud);
    }
    app->dispToConsole(
        QString("[Storey] %1 of %2 points of '%3' lie on an SRP (scalar field 'srp')")
            .arg(labelled)
            .arg(cloud->size())
            .arg(cloud->getName()));
    cloud->prepareDisplayForRefresh();
    app->refreshAll();
    app->updateUI();
  } catch (const std::exception& e) {
    consoleError(app, e.what());
  }
}

void performPlanesOfKeyframe(ccMainAppInterface* app, ccHObject* selected) {
  ccHObject* group = findRunGroup(selected);
  if (app == nullptr || group == nullptr)
    return consoleError(app, "select an entity of a Storey run");
  const int count = keyframeCount(*group);
  bool ok = false;
  const int keyframe =
      QInputDialog::getInt(app->getMainWindow(), "Storey: planes seen from a keyframe",
                           QString("Keyframe (0 to %1; -1 shows every SRP):").arg(count - 1), 0, -1,
                           std::max(0, count - 1), 1, &ok);
  if (!ok) return;
  try {
    const QStringList lines = showPlanesOfKeyframe(*group, keyframe);
    app->dispToConsole(
        keyframe < 0
            ? QString("[Storey] showing every SRP")
            : QString("[Storey] keyframe %1 observed %2 SRP(s):").arg(keyframe).arg(lines.size()));
    for (const QString& line : lines) app->dispToConsole("[Storey]   " + line);
    app->refreshAll();
  } catch (const std::exception& e) {
    consoleError(app, e.what());
  }
}

}  // namespace storey::plugin
