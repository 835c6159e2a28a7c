// PLY (read by core/eval's reader and by hand), PCD (read by PCL), KITTI,
// storeys.json (read by core/eval), report.md, and the map export folder.
#include <gtest/gtest.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
#include "eval/ply_reader.h"
#include "eval/storey_error.h"
#include "export/kitti.h"
#include "export/map_export.h"
#include "export/point_cloud_writers.h"
#include "export/report_markdown.h"
#include "export/storeys_json.h"
#include "export_fixtures.h"
#include "pipeline/run_report.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Ply, BinaryPropertiesReadBack) {
  test::TempDir dir;
  const MapCloud cloud = test::sampleCloud(500);
  writePly(dir.file("map.ply"), cloud);
  const eval::PlyPoints points = eval::readPlyPoints(dir.file("map.ply"));
  ASSERT_EQ(points.positions.size(), cloud.size());
  EXPECT_NEAR(points.positions[123].x(), cloud.positions[123].x(), 1e-4);

  const std::string text = readText(dir.file("map.ply"));
  const std::size_t end = text.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = text.substr(0, end);
  for (const char* p : {"format binary_little_endian 1.0", "element vertex 500", "property float x",
                        "property float intensity", "property double time", "property int keyframe",
                        "property int storey", "property uchar stairs"})
    EXPECT_NE(header.find(p), std::string::npos) << p;
  const std::size_t body = end + std::strlen("end_header\n");
  ASSERT_EQ(text.size(), body + 500 * 33);
  const char* r = text.data() + body + 7 * 33;  // record 7
  double time;
  std::int32_t keyframe, storey;
  std::memcpy(&time, r + 16, 8);
  std::memcpy(&keyframe, r + 24, 4);
  std::memcpy(&storey, r + 28, 4);
  EXPECT_DOUBLE_EQ(time, cloud.time[7]);
  EXPECT_EQ(keyframe, cloud.keyframe[7]);
  EXPECT_EQ(storey, cloud.storey[7]);
  EXPECT_EQ(static_cast<std::uint8_t>(r[32]), (cloud.flags[7] & kMapPointStairs) ? 1 : 0);
}

TEST(Pcd, PclReadsTheBinaryFile) {
  test::TempDir dir;
  const MapCloud cloud = test::sampleCloud(300);
  writePcd(dir.file("map.pcd"), cloud);
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("map.pcd"), blob), 0);
  EXPECT_EQ(blob.width * blob.height, 300u);
  std::vector<std::string> names;
  for (const auto& field : blob.fields) names.push_back(field.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"x", "y", "z", "intensity", "time", "keyframe", "storey"}));

  pcl::PointCloud<pcl::PointXYZI> xyzi;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("map.pcd"), xyzi), 0);
  ASSERT_EQ(xyzi.size(), 300u);
  EXPECT_FLOAT_EQ(xyzi[42].x, cloud.positions[42].x());
  EXPECT_FLOAT_EQ(xyzi[42].z, cloud.positions[42].z());
  EXPECT_FLOAT_EQ(xyzi[42].intensity, cloud.intensity[42]);
  // The integer fields, straight from the blob.
  std::int32_t storey;
  std::memcpy(&storey, blob.data.data() + 42 * blob.point_step + blob.fields[6].offset, 4);
  EXPECT_EQ(storey, cloud.storey[42]);
}

TEST(Kitti, TwelveNumbersPerLineRowMajor) {
  test::TempDir dir;
  Trajectory t;
  t.push_back({10.5, Pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                          Eigen::Vector3d(1, 2, 3))});
  t.push_back({10.6, Pose()});
  writeKitti(dir.file("t.txt"), dir.file("times.txt"), t);
  std::istringstream lines(readText(dir.file("t.txt")));
  std::string line;
  std::getline(lines, line);
  std::istringstream numbers(line);
  std::vector<double> v((std::istream_iterator<double>(numbers)), {});
  ASSERT_EQ(v.size(), 12u);
  const Eigen::Matrix4d m = t[0].pose.matrix();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(v[4 * r + c], m(r, c), 1e-8);
  EXPECT_EQ(readText(dir.file("times.txt")), "10.500000000\n10.600000000\n");
}

std::vector<StoreyInfo> sampleStoreys() {
  StoreyInfo a;
  a.index = 0;
  a.floor_elevation = -0.61;
  a.ceiling_elevation = 2.72;
  a.clear_height = 3.33;
  a.height = 3.6;
  a.footprint_area = 120.5;
  a.footprint = {{0, 0}, {10, 0}, {10, 12}, {0, 12}};
  a.points = 1000;
  StoreyInfo b;
  b.index = 1;
  b.floor_elevation = 2.99;
  b.points = 800;
  return {a, b};
}

TEST(StoreysJson, ReadByCoreEval) {
  test::TempDir dir;
  const std::string path = dir.write("storeys.json", storeysJson(sampleStoreys(), 0.02));
  const std::vector<eval::StoreyLevel> levels = eval::readEstimatedStoreys(path);
  ASSERT_EQ(levels.size(), 2u);
  EXPECT_EQ(levels[1].index, 1);
  EXPECT_DOUBLE_EQ(levels[0].floor_elevation, -0.61);
  const nlohmann::json j = nlohmann::json::parse(readText(path));
  EXPECT_TRUE(j["storeys"][1]["ceiling_elevation"].is_null());
  EXPECT_DOUBLE_EQ(j["storeys"][0]["area"].get<double>(), 120.5);
  EXPECT_EQ(j["storeys"][0]["footprint"].size(), 4u);
  EXPECT_EQ(j["storeys"][0]["footprint"][2][1].get<double>(), 12.0);
}

TEST(StoreysJson, TheOneReaderReadsBackWhatTheWriterWrote) {
  test::TempDir dir;
  const std::vector<StoreyInfo> written = sampleStoreys();
  const std::string path = dir.write("storeys.json", storeysJson(written, 0.02));
  const std::vector<StoreyInfo> read = readStoreysJson(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].index, written[i].index);
    EXPECT_EQ(read[i].floor_elevation, written[i].floor_elevation);
    EXPECT_EQ(read[i].ceiling_elevation, written[i].ceiling_elevation);
    EXPECT_EQ(read[i].clear_height, written[i].clear_height);
    EXPECT_EQ(read[i].height, written[i].height);
    EXPECT_EQ(read[i].footprint_area, written[i].footprint_area);
    EXPECT_EQ(read[i].points, written[i].points);
    EXPECT_EQ(read[i].footprint, written[i].footprint);
  }
  EXPECT_EQ(storeysJson(read, 0.02), storeysJson(written, 0.02));
  EXPECT_THROW(parseStoreysJson("{\"storeys\": [{\"index\": 1}]}", "s.json"), Error);
  // Found by fuzzing (tests/data/fuzz/storeys_json): a number beyond a double
  // escaped as nlohmann's out_of_range instead of a storey::Error.
  try {
    parseStoreysJson("[{\"index\": 0, \"floor_elevation\": 1e400}]", "s.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: not valid JSON"), std::string::npos) << e.what();
  }
}

TEST(ReportMarkdown, TablesFromTheRunReport) {
  // The storey table as the run report carries it (RunReportBuilder::setMap).
  RunReportBuilder builder{Config{}};
  MapStage map_stage;
  map_stage.storeys.storeys = sampleStoreys();
  builder.setMap(map_stage);
  nlohmann::json j = builder.json();
  j.update(nlohmann::json::parse(
      R"({"storey_version": "0.1.0", "input": {"log": "x.bag", "scans_read": 10},
          "odometry": {"scans": 10, "timing_ms": {"total_per_scan": {"median": 12.5, "p95": 20, "mean": 13, "max": 30}}},
          "backend": {"timing_ms_per_keyframe": {"srp_extraction": {"median": 9.5, "p95": 20, "mean": 11, "max": 40},
                                                 "final_optimisation": 106.7}},
          "end_point_drift": {"dX_m": 0.01, "dY_m": 0.02, "dZ_m": -0.03, "dXYZ_m": 0.037,
                              "dYaw_rad": 0.01745329, "path_length_m": 100},
          "warnings": ["something to check"]})"));
  const std::string report = j.dump();
  EXPECT_EQ(j["storeys"].size(), 2u);
  EXPECT_FALSE(j["storeys"][0].contains("footprint"));
  const std::string md = reportMarkdown(report);
  EXPECT_NE(md.find("## Table I"), std::string::npos);
  EXPECT_NE(md.find("| 0.010 | 0.020 | -0.030 | 0.037 | 1.000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| odometry: total_per_scan | 12.50 | 20.00 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| back end, per keyframe: srp_extraction | 9.50 | 20.00 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("whole graph: 106.7 ms"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0 | -0.610 | 2.720 | 3.330 | 3.600 | 120.5 | 1000 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 1 | 2.990 | – | – | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("- something to check"), std::string::npos);
  EXPECT_THROW(reportMarkdown(std::string("[1, 2]")), Error);
}

TEST(MapFiles, WritesTheFolderAndRemovesStaleStoreys) {
  test::TempDir dir;
  MapCloud cloud = test::sampleCloud(400);
  StoreySegmentation seg;
  seg.storeys = sampleStoreys();
  std::filesystem::create_directories(dir.path() / "storeys");
  dir.write("storeys/storey_07.las", "old");
  dir.write("storeys/notes.txt", "mine");
  const std::vector<std::string> files = writeMapFiles(dir.path().string(), cloud, seg, 0.02);
  EXPECT_EQ(files,
            (std::vector<std::string>{"map.las", "map.ply", "map.pcd", "storeys/storey_00.las",
                                      "storeys/storey_00.ply", "storeys/storey_01.las",
                                      "storeys/storey_01.ply", "storeys.json"}));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "storeys/storey_07.las"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "storeys/notes.txt"));
  std::size_t storey1 = 0;
  for (std::int16_t s : cloud.storey) storey1 += s == 1;
  EXPECT_EQ(eval::readPlyPoints((dir.path() / "storeys/storey_01.ply").string()).positions.size(),
            storey1);
}

}  // namespace
}  // namespace storey
