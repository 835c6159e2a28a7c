// The render step: which images, in which order, and the report rewrite.
#include "render/render.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/log.h"
#include "export/report_html.h"
#include "render/run_data.h"
#include "render/views.h"
#include "render/x_display.h"

namespace storey::render {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// Leaves out images of an earlier render that this one does not rewrite.
void removeOldRenders(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".png") continue;
    for (const char* prefix : {"elevation_", "storey_", "map_top", "srp_", "trajectories_"}) {
      if (name.rfind(prefix, 0) == 0) {
        fs::remove(entry.path(), ec);
        break;
      }
    }
  }
}

}  // namespace

void parseViewList(const std::string& list, RenderViews& views) {
  RenderViews v;
  v.elevation = v.storeys = v.srp = v.keyframe = v.trajectories = false;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    while (!item.empty() && item.front() == ' ') item.erase(0, 1);
    while (!item.empty() && item.back() == ' ') item.pop_back();
    if (item == "all")
      v.elevation = v.storeys = v.srp = v.keyframe = v.trajectories = true;
    else if (item == "elevation")
      v.elevation = true;
    else if (item == "storeys")
      v.storeys = true;
    else if (item == "srp")
      v.srp = true;
    else if (item == "keyframe")
      v.keyframe = true;
    else if (item == "trajectories")
      v.trajectories = true;
    else if (!item.empty())
      throw Error("--views: unknown view '" + item +
                  "' (known: elevation, storeys, srp, keyframe, trajectories, all)");
  }
  views = v;
}

RenderSummary renderRun(const RenderRequest& request, const RenderConfig& config,
                        const ProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  config.validate();
  RenderSummary summary;
  auto report = [&progress](double fraction, const char* stage) {
    if (progress && !progress(fraction, stage)) throw Cancelled();
  };
  report(0.0, "reading the run");
  const RunData run = loadRun(request.out_dir, static_cast<std::size_t>(config.max_display_points),
                              request.map_sample.get());
  summary.notes = run.notes;
  summary.map_points = run.map.file_points;
  summary.display_points = run.map.size();
  const ViewContext context = makeViewContext(run, config);

  // Checks that need no display first, so a wrong option fails fast.
  int keyframe = request.keyframe.value_or(config.keyframe);
  const bool want_keyframe = config.views.keyframe || request.keyframe.has_value();
  if (request.keyframe &&
      (*request.keyframe < 0 || *request.keyframe >= static_cast<int>(run.keyframes.size()))) {
    throw Error("--keyframe " + std::to_string(*request.keyframe) + ": " + request.out_dir +
                "/keyframes.tum has " + std::to_string(run.keyframes.size()) + " keyframes (0 to " +
                std::to_string(static_cast<int>(run.keyframes.size()) - 1) + ")");
  }
  if (keyframe < 0) keyframe = keyframeWithMostSrps(context);
  std::optional<TrajectoryComparison> comparison;
  if (!request.ground_truth.empty() && config.views.trajectories) {
    std::vector<NamedTrajectory> estimates{{"this run (" + context.run_name + ")", run.trajectory}};
    for (const std::string& dir : request.compare) {
      const fs::path t = fs::path(dir) / "trajectory.tum";
      if (!fs::exists(t)) throw Error("--compare " + dir + ": no trajectory.tum in it");
      fs::path p(dir);
      const std::string name =
          (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
      estimates.push_back({name, readTum(t.string())});
    }
    comparison = compareTrajectories(readTum(request.ground_truth),
                                     fs::path(request.ground_truth).filename().string(), estimates);
  } else if (config.views.trajectories && !request.compare.empty()) {
    summary.notes.push_back("--compare needs --gt: no trajectory comparison");
  }

  const fs::path renders = fs::path(request.out_dir) / "renders";
  fs::create_directories(renders);
  removeOldRenders(renders);
  XDisplayGuard display(config.width, config.height);
  summary.started_xvfb = display.startedXvfb();

  // The images to draw, counted first for the progress fraction.
  std::vector<NamedFigure> storey_tops;
  if (config.views.storeys) storey_tops = storeyTopFigures(context);
  const bool draw_srp_map = config.views.srp && !run.planes.empty();
  const bool draw_keyframe = want_keyframe && keyframe >= 0;
  const std::size_t planned = (config.views.elevation ? 2 : 0) + storey_tops.size() +
                              (draw_srp_map ? 1 : 0) + (draw_keyframe ? 1 : 0) +
                              (comparison ? 2 : 0);
  auto draw = [&](const Figure& figure, const std::string& file, const std::string& caption) {
    report(static_cast<double>(summary.images.size()) / std::max<std::size_t>(planned, 1),
           "drawing images");
    renderFigure(figure, (renders / file).string());
    summary.images.push_back({"renders/" + file, figure.title, caption});
    logInfo("render: wrote " + (renders / file).string());
  };
  if (config.views.elevation) {
    draw(elevationFigure(context, false), "elevation_front.png",
         "The whole map seen from the front, points coloured by storey, the trajectory in black, "
         "floor elevations dashed.");
    draw(elevationFigure(context, true), "elevation_side.png", "The same from the side.");
  }
  if (config.views.storeys) {
    for (const NamedFigure& f : storey_tops)
      draw(f.figure, f.file,
           "From above, points coloured by height above the floor (ceiling left out), the "
           "trajectory walked on this storey in black.");
  }
  if (config.views.srp) {
    if (!draw_srp_map)
      summary.notes.push_back("no SRP in planes.json: no SRP map view");
    else
      draw(
          srpMapFigure(context), "srp_map.png",
          "Every observation of a global SRP drawn as its patch (convex hull of its inliers at the "
          "keyframe's final pose), in the plane's colour in every storey where it was seen; map "
          "points on a patch take its colour, the rest of the map is grey.");
  }
  if (want_keyframe) {
    if (!draw_keyframe) {
      summary.notes.push_back("no keyframe with SRPs: no keyframe view");
    } else {
      char name[48];
      std::snprintf(name, sizeof(name), "srp_keyframe_%04d.png", keyframe);
      draw(srpKeyframeFigure(context, keyframe), name,
           "The SRPs extracted at one keyframe, in colour over the grey map around it, with the "
           "LiDAR's axes at the keyframe pose.");
    }
  }
  if (comparison) {
    draw(trajectoryFigure(context, *comparison, true), "trajectories_top.png",
         "Ground truth (black) and the estimated trajectories from above; ATE and end-point drift "
         "in the legend.");
    draw(trajectoryFigure(context, *comparison, false), "trajectories_front.png",
         "The same from the front: vertical drift between storeys shows here.");
  }

  report(1.0, "drawing images");
  // report.md with the images, and report.html next to it.
  const fs::path report_json = fs::path(request.out_dir) / "report.json";
  if (fs::exists(report_json)) {
    const std::string json = readFile(report_json);
    writeReportMarkdown(json, (fs::path(request.out_dir) / "report.md").string(), summary.images);
    writeReportHtml(json, (fs::path(request.out_dir) / "report.html").string(), summary.images);
  } else {
    summary.notes.push_back("no report.json: report.md and report.html not written");
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace storey::render
