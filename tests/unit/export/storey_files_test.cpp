// One file per storey (core/export/storey_files.h), what the plugin's "Export
// storeys" writes: names, order, the points of each storey read back (PLY by
// core/eval's reader, LAS point count and storey field from the header and
// records), and the error on a map without storey labels.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "eval/ply_reader.h"
#include "export/storey_files.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

/// Five points: storey 0 at x = 0 and 1, unlabelled at x = 2, storey 3 at
/// x = 3 and 4 (indices need not be contiguous).
MapCloud fivePoints() {
  MapCloud m;
  const std::int16_t storeys[5] = {0, 0, kNoStorey, 3, 3};
  for (int i = 0; i < 5; ++i) {
    m.positions.emplace_back(static_cast<float>(i), 0.f, storeys[i] == 3 ? 3.f : 0.f);
    m.intensity.push_back(10.f * static_cast<float>(i));
    m.time.push_back(100.0 + i);
    m.keyframe.push_back(i);
    m.storey.push_back(storeys[i]);
    m.flags.push_back(0);
  }
  return m;
}

std::vector<char> bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename T>
T at(const std::vector<char>& data, std::size_t offset) {
  T v{};
  EXPECT_LE(offset + sizeof(T), data.size());
  if (offset + sizeof(T) <= data.size()) std::memcpy(&v, data.data() + offset, sizeof(T));
  return v;
}

/// LAS 1.4 (ASPRS R15): point count (uint64 at 247), offset to the points
/// (uint32 at 96), record length (uint16 at 105); our storey extra byte field
/// is the int16 at byte 30 of a record.
std::vector<std::int16_t> lasStoreys(const std::string& path) {
  const std::vector<char> f = bytes(path);
  EXPECT_EQ(std::string(f.data(), f.size() < 4 ? f.size() : 4), "LASF") << path;
  const auto count = at<std::uint64_t>(f, 247);
  const auto offset = at<std::uint32_t>(f, 96);
  const auto length = at<std::uint16_t>(f, 105);
  std::vector<std::int16_t> storeys;
  for (std::uint64_t k = 0; k < count; ++k)
    storeys.push_back(at<std::int16_t>(f, offset + k * length + 30));
  return storeys;
}

TEST(StoreyFiles, OneFilePerStoreyWithItsPoints) {
  test::TempDir dir;
  const std::string out = dir.file("a/b");  // created, parents too
  StoreyFileFormats formats;
  formats.ply = true;
  const std::vector<std::string> files = writeStoreyFiles(fivePoints(), out, formats);
  const std::vector<std::string> expected = {out + "/storey_00.las", out + "/storey_00.ply",
                                             out + "/storey_03.las", out + "/storey_03.ply"};
  EXPECT_EQ(files, expected);
  EXPECT_EQ(std::distance(fs::directory_iterator(out), {}), 4) << "only those files";

  const eval::PlyPoints ply0 = eval::readPlyPoints(out + "/storey_00.ply");
  ASSERT_EQ(ply0.positions.size(), 2u);
  EXPECT_DOUBLE_EQ(ply0.positions[0].x(), 0.0);
  EXPECT_DOUBLE_EQ(ply0.positions[1].x(), 1.0);
  const eval::PlyPoints ply3 = eval::readPlyPoints(out + "/storey_03.ply");
  ASSERT_EQ(ply3.positions.size(), 2u);
  EXPECT_DOUBLE_EQ(ply3.positions[0].x(), 3.0);
  EXPECT_DOUBLE_EQ(ply3.positions[1].z(), 3.0);

  EXPECT_EQ(lasStoreys(out + "/storey_00.las"), (std::vector<std::int16_t>{0, 0}));
  EXPECT_EQ(lasStoreys(out + "/storey_03.las"), (std::vector<std::int16_t>{3, 3}));
}

TEST(StoreyFiles, LasOnlyByDefault) {
  test::TempDir dir;
  const std::vector<std::string> files = writeStoreyFiles(fivePoints(), dir.file("out"), {});
  EXPECT_EQ(files, (std::vector<std::string>{dir.file("out/storey_00.las"),
                                             dir.file("out/storey_03.las")}));
  EXPECT_FALSE(fs::exists(dir.file("out/storey_00.ply")));
}

TEST(StoreyFiles, IndicesAndPointsOfAStorey) {
  const MapCloud m = fivePoints();
  EXPECT_EQ(storeyIndices(m), (std::vector<int>{0, 3}));
  EXPECT_EQ(pointsOfStorey(m, 3), (std::vector<std::uint32_t>{3, 4}));
  EXPECT_TRUE(pointsOfStorey(m, 1).empty());
}

TEST(StoreyFiles, MapWithoutStoreysIsAnError) {
  test::TempDir dir;
  MapCloud m = fivePoints();
  for (auto& s : m.storey) s = kNoStorey;
  try {
    writeStoreyFiles(m, dir.file("out"), {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no storey labels"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.file("out"))) << "nothing is written";
}

}  // namespace
}  // namespace storey
