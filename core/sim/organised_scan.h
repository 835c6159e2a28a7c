#pragma once
/// A scan as an organised sensor (Ouster) reports it: every beam of every
/// column, no-returns included.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace storey::sim {

/// One cell (the Ouster driver's point): a no-return is all zeros but its time.
struct OrganisedPoint {
  Eigen::Vector3f p = Eigen::Vector3f::Zero();  ///< LiDAR frame [m]
  float intensity = 0.0f;                       ///< signal [0, 255]
  std::uint32_t t_ns = 0;                       ///< column time after the scan's stamp [ns]
  std::uint16_t reflectivity = 0;               ///< the surface's reflectivity [0, 255]
  std::uint32_t range_mm = 0;                   ///< [mm]
};

/// `rows` beams (row 0 = the top beam) x `columns` columns (firing order), row-major.
struct OrganisedScan {
  int rows = 0;
  int columns = 0;
  std::vector<OrganisedPoint> cells;
  const OrganisedPoint& at(int row, int column) const {
    return cells[static_cast<std::size_t>(row) * columns + column];
  }
};

}  // namespace storey::sim
