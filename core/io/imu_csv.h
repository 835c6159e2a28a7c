#pragma once
/// IMU samples from a CSV file (see docs/formats.md, "Input: IMU CSV"):
///   # comment lines start with '#'
///   time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z      (optional header)
///   1673400471.737763,0.001,-0.002,0.010,0.12,-0.05,9.80
/// Separators: comma, semicolon, tab or spaces. Without a header the columns
/// are in the order above. Time: seconds (decimal, any epoch; read exactly to
/// the nanosecond), or integer nanoseconds when the time column is named
/// time_ns / stamp_ns / timestamp_ns. Gyro in rad/s (deg/s when the columns
/// end in _dps), acceleration in m/s^2 (g when they end in _g), in the IMU frame.
/// A constant offset is added to every stamp (the LiDAR clock minus the CSV clock).
#include <cstdint>
#include <fstream>
#include <string>

#include "types/imu_sample.h"

namespace storey {

/// Key of LogReadStats::dropped for lines of an IMU CSV that could not be read.
inline constexpr const char* kDropImuCsvBadLine = "imu_csv_bad_line";

class ImuCsvReader {
 public:
  /// Opens the file and reads its header. Throws storey::Error naming the file
  /// when it cannot be opened, its header lacks a needed column, or it holds no sample.
  ImuCsvReader(const std::string& path, std::int64_t offset_ns);

  /// Next sample in file order; false at the end. Lines that cannot be read
  /// are skipped, counted (badLines) and the first few named in a warning.
  bool next(ImuSample& sample);

  std::int64_t badLines() const { return bad_lines_; }
  std::int64_t samples() const { return samples_; }
  const std::string& path() const { return path_; }
  /// Fraction of the file read [0, 1].
  double progress() const;

 private:
  bool parseLine(const std::string& line, ImuSample& sample, std::string& why) const;

  std::string path_;
  std::ifstream in_;
  std::int64_t offset_ns_;
  std::int64_t line_number_ = 0;
  std::int64_t bad_lines_ = 0;
  std::int64_t samples_ = 0;
  std::uint64_t size_ = 0;
  int column_[7] = {0, 1, 2, 3, 4, 5, 6};  ///< time, gx, gy, gz, ax, ay, az -> column index
  bool time_in_ns_ = false;
  double gyro_scale_ = 1.0;   ///< to rad/s
  double accel_scale_ = 1.0;  ///< to m/s^2
  std::string pending_;       ///< first data line, read while looking for the header
  bool have_pending_ = false;
};

/// Parses a decimal number of seconds ("1673400471.737763", "-0.5", "12")
/// exactly into nanoseconds; false when `text` is not such a number.
bool parseSecondsToNs(const std::string& text, std::int64_t& ns);

}  // namespace storey
