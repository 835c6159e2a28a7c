#pragma once
/// "Run Storey SLAM on a log…": the parameters a surveyor changes. The
/// dialog edits a storey::Config (the core's struct, loaded from the config
/// and calibration files exactly as `storey run` does); it holds no
/// parameters of its own.
#include <QDialog>

#include "StoreyRun.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;

namespace storey::plugin {

class RunDialog : public QDialog {
  Q_OBJECT
 public:
  RunDialog(const QString& log_path, QWidget* parent = nullptr);

  /// Fill the file fields (and reload the parameters), as a user would.
  void setConfigFile(const QString& path);
  void setOutputFolder(const QString& path);

  /// Why the config or calibration file could not be loaded; empty when they were.
  const QString& loadError() const { return load_error_; }

  RunRequest request() const;
  /// The loaded config with the dialog's values written over it.
  Config config() const;

 private:
  void reload();  ///< re-reads the config and calibration files into the widgets
  void browse(QLineEdit* edit, const QString& title, bool folder);

  Config loaded_;
  QString load_error_;
  QLineEdit* log_ = nullptr;
  QLineEdit* config_file_ = nullptr;
  QLineEdit* calibration_ = nullptr;
  QLineEdit* out_dir_ = nullptr;
  QComboBox* sensor_ = nullptr;
  QDoubleSpinBox* voxel_ = nullptr;
  QCheckBox* srp_ = nullptr;
  QCheckBox* storeys_ = nullptr;
  QLabel* status_ = nullptr;
};

}  // namespace storey::plugin
