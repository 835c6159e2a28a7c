#include "sim/imu_csv_writer.h"

#include <cerrno>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "common/error.h"

namespace storey::sim {
namespace {

void appendDouble(std::string& line, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);  // shortest round trip
  line.append(buffer, result.ptr);
}

}  // namespace

std::string imuCsvLine(const ImuSample& sample) {
  std::string line;
  line.reserve(160);
  const std::int64_t ns = sample.stamp_ns;
  const std::uint64_t magnitude =
      ns < 0 ? 0 - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  char stamp[40];
  std::snprintf(stamp, sizeof(stamp), "%s%" PRIu64 ".%09" PRIu64, ns < 0 ? "-" : "",
                magnitude / 1'000'000'000u, magnitude % 1'000'000'000u);
  line += stamp;
  for (int i = 0; i < 3; ++i) {
    line += ',';
    appendDouble(line, sample.gyro[i]);
  }
  for (int i = 0; i < 3; ++i) {
    line += ',';
    appendDouble(line, sample.accel[i]);
  }
  return line;
}

void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples,
                 std::int64_t stamp_offset_ns, const std::vector<std::string>& comment) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  std::setvbuf(file, nullptr, _IOFBF, 1 << 20);
  std::string text;
  for (const std::string& line : comment) text += "# " + line + "\n";
  text += "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  for (std::size_t i = 0; ok && i < samples.size(); ++i) {
    ImuSample sample = samples[i];
    sample.stamp_ns += stamp_offset_ns;
    text = imuCsvLine(sample);
    text += '\n';
    ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  }
  const int saved_errno = errno;
  ok = std::fclose(file) == 0 && ok;
  if (!ok)
    throw Error(path + ": cannot write: " + std::strerror(saved_errno ? saved_errno : errno));
}

}  // namespace storey::sim
