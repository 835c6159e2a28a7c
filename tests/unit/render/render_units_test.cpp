// Render parts that need no display: palette, PLY subsample, patches,
// view list, report.md images and report.html.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "common/error.h"
#include "export/point_cloud_writers.h"
#include "export/report_html.h"
#include "export/report_markdown.h"
#include "render/palette.h"
#include "render/render.h"
#include "render/run_data.h"
#include "render/srp_patches.h"
#include "render_fixture.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

using render::Rgb;

TEST(RenderPalette, SrpColoursAreDistinctAndNeverGrey) {
  std::set<std::uint32_t> seen;
  for (int id = 0; id < render::kSrpPaletteSize; ++id) {
    const Rgb c = render::srpColour(id);
    EXPECT_FALSE(c.r == c.g && c.g == c.b) << id;
    EXPECT_TRUE(seen.insert((c.r << 16) | (c.g << 8) | c.b).second)
        << "colour of SRP " << id << " repeats";
  }
  EXPECT_EQ(render::srpColour(0), render::srpColour(render::kSrpPaletteSize));
  const Rgb g = render::mapGrey(0.3);
  EXPECT_TRUE(g.r == g.g && g.g == g.b);
}

TEST(RenderMapPly, KeepsAllOrAUniformSubsample) {
  test::TempDir dir;
  std::vector<test::MapPoint> points;
  for (int i = 0; i < 20000; ++i)
    points.push_back(
        {Eigen::Vector3f(static_cast<float>(i % 100), static_cast<float>(i / 100), 1.0f), i % 7,
         i % 3 - 1, i % 5 == 0});
  test::writeMapPly(dir.file("map.ply"), points);
  const render::MapSample all = render::readMapSample(dir.file("map.ply"), 50000);
  ASSERT_EQ(all.size(), 20000u);
  EXPECT_EQ(all.file_points, 20000u);
  EXPECT_EQ(all.positions[123], points[123].p);
  EXPECT_EQ(all.keyframe[123], 123 % 7);
  EXPECT_EQ(all.storey[124], 124 % 3 - 1);
  EXPECT_EQ(all.stairs[125], 1);
  const render::MapSample some = render::readMapSample(dir.file("map.ply"), 2000);
  EXPECT_NEAR(static_cast<double>(some.size()), 2000.0, 200.0);
  // Uniform: both halves of the file are represented about equally.
  std::size_t low = 0;
  for (const auto& p : some.positions) low += p.y() < 100.0f;
  EXPECT_NEAR(static_cast<double>(low) / some.size(), 0.5, 0.06);
}

TEST(RenderMapPly, TheSampleOfTheMapInMemoryIsTheSampleOfItsFile) {
  // storey run hands its renders the sample of the map in memory: it must be
  // what they would read from the map.ply written from that map.
  MapCloud map;
  for (int i = 0; i < 30000; ++i) {
    const float x = static_cast<float>(i % 173) * 0.013f;
    map.positions.emplace_back(x, static_cast<float>(i / 173) * 0.021f, std::sin(x) * 3.0f);
    map.intensity.push_back(static_cast<float>(i % 255));
    map.time.push_back(1.7e9 + i * 1e-4);
    map.keyframe.push_back(i / 100);
    map.storey.push_back(static_cast<std::int16_t>(i % 4 - 1));
    map.flags.push_back(static_cast<std::uint8_t>(i % 3 == 0 ? kMapPointStairs : 0));
  }
  map.positions[5].x() = std::numeric_limits<float>::quiet_NaN();  // left out by both
  test::TempDir dir;
  writePly(dir.file("map.ply"), map);
  for (std::size_t max_points : {std::size_t{100000}, std::size_t{5000}}) {
    const render::MapSample from_file = render::readMapSample(dir.file("map.ply"), max_points);
    const render::MapSample in_memory = render::sampleMap(map, max_points);
    EXPECT_EQ(in_memory.file_points, from_file.file_points);
    ASSERT_EQ(in_memory.size(), from_file.size()) << max_points;
    EXPECT_LT(in_memory.size(), map.size());
    EXPECT_EQ(in_memory.positions, from_file.positions);
    EXPECT_EQ(in_memory.keyframe, from_file.keyframe);
    EXPECT_EQ(in_memory.storey, from_file.storey);
    EXPECT_EQ(in_memory.stairs, from_file.stairs);
  }
}

TEST(RenderMapPly, TruncatedOrForeignFilesAreErrorsNamingTheFile) {
  test::TempDir dir;
  std::vector<test::MapPoint> points(100);
  test::writeMapPly(dir.file("map.ply"), points);
  std::filesystem::resize_file(dir.file("map.ply"),
                               std::filesystem::file_size(dir.file("map.ply")) - 10);
  try {
    render::readMapSample(dir.file("map.ply"), 1000);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(dir.file("map.ply")), std::string::npos) << e.what();
  }
  dir.write("ascii.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n");
  EXPECT_THROW(render::readMapSample(dir.file("ascii.ply"), 10), Error);
}

TEST(RenderPatches, HullsAreMovedByTheKeyframePoseAndColourTheirPoints) {
  test::TempDir dir;
  const int planes = test::writeRoomRun(dir.file("run"));
  const render::RunData run = render::loadRun(dir.file("run"), 1000000);
  ASSERT_EQ(static_cast<int>(run.planes.size()), planes);
  const render::PatchSet set = render::worldPatches(run, 0.05, 8.0);
  EXPECT_EQ(set.estimated, 0u);
  EXPECT_EQ(set.skipped, 0u);
  ASSERT_EQ(set.patches.size(), 8u);
  for (const render::WorldPatch& p : set.patches) {
    // Every world hull vertex lies on the true plane (keyframe 1 is turned 90 degrees).
    const GlobalPlane& plane = run.planes[static_cast<std::size_t>(p.plane_index)];
    for (const auto& v : p.hull)
      EXPECT_NEAR(plane.normal_world.dot(v), plane.distance_world, 1e-6) << p.plane_id;
    EXPECT_EQ(p.hull.size(), 4u);
  }
  const std::vector<int> srp = render::srpOfPoints(run.map, set.patches, 0.05);
  std::set<int> ids(srp.begin(), srp.end());
  EXPECT_EQ(ids, (std::set<int>{0, 1, 2, 3, 4, 5}));
}

TEST(RenderViews, ListParsesAndRejectsUnknownNames) {
  RenderViews v;
  render::parseViewList("srp, keyframe", v);
  EXPECT_TRUE(v.srp && v.keyframe);
  EXPECT_FALSE(v.elevation || v.storeys || v.trajectories);
  render::parseViewList("all", v);
  EXPECT_TRUE(v.elevation && v.storeys && v.srp && v.keyframe && v.trajectories);
  EXPECT_THROW(render::parseViewList("srp,bogus", v), Error);
}

TEST(RenderReport, MarkdownEmbedsImagesAndHtmlIsOnePage) {
  const std::string json =
      R"({"storey_version": "0.1.0", "input": {"log": "a.bag", "scans_read": 3},
    "odometry": {"scans": 3, "timing_ms": {"scan": {"median": 1.5, "p95": 2, "mean": 1.6, "max": 3}}},
    "warnings": ["w <1>"]})";
  EXPECT_EQ(reportMarkdown(json).find("## Renders"), std::string::npos);
  const std::vector<ReportImage> images{{"renders/srp_map.png", "SRP map", "Planes & map."}};
  const std::string md = reportMarkdown(json, images);
  EXPECT_NE(md.find("![SRP map](renders/srp_map.png)"), std::string::npos) << md;
  const std::string html = reportHtml(json, images);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<img src=\"renders/srp_map.png\""), std::string::npos) << html;
  EXPECT_NE(html.find("<table>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td class=\"r\">1.50</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("Planes &amp; map."), std::string::npos) << html;
  EXPECT_NE(html.find("<li>w &lt;1&gt;</li>"), std::string::npos) << html;
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "self-contained: nothing fetched";
}

}  // namespace
}  // namespace storey
