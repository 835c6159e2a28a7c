// `storey run`: the pipeline on a log, or on the built-in simulated building
// (simulated into OUT/simulation/ first, with its calibration and ground truth).
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "common/error.h"
#include "config/config.h"
#include "options_config.h"
#include "pipeline/pipeline.h"
#include "pipeline/run_summary.h"
#include "progress_bar.h"
#include "render/render.h"
#include "sim/simulator.h"
#include "stop_signals.h"

namespace storey::cli {

namespace {

/// `callback`, returning false (stop) once Ctrl-C or SIGTERM has arrived.
ProgressFn stoppable(ProgressFn callback) {
  return [callback](double fraction, const std::string& stage) {
    return !StopSignals::requested() && callback(fraction, stage);
  };
}

int runStoppable(const RunOptions& options) {
  Config config = configFromOptions(options.common);
  if (options.no_srp) config.backend.srp = false;
  if (options.no_render) config.render.enabled = false;
  if (options.threads == 1) {
    config.input.read_ahead_scans = 0;
    config.backend.queue_scans = 0;
    config.map.build_threads = 1;
    config.map.export_threads = 1;
    config.odometry.threads = 1;
  }
  std::string log_path = options.log_path;
  std::string ground_truth;  // the simulator's, when the built-in building is mapped
  if (log_path.empty()) {
    const std::string sim_dir = (std::filesystem::path(options.out_dir) / "simulation").string();
    std::cerr << "storey run: no LOG given: simulating the built-in building '" << options.preset
              << "' into " << sim_dir << '\n';
    ProgressBar sim_bar("run");
    const sim::SimulationResult sim = sim::simulate(sim::loadBuildingSpec(options.preset), {},
                                                    sim_dir, stoppable(sim_bar.callback()));
    sim_bar.done();
    std::cerr << "storey run: simulated " << sim.path_length << " m in " << sim.duration << " s, "
              << sim.scans << " scans\n";
    log_path = (std::filesystem::path(sim_dir) / sim::kBagFile).string();
    ground_truth = (std::filesystem::path(sim_dir) / sim::kLidarTruthFile).string();
    // The simulated sensors' calibration, unless the user gave one.
    if (options.common.calibration_path.empty())
      applyCalibrationFile(config,
                           (std::filesystem::path(sim_dir) / sim::kCalibrationFile).string());
  }
  ProgressBar bar("run");
  PipelineResult result = runPipeline(log_path, config, options.out_dir, stoppable(bar.callback()),
                                      bar.logTimeCallback());
  bar.done();
  // Only the report and the map's display sample are kept: the map and the
  // rest are freed before the renders (peak memory, issue 23), which read
  // the other written files back.
  const std::string report_json = std::move(result.report_json);
  std::shared_ptr<const render::MapSample> map_sample;
  if (config.render.enabled && result.map)
    map_sample = std::make_shared<const render::MapSample>(
        render::sampleMap(*result.map, static_cast<std::size_t>(config.render.max_display_points)));
  result = PipelineResult();
  if (config.render.enabled) {
    // The SLAM outputs are written: a render failure is only a warning here.
    try {
      render::RenderRequest request;
      request.out_dir = options.out_dir;
      request.ground_truth = ground_truth;
      request.map_sample = map_sample;
      ProgressBar render_bar("render");
      const render::RenderSummary summary =
          render::renderRun(request, config.render, stoppable(render_bar.callback()));
      render_bar.done();
      std::cout << summary.images.size() << " renders in " << options.out_dir << "/renders ("
                << std::fixed << std::setprecision(1) << summary.seconds << " s)\n";
    } catch (const Cancelled&) {
      throw;
    } catch (const std::exception& e) {
      std::cerr << "storey run: warning: renders not written: " << e.what()
                << " (the mapping outputs are complete; retry with `storey render "
                << options.out_dir << "`)\n";
    }
  }
  std::cout << "storey run: finished\n" << summariseRun(report_json, options.out_dir).text();
  return 0;
}

}  // namespace

int runRun(const RunOptions& options) {
  // Ctrl-C / SIGTERM stop the run at its next progress report (within a
  // fraction of a second while reading the log); outputs are written whole or
  // not at all (common/atomic_file.h).
  const StopSignals stop_signals;
  try {
    return runStoppable(options);
  } catch (const Cancelled&) {
    if (!StopSignals::requested()) throw;
    std::cerr << "storey run: stopped by " << StopSignals::signalName()
              << "; no output file of this run is half-written (files it had not written yet "
                 "are missing or from an earlier run)\n";
    return 130;
  }
}

}  // namespace storey::cli
