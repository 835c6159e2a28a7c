#pragma once
/// The run's remaining files: trajectories, keyframes, planes.json and the
/// report (written last, once).
#include <string>
#include <vector>

#include "backend/backend.h"
#include "pipeline/run_report.h"
#include "pipeline/scan_timings.h"

namespace storey {

/// Creates the output folder (storey::Error naming it when it cannot) and
/// removes the temporaries a killed earlier run left in it.
void createOutputFolder(const std::string& out_dir);

/// Writes the trajectories (TUM, KITTI), keyframes.tum, timing.csv (the
/// per-scan wall times), planes.json (or removes a stale one when the back
/// end is off), then report.json,
/// report.md and report.html (without images) last. `files` (relative to out_dir) is extended with
/// them. Returns the report as written (report.json's text).
std::string writeRunOutputs(const std::string& out_dir, const SlamResult& slam,
                            const ScanTimings& timings, RunReportBuilder& report,
                            std::vector<std::string>& files);

}  // namespace storey
