#include "io/ros_message_source.h"

#include <cstdio>
#include <sstream>

namespace storey {

std::int64_t RosMessageSource::messageCount() const {
  std::int64_t n = 0;
  for (const auto& t : topics()) n += t.count;
  return n;
}

bool definitionStartsWithHeader(const std::string& definition) {
  std::istringstream lines(definition);
  std::string line;
  while (std::getline(lines, line)) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string type, name;
    if (!(words >> type)) continue;  // blank or comment line
    words >> name;
    return (type == "Header" || type == "std_msgs/Header" || type == "std_msgs/msg/Header") &&
           !name.empty();
  }
  return false;
}

std::string formatSecondsNs(std::int64_t ns) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.6f", static_cast<double>(ns) * 1e-9);
  return text;
}

}  // namespace storey
