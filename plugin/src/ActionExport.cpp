#include "ActionExport.h"

#include <ccPointCloud.h>

#include <QFileDialog>
#include <QInputDialog>
#include <QMainWindow>

#include "ActionCommon.h"
#include "Entities.h"
#include "export/storey_files.h"

namespace storey::plugin {

void performExportStoreys(ccMainAppInterface* app, ccHObject* selected) {
  ccPointCloud* cloud = findStoreyCloud(selected);
  if (app == nullptr || cloud == nullptr) return consoleError(app, "select a Storey cloud");
  QWidget* parent = app->getMainWindow();
  const QString dir = QFileDialog::getExistingDirectory(parent, "Storey: export storeys into");
  if (dir.isEmpty()) return;
  bool ok = false;
  const QString format =
      QInputDialog::getItem(parent, "Storey: export storeys",
                            "Format:", {"LAS 1.4", "PLY", "LAS 1.4 and PLY"}, 0, false, &ok);
  if (!ok) return;
  StoreyFileFormats formats;
  formats.las = format.startsWith("LAS");
  formats.ply = format.contains("PLY");
  try {
    std::vector<std::string> files;
    {
      WaitCursor wait;
      files = writeStoreyFiles(fromCloud(*cloud), dir.toStdString(), formats);
    }
    for (const std::string& f : files)
      app->dispToConsole("[Storey] wrote " + QString::fromStdString(f));
  } catch (const std::exception& e) {
    consoleError(app, e.what());
  }
}

}  // namespace storey::plugin
