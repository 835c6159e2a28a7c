#include "io/imu_csv.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <vector>

#include "common/error.h"
#include "common/log.h"

namespace storey {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kStandardGravity = 9.80665;
constexpr int kNamedBadLines = 3;

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string current;
  bool in_field = false;
  const bool has_delimiter = line.find_first_of(",;\t") != std::string::npos;
  for (char c : line) {
    const bool delimiter = has_delimiter ? (c == ',' || c == ';' || c == '\t') : c == ' ';
    if (delimiter) {
      fields.push_back(current);
      current.clear();
      in_field = false;
    } else if (!(std::isspace(static_cast<unsigned char>(c)))) {
      current += c;
      in_field = true;
    }
  }
  if (in_field || !current.empty() || has_delimiter) fields.push_back(current);
  if (!has_delimiter) {
    fields.erase(std::remove(fields.begin(), fields.end(), std::string()), fields.end());
  }
  return fields;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool parseDouble(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

}  // namespace

bool parseSecondsToNs(const std::string& text, std::int64_t& ns) {
  std::size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '-' || text[i] == '+')) negative = text[i++] == '-';
  // whole * 1e9 + fraction must fit in int64 (about 292 years of nanoseconds).
  constexpr std::int64_t kMaxWholeSeconds = 9'223'372'035;
  std::int64_t whole = 0, fraction = 0;
  int digits = 0, fraction_digits = 0;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i, ++digits) {
    if (whole > kMaxWholeSeconds) return false;
    whole = whole * 10 + (text[i] - '0');
  }
  if (whole > kMaxWholeSeconds) return false;
  if (i < text.size() && text[i] == '.') {
    for (++i; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
      if (fraction_digits < 9) {
        fraction = fraction * 10 + (text[i] - '0');
        ++fraction_digits;
      }
      ++digits;
    }
  }
  if (digits == 0 || i != text.size()) return false;
  for (int k = fraction_digits; k < 9; ++k) fraction *= 10;
  ns = whole * 1'000'000'000 + fraction;
  if (negative) ns = -ns;
  return true;
}

ImuCsvReader::ImuCsvReader(const std::string& path, std::int64_t offset_ns)
    : path_(path), in_(path, std::ios::binary), offset_ns_(offset_ns) {
  if (!in_) throw Error(path + ": cannot open the IMU CSV file");
  std::error_code ec;
  size_ = std::filesystem::file_size(path, ec);
  std::string line;
  while (std::getline(in_, line)) {
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto fields = splitFields(line);
    double number;
    std::int64_t ns;
    if (!fields.empty() && (parseSecondsToNs(fields[0], ns) || parseDouble(fields[0], number))) {
      pending_ = line;  // no header: the default column order
      have_pending_ = true;
      --line_number_;
      break;
    }
    // A header: find the columns by name.
    const std::vector<std::vector<std::string>> names = {
        {"time", "t", "timestamp", "stamp", "time_s", "time_ns", "stamp_ns", "timestamp_ns"},
        {"gyro_x", "gx", "wx", "angular_velocity_x", "gyro_x_dps"},
        {"gyro_y", "gy", "wy", "angular_velocity_y", "gyro_y_dps"},
        {"gyro_z", "gz", "wz", "angular_velocity_z", "gyro_z_dps"},
        {"accel_x", "ax", "acc_x", "linear_acceleration_x", "accel_x_g"},
        {"accel_y", "ay", "acc_y", "linear_acceleration_y", "accel_y_g"},
        {"accel_z", "az", "acc_z", "linear_acceleration_z", "accel_z_g"}};
    for (std::size_t q = 0; q < names.size(); ++q) {
      column_[q] = -1;
      for (std::size_t c = 0; c < fields.size(); ++c) {
        const std::string name = lower(fields[c]);
        if (std::find(names[q].begin(), names[q].end(), name) != names[q].end()) {
          column_[q] = static_cast<int>(c);
          if (q == 0) time_in_ns_ = name.size() > 3 && name.substr(name.size() - 3) == "_ns";
          if (q >= 1 && q <= 3 && name.size() > 4 && name.substr(name.size() - 4) == "_dps") {
            gyro_scale_ = kPi / 180.0;
          }
          if (q >= 4 && name.size() > 2 && name.substr(name.size() - 2) == "_g") {
            accel_scale_ = kStandardGravity;
          }
          break;
        }
      }
      if (column_[q] < 0) {
        throw Error(path + ": line " + std::to_string(line_number_) + ": header '" + line +
                    "' lacks a column for " + names[q][0] +
                    " (expected: time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z)");
      }
    }
    break;
  }
  ImuSample probe;
  std::string why;
  if (!have_pending_) {
    // Header read: the first data line must follow.
    while (std::getline(in_, line)) {
      ++line_number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '#') continue;
      pending_ = line;
      have_pending_ = true;
      --line_number_;
      break;
    }
  }
  if (!have_pending_) throw Error(path + ": the IMU CSV file holds no sample");
}

bool ImuCsvReader::parseLine(const std::string& line, ImuSample& sample, std::string& why) const {
  const auto fields = splitFields(line);
  const int needed = *std::max_element(std::begin(column_), std::end(column_)) + 1;
  if (static_cast<int>(fields.size()) < needed) {
    why = std::to_string(fields.size()) + " columns, expected " + std::to_string(needed);
    return false;
  }
  std::int64_t stamp = 0;
  const std::string& t = fields[column_[0]];
  if (time_in_ns_) {
    char* end = nullptr;
    stamp = std::strtoll(t.c_str(), &end, 10);
    if (t.empty() || end != t.c_str() + t.size()) {
      why = "time '" + t + "' is not an integer number of nanoseconds";
      return false;
    }
  } else if (!parseSecondsToNs(t, stamp)) {
    why = "time '" + t + "' is not a decimal number of seconds";
    return false;
  }
  double v[6];
  for (int k = 0; k < 6; ++k) {
    if (!parseDouble(fields[column_[k + 1]], v[k])) {
      why = "value '" + fields[column_[k + 1]] + "' is not a finite number";
      return false;
    }
  }
  if (__builtin_add_overflow(stamp, offset_ns_, &sample.stamp_ns)) {
    why = "time '" + t + "' plus the offset is beyond the nanosecond range";
    return false;
  }
  sample.gyro = Eigen::Vector3d(v[0], v[1], v[2]) * gyro_scale_;
  sample.accel = Eigen::Vector3d(v[3], v[4], v[5]) * accel_scale_;
  return true;
}

bool ImuCsvReader::next(ImuSample& sample) {
  std::string line;
  for (;;) {
    if (have_pending_) {
      line = pending_;
      have_pending_ = false;
    } else if (!std::getline(in_, line)) {
      return false;
    }
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::string why;
    if (parseLine(line, sample, why)) {
      ++samples_;
      return true;
    }
    if (++bad_lines_ <= kNamedBadLines) {
      logWarning(path_ + ": line " + std::to_string(line_number_) + " skipped: " + why);
    }
  }
}

double ImuCsvReader::progress() const {
  if (size_ == 0) return 0.0;
  auto& stream = const_cast<std::ifstream&>(in_);
  const auto at = stream.tellg();
  if (at < 0) return 1.0;
  return std::min(1.0, static_cast<double>(at) / static_cast<double>(size_));
}

}  // namespace storey
