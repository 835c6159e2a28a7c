#include "io/topic_selection.h"

#include <algorithm>

#include "common/error.h"
#include "common/log.h"

namespace storey {
namespace {

/// `types`: the accepted types in order of preference (canonical spelling);
/// the chosen topic's type goes to `chosen_type`.
std::string chooseOne(const std::vector<TopicInfo>& topics, const std::vector<std::string>& types,
                      const std::string& override_name, const char* what, const char* option,
                      const std::string& file, std::string* chosen_type = nullptr) {
  std::string type_list;
  for (const auto& type : types) type_list += (type_list.empty() ? "" : " or ") + type;
  if (!override_name.empty()) {
    bool found = false;
    for (const auto& t : topics) {
      if (t.name != override_name) continue;
      found = true;
      const std::string canonical = canonicalRosType(t.type);
      if (std::find(types.begin(), types.end(), canonical) != types.end()) {
        if (chosen_type) *chosen_type = canonical;
        return t.name;
      }
    }
    if (found) {
      throw Error(file + ": topic " + override_name + " is not of type " + type_list +
                  " (topics found: " + describeTopics(topics) + ")");
    }
    throw Error(file + ": " + what + " topic " + override_name +
                " does not exist (topics found: " + describeTopics(topics) + ")");
  }
  std::vector<TopicInfo> candidates;
  std::string type;
  for (const auto& wanted : types) {
    for (const auto& t : topics) {
      if (canonicalRosType(t.type) == wanted) candidates.push_back(t);
    }
    if (!candidates.empty()) {
      type = wanted;
      break;
    }
  }
  if (candidates.empty()) {
    throw Error(file + ": no " + what + " topic (" + type_list +
                ") in the log; topics found: " + describeTopics(topics));
  }
  if (chosen_type) *chosen_type = type;
  std::stable_sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.count != b.count ? a.count > b.count : a.name < b.name;
  });
  if (candidates.size() > 1) {
    std::vector<TopicInfo> others(candidates.begin() + 1, candidates.end());
    logWarning(file + ": several " + type + " topics; using " + candidates.front().name + " (" +
               std::to_string(candidates.front().count) + " messages), not " +
               describeTopics(others) + "; set " + option + " to choose another");
  }
  return candidates.front().name;
}

}  // namespace

std::string describeTopics(const std::vector<TopicInfo>& topics) {
  if (topics.empty()) return "none";
  std::string text;
  for (const auto& t : topics) {
    if (!text.empty()) text += ", ";
    text += t.name + " (" + t.type + ", " + std::to_string(t.count) + " messages)";
  }
  return text;
}

TopicChoice chooseTopics(const std::vector<TopicInfo>& topics, const InputConfig& input,
                         const std::string& file) {
  TopicChoice choice;
  choice.points_topic =
      chooseOne(topics, {kPointCloud2Type, kVelodyneScanType}, input.points_topic, "point cloud",
                "input.points_topic (--points-topic)", file, &choice.points_type);
  choice.imu_topic =
      chooseOne(topics, {kImuType}, input.imu_topic, "IMU", "input.imu_topic (--imu-topic)", file);
  return choice;
}

}  // namespace storey
