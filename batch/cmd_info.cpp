// `storey info LOG`: what a log holds, topic by topic, as readable tables.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "io/log_summary.h"
#include "io/ros_messages.h"
#include "options_config.h"

namespace storey::cli {
namespace {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string stampText(std::int64_t ns) {
  return fixed(static_cast<double>(ns) * 1e-9, 6);
}

std::string bytesText(std::uint64_t bytes) {
  if (bytes >= (1ull << 30)) return fixed(bytes / double(1ull << 30), 2) + " GiB";
  if (bytes >= (1ull << 20)) return fixed(bytes / double(1ull << 20), 2) + " MiB";
  if (bytes >= (1ull << 10)) return fixed(bytes / double(1ull << 10), 2) + " KiB";
  return std::to_string(bytes) + " B";
}

/// A text table: columns padded to their widest cell, numbers right-aligned.
class Table {
 public:
  Table(std::vector<std::string> header, std::vector<bool> right_aligned)
      : rows_{std::move(header)}, right_(std::move(right_aligned)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void print(std::ostream& out, const std::string& indent) const {
    std::vector<std::size_t> width(right_.size(), 0);
    for (const auto& row : rows_) {
      for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    }
    for (const auto& row : rows_) {
      std::string line = indent;
      for (std::size_t c = 0; c < row.size(); ++c) {
        const std::string pad(width[c] - row[c].size(), ' ');
        line += right_[c] ? pad + row[c] : row[c] + (c + 1 < row.size() ? pad : "");
        if (c + 1 < row.size()) line += "  ";
      }
      out << line << '\n';
    }
  }

 private:
  std::vector<std::vector<std::string>> rows_;
  std::vector<bool> right_;
};

void printTopics(const LogSummary& summary, std::ostream& out) {
  Table table(
      {"topic", "type", "messages", "rate Hz", "duration s", "first stamp", "last stamp", "stamps"},
      {false, false, true, true, true, true, true, false});
  for (const auto& t : summary.topics) {
    table.add({t.name, t.type, std::to_string(t.count), fixed(t.rateHz(), 2),
               fixed(t.durationSeconds(), 3), stampText(t.first_stamp_ns),
               stampText(t.last_stamp_ns), t.header_stamps ? "header" : "record"});
  }
  table.print(out, "  ");
}

void printCloudTopic(const TopicSummary& t, std::ostream& out) {
  out << "\nPoint cloud " << t.name << ": point_step " << t.point_step
      << " bytes; points per message"
      << " min " << t.points_min << ", median " << t.points_median << ", max " << t.points_max
      << '\n';
  Table table({"field", "datatype", "offset", "count"}, {false, false, true, true});
  for (const auto& f : t.fields) {
    table.add({f.name, pointFieldTypeName(f.datatype), std::to_string(f.offset),
               std::to_string(f.count)});
  }
  table.print(out, "  ");
  if (t.layout_varies) out << "  (the field layout changes between messages; shown: the first)\n";
}

}  // namespace

int runInfo(const InfoOptions& options) {
  const Config config = configFromOptions(options.common);
  const LogSummary summary = summarizeLog(options.log_path, config.input, config.sensor);
  std::ostream& out = std::cout;
  const bool bag = summary.ros;

  out << "Log " << summary.path << '\n'
      << "  format       " << summary.format << ", " << bytesText(summary.size_bytes);
  if (!summary.compression.empty()) {
    out << ", " << summary.chunks << " chunks (compression: " << summary.compression << ")";
  }
  out << "\n  messages     " << summary.messages << '\n';
  if (summary.messages > 0) {
    out << (bag ? "  record time  " : "  time         ") << stampText(summary.start_ns) << " .. "
        << stampText(summary.end_ns) << " ("
        << fixed(static_cast<double>(summary.end_ns - summary.start_ns) * 1e-9, 3) << " s)\n";
  }
  for (const auto& [name, value] : summary.properties) {
    out << "  " << name << std::string(name.size() < 13 ? 13 - name.size() : 1, ' ') << value
        << '\n';
  }
  out << (bag ? "\nTopics\n" : "\nStreams\n");
  printTopics(summary, out);
  if (!bag) {
    for (const auto& t : summary.topics) {
      if (t.type == "scan" && t.count > 0) {
        out << "  " << t.name << ": points per scan min " << t.points_min << ", median "
            << t.points_median << ", max " << t.points_max << '\n';
      }
    }
  }
  if (!summary.dropped.empty()) {
    out << "\nSkipped or repaired (reason: count)\n";
    Table table({"reason", "count"}, {false, true});
    for (const auto& [reason, count] : summary.dropped) table.add({reason, std::to_string(count)});
    table.print(out, "  ");
  }
  for (const auto& t : summary.topics) {
    if (!t.fields.empty() || canonicalRosType(t.type) == kPointCloud2Type) printCloudTopic(t, out);
    if (canonicalRosType(t.type) == kVelodyneScanType && t.count > 0) {
      out << "\nVelodyne packets " << t.name << ": packets per message min " << t.points_min
          << ", median " << t.points_median << ", max " << t.points_max << '\n';
    }
  }
  out << '\n';
  if (summary.input_problem.empty()) {
    out << "Storey reads " << (bag ? "the LiDAR from " : "") << summary.points_topic
        << " and IMU from " << summary.imu_topic << '\n';
  } else {
    out << "Storey cannot run on this log as it is: " << summary.input_problem << '\n';
  }
  return 0;
}

}  // namespace storey::cli
