#include "RunDialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

#include "common/error.h"
#include "io/log_format.h"

namespace storey::plugin {

namespace {

constexpr LidarModel kSensorPresets[] = {LidarModel::kVlp16, LidarModel::kVlp32c,
                                         LidarModel::kHdl32e, LidarModel::kOs1_64,
                                         LidarModel::kGeneric};

}  // namespace

RunDialog::RunDialog(const QString& log_path, QWidget* parent) : QDialog(parent) {
  setWindowTitle("Run Storey SLAM");
  auto* form = new QFormLayout;

  auto fileRow = [&](QLineEdit*& edit, const QString& label, const QString& placeholder,
                     const QString& title, bool folder) {
    edit = new QLineEdit;
    edit->setPlaceholderText(placeholder);
    edit->setMinimumWidth(380);
    auto* button = new QPushButton("…");
    connect(button, &QPushButton::clicked, this, [=] { browse(edit, title, folder); });
    auto* row = new QHBoxLayout;
    row->addWidget(edit);
    row->addWidget(button);
    form->addRow(label, row);
  };
  fileRow(log_, "Log:", "ROS1/ROS 2 bag, MCAP, Velodyne pcap or PCD folder", "LiDAR + IMU log",
          false);
  fileRow(config_file_, "Config file:", "optional: built-in defaults",
          "Storey configuration (YAML)", false);
  fileRow(calibration_, "Calibration:", "optional: calibration.yaml beside the log, if any",
          "Sensor calibration (YAML)", false);
  fileRow(out_dir_, "Output folder:", "default: <log folder>/<log name>_storey", "Output folder",
          true);
  log_->setText(log_path);

  sensor_ = new QComboBox;
  for (LidarModel m : kSensorPresets) sensor_->addItem(toString(m));
  sensor_->setToolTip(
      "LiDAR model (ring elevations, firing timing); the calibration file sets it too");
  form->addRow("Sensor preset:", sensor_);

  voxel_ = new QDoubleSpinBox;
  voxel_->setDecimals(3);
  voxel_->setRange(0.005, 5.0);
  voxel_->setSingleStep(0.01);
  voxel_->setSuffix(" m");
  voxel_->setToolTip("map.voxel_size: one point per voxel of this edge");
  form->addRow("Map voxel size:", voxel_);

  srp_ = new QCheckBox("SRP back end (structural planes, keyframe graph)");
  form->addRow("", srp_);
  storeys_ = new QCheckBox("Storey segmentation");
  form->addRow("", storeys_);

  status_ = new QLabel;
  status_->setWordWrap(true);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  buttons->button(QDialogButtonBox::Ok)->setText("Run");
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    if (log_->text().trimmed().isEmpty()) {
      status_->setText("<font color=red>Choose a log.</font>");
      return;
    }
    if (!load_error_.isEmpty()) {
      status_->setText(QString("<font color=red>%1</font>").arg(load_error_.toHtmlEscaped()));
      return;
    }
    try {
      config().validate();
    } catch (const Error& e) {
      status_->setText(QString("<font color=red>%1</font>")
                           .arg(QString::fromStdString(e.what()).toHtmlEscaped()));
      return;
    }
    accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(status_);
  layout->addWidget(buttons);

  connect(config_file_, &QLineEdit::editingFinished, this, &RunDialog::reload);
  connect(calibration_, &QLineEdit::editingFinished, this, &RunDialog::reload);
  connect(log_, &QLineEdit::editingFinished, this, &RunDialog::reload);
  reload();
}

void RunDialog::browse(QLineEdit* edit, const QString& title, bool folder) {
  QString path;
  if (folder) {
    path = QFileDialog::getExistingDirectory(this, title, edit->text());
  } else if (edit == log_) {
    // A rosbag2 folder is chosen by its metadata.yaml, a PCD folder by one of its scans.
    path = QFileDialog::getOpenFileName(this, title, edit->text(), kLogFileDialogFilter);
    if (!path.isEmpty()) path = QString::fromStdString(logPathForChosenFile(path.toStdString()));
  } else {
    path = QFileDialog::getOpenFileName(this, title, edit->text());
  }
  if (path.isEmpty()) return;
  edit->setText(path);
  reload();
}

void RunDialog::setConfigFile(const QString& path) {
  config_file_->setText(path);
  reload();
}

void RunDialog::setOutputFolder(const QString& path) {
  out_dir_->setText(path);
}

RunRequest RunDialog::request() const {
  RunRequest r;
  r.log_path = log_->text().trimmed().toStdString();
  r.config_path = config_file_->text().trimmed().toStdString();
  r.calibration_path = calibration_->text().trimmed().toStdString();
  r.out_dir = out_dir_->text().trimmed().toStdString();
  return r;
}

void RunDialog::reload() {
  const RunRequest r = request();
  load_error_.clear();
  try {
    loaded_ = loadRequestConfig(r);
    const std::string calibration = resolveCalibration(r);
    status_->setText(calibration.empty() || !r.calibration_path.empty()
                         ? QString()
                         : QString("Calibration: %1").arg(QString::fromStdString(calibration)));
  } catch (const Error& e) {
    loaded_ = Config{};
    load_error_ = QString::fromStdString(e.what());
    status_->setText(
        QString("<font color=red>%1</font>").arg(QString::fromStdString(e.what()).toHtmlEscaped()));
  }
  sensor_->setCurrentText(toString(loaded_.sensor.lidar_model));
  voxel_->setValue(loaded_.map.voxel_size);
  srp_->setChecked(loaded_.backend.srp);
  storeys_->setChecked(loaded_.storeys.enabled);
}

Config RunDialog::config() const {
  Config c = loaded_;
  c.sensor.lidar_model = lidarModelFromString(sensor_->currentText().toStdString());
  c.map.voxel_size = voxel_->value();
  c.backend.srp = srp_->isChecked();
  c.storeys.enabled = storeys_->isChecked();
  return c;
}

}  // namespace storey::plugin
