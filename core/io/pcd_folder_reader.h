#pragma once
/// LogReader for a folder of PCD scans (see docs/formats.md, "Input: PCD
/// folder"): one PCD file per scan in the LiDAR frame, each scan's time from
/// a list file (timestamps.txt: "<file> <time>" per line) or from the number in
/// its file name; per-point time from a time field when present (time, t,
/// timestamp, offset_time as for ROS clouds), else from the azimuth; IMU from
/// input.imu_csv or the folder's imu.csv.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/input_config.h"
#include "io/log_reader.h"
#include "types/sensor.h"

namespace storey {

/// Name of the optional list file and of the IMU CSV looked for in the folder.
inline constexpr const char* kPcdListFile = "timestamps.txt";
inline constexpr const char* kPcdFolderImuCsv = "imu.csv";

struct PcdScanEntry {
  std::string path;
  std::int64_t stamp_ns = 0;
};

/// The folder's scans in time order with their stamps. Throws storey::Error
/// naming the folder (and the list file line) when it holds no PCD scan, a
/// listed file is missing, or a time cannot be found.
std::vector<PcdScanEntry> findPcdScans(const std::string& folder);

/// Stamp from a file name: the last number in the stem. With a decimal point
/// it is seconds; an integer is read by its digits: >= 18 ns, 15..17 us,
/// 12..14 ms, else seconds. False when the stem holds no number.
bool stampFromFileName(const std::string& file_name, std::int64_t& stamp_ns);

/// The IMU CSV a PCD folder run uses: input.imu_csv, else <folder>/imu.csv if
/// it exists, else empty.
std::string pcdFolderImuCsv(const std::string& folder, const InputConfig& input);

/// Opens the folder as a LogReader. `require_imu` false allows a folder
/// without IMU (scans only, e.g. for summaries).
std::unique_ptr<LogReader> openPcdFolderLog(const std::string& folder, const InputConfig& input,
                                            const SensorConfig& sensor, bool require_imu = true);

}  // namespace storey
