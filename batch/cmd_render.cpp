// `storey render OUTDIR`: PNG renders of a finished run, off-screen, and
// report.md / report.html with the images.
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "config/config.h"
#include "progress_bar.h"
#include "render/render.h"

namespace storey::cli {

int runRender(const RenderOptions& options) {
  Config config = options.config_path.empty() ? Config{} : loadConfig(options.config_path);
  RenderConfig& r = config.render;
  if (options.width) r.width = *options.width;
  if (options.height) r.height = *options.height;
  if (options.max_points) r.max_display_points = *options.max_points;
  if (!options.views.empty()) render::parseViewList(options.views, r.views);
  if (options.keyframe) r.views.keyframe = true;
  config.validate();

  render::RenderRequest request;
  request.out_dir = options.out_dir;
  request.keyframe = options.keyframe;
  request.ground_truth = options.ground_truth;
  request.compare = options.compare;
  ProgressBar bar("render");
  const render::RenderSummary summary = render::renderRun(request, r, bar.callback());
  bar.done();
  for (const std::string& note : summary.notes)
    std::cerr << "storey render: note: " << note << '\n';
  std::cout << std::fixed << std::setprecision(1) << summary.images.size() << " images in "
            << options.out_dir << "/renders (" << summary.display_points << " of "
            << summary.map_points << " map points drawn) in " << summary.seconds << " s"
            << (summary.started_xvfb ? ", private Xvfb" : "")
            << "; report.md and report.html updated\n";
  return 0;
}

}  // namespace storey::cli
