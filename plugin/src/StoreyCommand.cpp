#include "StoreyCommand.h"

#include <QFileInfo>
#include <cmath>

#include "Entities.h"
#include "StoreyRun.h"
#include "common/error.h"
#include "common/progress.h"
#include "export/storey_files.h"

namespace storey::plugin {

namespace {

constexpr const char* kKeyword = "STOREY_SLAM";
constexpr const char* kConfig = "STOREY_CONFIG";
constexpr const char* kCalibration = "STOREY_CALIBRATION";
constexpr const char* kOut = "STOREY_OUT";

}  // namespace

StoreyCommand::StoreyCommand() : Command("Storey SLAM", kKeyword) {}

bool StoreyCommand::process(ccCommandLineInterface& cmd) {
  QStringList& args = cmd.arguments();
  const QString usage = QString("usage: -%1 LOG [-%2 FILE] [-%3 FILE] [-%4 DIR]")
                            .arg(kKeyword, kConfig, kCalibration, kOut);
  if (args.empty() || args.front().startsWith('-'))
    return cmd.error(QString("[Storey] missing LOG after -%1; %2").arg(kKeyword, usage));
  RunRequest request;
  request.log_path = args.takeFirst().toStdString();
  while (!args.empty()) {
    std::string* target = nullptr;
    QString option;
    for (const auto& [keyword, field] :
         {std::pair{kConfig, &request.config_path},
          std::pair{kCalibration, &request.calibration_path}, std::pair{kOut, &request.out_dir}}) {
      if (ccCommandLineInterface::IsCommand(args.front(), keyword)) {
        target = field;
        option = keyword;
      }
    }
    if (target == nullptr) break;  // the next CloudCompare command
    args.takeFirst();
    if (args.empty() || args.front().startsWith('-'))
      return cmd.error(QString("[Storey] missing value after -%1; %2").arg(option, usage));
    *target = args.takeFirst().toStdString();
  }

  RunOutcome outcome;
  try {
    const Config config = loadRequestConfig(request);
    cmd.print(QString("[Storey] mapping %1 (calibration: %2, output: %3)")
                  .arg(QString::fromStdString(request.log_path),
                       QString::fromStdString(resolveCalibration(request).empty()
                                                  ? std::string("none")
                                                  : resolveCalibration(request)),
                       QString::fromStdString(resolveOutDir(request))));
    std::string last_stage;
    int last_percent = -10;
    ProgressMeter meter;
    outcome = runStorey(
        request, config,
        [&](double fraction, const std::string& stage) {
          meter.update(fraction, stage);
          const int percent = static_cast<int>(std::floor(fraction * 100.0));
          if (stage != last_stage || percent >= last_percent + 10) {
            cmd.print(QString("[Storey] %1 %2% (%3)")
                          .arg(QString::fromStdString(stage))
                          .arg(percent)
                          .arg(QString::fromStdString(timingText(meter.reading()))));
            last_stage = stage;
            last_percent = percent;
          }
          return true;
        },
        [&](double log_seconds) { meter.setLogTime(log_seconds); });
  } catch (const std::exception& e) {
    return cmd.error(QString("[Storey] %1").arg(QString::fromStdString(e.what())));
  }

  for (const ConsoleLine& line : runConsoleLines(outcome)) {
    if (line.warning)
      cmd.warning(QString::fromStdString(line.text));
    else
      cmd.print(QString::fromStdString(line.text));
  }

  if (!outcome.result.map) {
    cmd.warning("[Storey] the map is off (map.enabled: false): no cloud to hand over");
    return true;
  }
  const QString stem = QFileInfo(QString::fromStdString(outcome.log_path)).completeBaseName();
  const QString out = QString::fromStdString(outcome.out_dir);
  const MapCloud& map = *outcome.result.map;
  const double origin =
      outcome.result.trajectory.empty() ? 0.0 : outcome.result.trajectory.front().time;
  try {
    cmd.clouds().emplace_back(toCloud(map, nullptr, origin, stem + "_map"), stem + "_map", out);
    for (const int s : storeyIndices(map)) {
      const std::vector<std::uint32_t> indices = pointsOfStorey(map, s);
      const QString name = QString("%1_storey_%2").arg(stem).arg(s, 2, 10, QChar('0'));
      cmd.clouds().emplace_back(toCloud(map, &indices, origin, name), name, out);
    }
  } catch (const std::exception& e) {
    return cmd.error(QString("[Storey] %1").arg(QString::fromStdString(e.what())));
  }
  return true;
}

}  // namespace storey::plugin
