#include "io/pcd_folder_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/log.h"
#include "io/imu_csv.h"
#include "io/message_sequencer.h"
#include "io/pcd_file.h"
#include "io/point_cloud_to_scan.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

/// Scans whose file names look like indices (all stamps below this) have no real times.
constexpr std::int64_t kIndexLikeNs = 100'000LL * 1'000'000'000LL;
constexpr std::int64_t kCsvLeadNs = 200'000'000;
constexpr std::int64_t kCsvBeforeLogNs = 2'000'000'000;

bool hasPcdExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".pcd";
}

}  // namespace

bool stampFromFileName(const std::string& file_name, std::int64_t& stamp_ns) {
  const std::string stem = fs::path(file_name).stem().string();
  // The last run of digits, with an optional decimal part.
  std::size_t end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  if (end == 0) return false;
  std::size_t begin = end;
  while (begin > 0 &&
         (std::isdigit(static_cast<unsigned char>(stem[begin - 1])) || stem[begin - 1] == '.')) {
    --begin;
  }
  std::string number = stem.substr(begin, end - begin);
  while (!number.empty() && number.front() == '.') number.erase(number.begin());
  if (number.empty() || std::count(number.begin(), number.end(), '.') > 1) return false;
  if (number.find('.') != std::string::npos) return parseSecondsToNs(number, stamp_ns);
  const std::size_t digits = number.size();
  std::int64_t value = 0;
  if (digits > 19) return false;
  for (char c : number) value = value * 10 + (c - '0');
  if (digits >= 18)
    stamp_ns = value;
  else if (digits >= 15)
    stamp_ns = value * 1000;
  else if (digits >= 12)
    stamp_ns = value * 1'000'000;
  else
    stamp_ns = value * 1'000'000'000;
  return true;
}

std::vector<PcdScanEntry> findPcdScans(const std::string& folder) {
  std::vector<PcdScanEntry> scans;
  const fs::path list = fs::path(folder) / kPcdListFile;
  if (fs::exists(list)) {
    std::ifstream in(list);
    if (!in) throw Error(list.string() + ": cannot open the list file");
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      std::istringstream words(line);
      std::string a, b;
      if (!(words >> a) || a[0] == '#') continue;
      if (!(words >> b)) {
        throw Error(list.string() + ": line " + std::to_string(line_number) +
                    ": expected '<file> <time in seconds>'");
      }
      if (hasPcdExtension(a) == false && hasPcdExtension(b)) std::swap(a, b);
      PcdScanEntry entry;
      if (!parseSecondsToNs(b, entry.stamp_ns)) {
        throw Error(list.string() + ": line " + std::to_string(line_number) + ": time '" + b +
                    "' is not a decimal number of seconds");
      }
      entry.path = (fs::path(folder) / a).string();
      if (!fs::exists(entry.path)) {
        throw Error(list.string() + ": line " + std::to_string(line_number) + ": no file " +
                    entry.path);
      }
      scans.push_back(entry);
    }
    if (scans.empty()) throw Error(list.string() + ": lists no scan");
  } else {
    std::error_code ec;
    for (const auto& item : fs::directory_iterator(folder, ec)) {
      if (!item.is_regular_file() || !hasPcdExtension(item.path())) continue;
      PcdScanEntry entry;
      entry.path = item.path().string();
      if (!stampFromFileName(item.path().filename().string(), entry.stamp_ns)) {
        throw Error(entry.path +
                    ": no time in the file name; name the scans by their time "
                    "(e.g. 1673400471.737763.pcd) or list them in " +
                    list.string());
      }
      scans.push_back(entry);
    }
    if (ec) throw Error(folder + ": cannot list the folder: " + ec.message());
    if (scans.empty()) {
      throw Error(folder + ": is a directory without PCD scans (*.pcd) or " + kPcdListFile +
                  ", not a log");
    }
    const bool index_like = std::all_of(scans.begin(), scans.end(), [](const PcdScanEntry& e) {
      return e.stamp_ns < kIndexLikeNs;
    });
    if (index_like && scans.size() > 1) {
      bool consecutive = true;
      std::vector<std::int64_t> v;
      for (const auto& s : scans) v.push_back(s.stamp_ns / 1'000'000'000);
      std::sort(v.begin(), v.end());
      for (std::size_t i = 1; i < v.size(); ++i) consecutive = consecutive && v[i] == v[i - 1] + 1;
      if (consecutive) {
        throw Error(folder +
                    ": the PCD file names are scan numbers, not times; list the scans "
                    "with their times in " +
                    list.string() + " ('<file> <seconds>' per line)");
      }
    }
  }
  std::stable_sort(scans.begin(), scans.end(), [](const PcdScanEntry& a, const PcdScanEntry& b) {
    return a.stamp_ns < b.stamp_ns;
  });
  // The first file's content must be a PCD.
  readPcdHeader(scans.front().path);
  return scans;
}

std::string pcdFolderImuCsv(const std::string& folder, const InputConfig& input) {
  if (!input.imu_csv.empty()) return input.imu_csv;
  const fs::path alongside = fs::path(folder) / kPcdFolderImuCsv;
  return fs::exists(alongside) ? alongside.string() : std::string();
}

namespace {

class PcdFolderReader final : public LogReader {
 public:
  PcdFolderReader(const std::string& folder, const InputConfig& input, const SensorConfig& sensor,
                  bool require_imu)
      : folder_(folder),
        scans_(findPcdScans(folder)),
        clouds_("PCD folder", sensor.lidar_model, PointFilter{input.min_range, input.max_range}),
        sequencer_(sequencerOptions(sensor), stats_),
        lidar_to_imu_ns_(secondsToNs(sensor.time_offset_lidar_to_imu)) {
    const std::string csv = pcdFolderImuCsv(folder, input);
    if (!csv.empty()) {
      csv_ = std::make_unique<ImuCsvReader>(csv, secondsToNs(input.imu_csv_time_offset));
    } else if (require_imu) {
      throw Error(folder + ": no IMU: put the IMU CSV in the folder as " + kPcdFolderImuCsv +
                  " or give it with input.imu_csv (--imu-csv)");
    }
  }

  bool next(LogMessage& message) override {
    while (!sequencer_.pop(message)) {
      if (ended_) return false;
      if (next_scan_ >= scans_.size()) {
        ended_ = true;
        if (csv_ && !scans_.empty()) {
          feedCsv(scans_.back().stamp_ns + lidar_to_imu_ns_ + kCsvLeadNs + 1'000'000'000);
          if (csv_->badLines() > 0) stats_.dropped[kDropImuCsvBadLine] = csv_->badLines();
        }
        sequencer_.finish();
        continue;
      }
      readScan(scans_[next_scan_++]);
    }
    return true;
  }

  const LogReadStats& stats() const override { return stats_; }
  std::string describe() const override {
    return "PCD folder " + folder_ + " (" + std::to_string(scans_.size()) +
           " scans, IMU: " + (csv_ ? csv_->path() : std::string("none")) + ")";
  }
  double progress() const override {
    return scans_.empty() ? 1.0
                          : static_cast<double>(next_scan_) / static_cast<double>(scans_.size());
  }

 private:
  static MessageSequencer::Options sequencerOptions(const SensorConfig& sensor) {
    MessageSequencer::Options o;
    o.lidar_to_imu_offset_ns = secondsToNs(sensor.time_offset_lidar_to_imu);
    return o;
  }

  void readScan(const PcdScanEntry& entry) {
    const PcdCloud cloud = readPcd(entry.path);
    Scan scan;
    try {
      scan = clouds_.convert(cloud.view(), entry.stamp_ns, "pcd", stats_.dropped);
    } catch (const Error& e) {
      throw Error(entry.path + ": " + e.what());
    }
    if (csv_) feedCsv(entry.stamp_ns + lidar_to_imu_ns_ + kCsvLeadNs);
    sequencer_.push(std::move(scan));
  }

  void feedCsv(std::int64_t until_ns) {
    if (!have_sample_ && !csv_done_) {
      have_sample_ = csv_->next(sample_);
      csv_done_ = !have_sample_;
    }
    while (have_sample_ && sample_.stamp_ns <= until_ns) {
      if (pushed_ == 0 && sample_.stamp_ns < scans_.front().stamp_ns - kCsvBeforeLogNs) {
        ++stats_.dropped["imu_csv_before_log"];
      } else {
        sequencer_.push(sample_);
        ++pushed_;
      }
      have_sample_ = csv_->next(sample_);
      csv_done_ = !have_sample_;
    }
  }

  std::string folder_;
  std::vector<PcdScanEntry> scans_;
  PointCloudToScan clouds_;
  LogReadStats stats_;
  MessageSequencer sequencer_;
  std::int64_t lidar_to_imu_ns_;
  std::unique_ptr<ImuCsvReader> csv_;
  std::size_t next_scan_ = 0;
  bool ended_ = false;
  ImuSample sample_;
  bool have_sample_ = false;
  bool csv_done_ = false;
  std::int64_t pushed_ = 0;
};

}  // namespace

std::unique_ptr<LogReader> openPcdFolderLog(const std::string& folder, const InputConfig& input,
                                            const SensorConfig& sensor, bool require_imu) {
  return std::make_unique<PcdFolderReader>(folder, input, sensor, require_imu);
}

}  // namespace storey
