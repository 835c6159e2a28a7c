// The PLY reader: ASCII and binary meshes and clouds, the simulator's mesh,
// and clear errors on truncated or foreign files.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "eval/ply_reader.h"
#include "sim/mesh.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

using test::eval::readText;
using test::eval::writeText;

class EvalPly : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::eval::makeTempDir("ply"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
};

template <typename T>
void append(std::string& bytes, T value, bool big_endian = false) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  bytes.append(raw, sizeof(T));
}

/// Binary cloud: x y z float, intensity ushort, storey uchar.
std::string binaryCloud(const std::vector<Eigen::Vector3d>& points, bool big_endian) {
  std::string bytes = std::string("ply\nformat ") +
                      (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\ncomment test cloud\nelement vertex " + std::to_string(points.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "property ushort intensity\nproperty uchar storey\nend_header\n";
  for (const Eigen::Vector3d& p : points) {
    for (int k = 0; k < 3; ++k) append<float>(bytes, static_cast<float>(p[k]), big_endian);
    append<std::uint16_t>(bytes, 1234, big_endian);
    append<std::uint8_t>(bytes, 2, big_endian);
  }
  return bytes;
}

const std::vector<Eigen::Vector3d> kPoints = {{0.5, -1.25, 3.0}, {1e3, 2.5, -0.125}, {0, 0, 0}};

TEST_F(EvalPly, ReadsBinaryCloudsOfEitherByteOrder) {
  for (bool big : {false, true}) {
    writeText(path("cloud.ply"), binaryCloud(kPoints, big));
    const PlyPoints cloud = readPlyPoints(path("cloud.ply"));
    ASSERT_EQ(cloud.positions.size(), kPoints.size()) << big;
    for (std::size_t i = 0; i < kPoints.size(); ++i)
      EXPECT_TRUE(cloud.positions[i].isApprox(kPoints[i])) << i;  // exact in float
  }
}

TEST_F(EvalPly, ReadsAsciiCloudsWithDoublesAndCountsNonFinitePoints) {
  writeText(
      path("cloud.ply"),
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\nproperty double y\r\n"
      "property double z\r\nproperty int label\r\nend_header\r\n"
      "0.1 0.2 0.3 7\r\n1e-3 -2 4.5 -1\r\nnan 0 0 0\r\n");
  const PlyPoints cloud = readPlyPoints(path("cloud.ply"));
  ASSERT_EQ(cloud.positions.size(), 2u);
  EXPECT_EQ(cloud.non_finite, 1u);
  EXPECT_TRUE(cloud.positions[1].isApprox(Eigen::Vector3d(1e-3, -2, 4.5)));
}

TEST_F(EvalPly, ReadsTheSimulatorsMeshWithoutItsGlass) {
  sim::TriangleMesh mesh;
  mesh.addBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3), sim::Surface::kWall);
  mesh.addQuad({5, 0, 0}, {6, 0, 0}, {6, 0, 1}, {5, 0, 1}, sim::Surface::kGlass, 0.0f);
  mesh.writePly(path("building.ply"));

  const PlyMesh returning = readPlyMesh(path("building.ply"));
  EXPECT_EQ(returning.vertices.size(), mesh.vertices().size());
  EXPECT_EQ(returning.faces_read, 14u);
  EXPECT_EQ(returning.faces_not_returning, 2u);
  ASSERT_EQ(returning.triangles.size(), 12u);
  for (std::size_t i = 0; i < 12; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(returning.triangles[i][k], mesh.triangles()[i].v[k]);
  EXPECT_EQ(readPlyMesh(path("building.ply"), false).triangles.size(), 14u);
}

TEST_F(EvalPly, SplitsPolygonsIntoFans) {
  writeText(path("quad.ply"),
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const PlyMesh mesh = readPlyMesh(path("quad.ply"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

/// Expects readPlyPoints(file) to throw a storey::Error naming the file and `what`.
void expectError(const std::string& file, const std::string& what, bool mesh = false) {
  try {
    if (mesh)
      readPlyMesh(file);
    else
      readPlyPoints(file);
    FAIL() << "expected storey::Error for " << file;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_F(EvalPly, TruncatedFilesAreErrorsNamingTheRecord) {
  const std::string full = binaryCloud(kPoints, false);
  writeText(path("cut.ply"), full.substr(0, full.size() - 5));  // into the last record
  expectError(path("cut.ply"), "truncated or malformed in element 'vertex' record 2 of 3");

  const std::string header_only = full.substr(0, full.find("end_header"));
  writeText(path("header.ply"), header_only);
  expectError(path("header.ply"), "file ends before 'end_header'");

  writeText(path("ascii.ply"),
            "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n1 2 3\n4 5\n");
  expectError(path("ascii.ply"), "record 1 of 2, property 'z'");

  // A corrupt count: no huge allocation, the error names the record where the data ends.
  writeText(path("count.ply"),
            "ply\nformat ascii 1.0\nelement vertex 4000000000000\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n1 2 3\n");
  expectError(path("count.ply"), "record 1 of 4000000000000, property 'x'");

  sim::TriangleMesh mesh;
  mesh.addBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), sim::Surface::kWall);
  mesh.writePly(path("mesh.ply"));
  const std::string bytes = readText(path("mesh.ply"));
  writeText(path("mesh_cut.ply"), bytes.substr(0, bytes.size() - 10));
  expectError(path("mesh_cut.ply"), "element 'face' record 11 of 12", true);
}

TEST_F(EvalPly, ForeignOrBrokenFilesAreClearErrors) {
  expectError(path("missing.ply"), "cannot open");
  writeText(path("empty.ply"), "");
  expectError(path("empty.ply"), "empty file");
  writeText(path("obj.ply"), "v 0 0 0\n");
  expectError(path("obj.ply"), "not a PLY file");
  writeText(path("format.ply"), "ply\nformat binary_middle_endian 1.0\nend_header\n");
  expectError(path("format.ply"), "header line 2: unknown format 'binary_middle_endian'");
  writeText(path("type.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n");
  expectError(path("type.ply"), "header line 4: unknown type 'half'");
  writeText(path("noz.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
            "y\nend_header\n1 2\n");
  expectError(path("noz.ply"), "no property 'z'");
  writeText(path("noface.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n1 2 3\n");
  expectError(path("noface.ply"), "no 'face' element", true);
  writeText(path("index.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n");
  expectError(path("index.ply"), "face 0 refers to vertex 3 of 3", true);
}

TEST_F(EvalPly, AnElementDeclaredTwiceIsAnError) {
  // Found by the fuzz smoke of CI (tests/data/fuzz/ply): the second 'vertex'
  // (one property) was read with the first one's x y z indexes, past the end
  // of its values (heap overflow). The header is refused, naming the line.
  writeText(path("twice.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
            "property float z\nelement vertex 1\nproperty float x\nend_header\n1 2 3\n4\n");
  try {
    readPlyPoints(path("twice.ply"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("element 'vertex' declared twice"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace storey::eval
