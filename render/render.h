#pragma once
/// `storey render OUTDIR` and the render step at the end of `storey run`:
/// reads a finished run's files, writes OUTDIR/renders/*.png off-screen
/// (starting a private Xvfb when there is no X display), then rewrites
/// OUTDIR/report.md with the images and writes OUTDIR/report.html.
/// docs/renders.md lists the images.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/progress.h"
#include "config/render_config.h"
#include "export/report_markdown.h"
#include "render/run_data.h"

namespace storey::render {

struct RenderRequest {
  std::string out_dir;               ///< output folder of `storey run`
  std::optional<int> keyframe;       ///< keyframe view; default: config.keyframe
  std::string ground_truth;          ///< TUM file; empty = no trajectory comparison
  std::vector<std::string> compare;  ///< other run folders (e.g. --no-srp) drawn with it
  /// The map's display sample (sampleMap, run_data.h) when the caller still
  /// has the map in memory (`storey run`): map.ply is then not read back.
  std::shared_ptr<const MapSample> map_sample;
};

struct RenderSummary {
  std::vector<ReportImage> images;  ///< paths relative to out_dir
  std::vector<std::string> notes;   ///< views left out and why
  std::size_t map_points = 0;       ///< in map.ply
  std::size_t display_points = 0;   ///< kept for display
  bool started_xvfb = false;
  double seconds = 0.0;  ///< wall time
};

/// Throws storey::Error (missing or malformed files, no display possible,
/// a keyframe that does not exist, ...). `progress` gets the stages "reading
/// the run" and "drawing images" (the fraction of the images drawn); false
/// cancels (storey::Cancelled).
RenderSummary renderRun(const RenderRequest& request, const RenderConfig& config,
                        const ProgressFn& progress = nullptr);

/// Image names a view list accepts: elevation, storeys, srp, keyframe, trajectories.
/// Parses a comma-separated list ("all" = every view) into `views`; throws
/// storey::Error naming an unknown entry.
void parseViewList(const std::string& list, RenderViews& views);

}  // namespace storey::render
