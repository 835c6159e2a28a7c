#include "pipeline/run_outputs.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "export/kitti.h"
#include "export/planes_json.h"
#include "export/report_html.h"
#include "export/report_markdown.h"
#include "trajectory/tum.h"

namespace storey {

namespace fs = std::filesystem;

void createOutputFolder(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir + ": cannot create the output folder: " + ec.message());
  const std::size_t stale = removeStaleTemporaries(out_dir);
  if (stale > 0)
    logInfo(out_dir + ": removed " + std::to_string(stale) +
            " temporary file(s) left by an earlier run that was killed");
}

std::string writeRunOutputs(const std::string& out_dir, const SlamResult& slam,
                            const ScanTimings& timings, RunReportBuilder& report,
                            std::vector<std::string>& files) {
  const fs::path out(out_dir);
  writeTum((out / "odometry.tum").string(), slam.odometry);
  writeTum((out / "trajectory.tum").string(), slam.trajectory);
  writeKitti((out / "trajectory_kitti.txt").string(), (out / "trajectory_kitti_times.txt").string(),
             slam.trajectory);
  writeTum((out / "keyframes.tum").string(), slam.keyframes);
  timings.write((out / "timing.csv").string());
  files.insert(files.end(), {"odometry.tum", "trajectory.tum", "trajectory_kitti.txt",
                             "trajectory_kitti_times.txt", "keyframes.tum", "timing.csv"});
  if (slam.planes) {
    writePlanesJson((out / "planes.json").string(), *slam.planes);
    files.push_back("planes.json");
  } else {
    std::error_code ec;
    fs::remove(out / "planes.json", ec);  // a previous run's would be mistaken for this one's
  }
  // The report last, with the whole run's wall time and the file list.
  files.insert(files.end(), {"report.json", "report.md", "report.html"});
  report.setFiles(files);
  const nlohmann::json report_json = report.json();
  const std::string report_text = report_json.dump(2);
  writeFileAtomically((out / "report.json").string(), report_text + "\n");
  writeReportMarkdown(report_json, (out / "report.md").string());
  writeReportHtml(report_text, (out / "report.html").string());  // the render step adds images
  return report_text;
}

}  // namespace storey
