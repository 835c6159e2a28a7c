#pragma once
/// A small reader for the PLY files `storey eval` compares: the true building
/// mesh (as the simulator writes it: vertex x y z, face vertex_indices, optional
/// per-face `returns`) and the map (a point cloud: vertex x y z at least, any
/// other properties ignored). Formats ascii, binary_little_endian and
/// binary_big_endian; scalar types char/uchar/short/ushort/int/uint/float/double
/// and their int8..float64 aliases; list properties anywhere. Errors name the
/// file and the header line or the element record where reading failed.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace storey::eval {

struct PlyMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< polygons are split into fans
  std::size_t faces_read = 0;                           ///< face records in the file
  std::size_t faces_not_returning = 0;  ///< left out: `returns` is 0 (glass) and returning_only
  std::size_t faces_degenerate = 0;     ///< left out: fewer than 3 vertices
};

struct PlyPoints {
  std::vector<Eigen::Vector3d> positions;  ///< finite points only
  std::size_t non_finite = 0;              ///< vertices with a NaN/inf coordinate, left out
};

/// Reads a triangle mesh. With returning_only, faces whose `returns` property
/// is 0 are left out (the simulator marks glass so: the LiDAR sees through it).
PlyMesh readPlyMesh(const std::string& path, bool returning_only = true);
/// Reads the vertices of a PLY file as points (faces, if any, are ignored).
PlyPoints readPlyPoints(const std::string& path);

/// Every vertex of a PLY file in file order (non-finite ones too) with the
/// named scalar vertex properties, one column per name in the given order.
struct PlyVertexColumns {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::vector<double>> columns;
};
/// Throws storey::Error naming the file and the property when one of `names`
/// is missing or a list.
PlyVertexColumns readPlyVertexColumns(const std::string& path,
                                      const std::vector<std::string>& names);

}  // namespace storey::eval
