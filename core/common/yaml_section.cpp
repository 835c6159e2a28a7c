#include "common/yaml_section.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace storey {
namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0) return "";
  return " (line " + std::to_string(mark.line + 1) + ")";
}

std::string scalarText(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "nothing";
}

}  // namespace

YamlSection::YamlSection(const YAML::Node& node, std::string source, std::string path)
    : node_(node), source_(std::move(source)), path_(std::move(path)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    throw Error(source_ + ": " +
                (path_.empty() ? std::string("the document") : "key '" + path_ + "'") +
                lineOf(node_) + " must be a mapping of keys, got " + scalarText(node_));
  }
}

std::string YamlSection::fullKey(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void YamlSection::fail(const std::string& key, const std::string& what) const {
  std::string line;
  const YAML::Node& map = node_;
  if (map && map.IsMap() && map[key]) line = lineOf(map[key]);
  throw Error(source_ + ": key '" + fullKey(key) + "'" + line + " " + what);
}

bool YamlSection::has(const std::string& key) const {
  const YAML::Node& map = node_;
  return map && map.IsMap() && map[key] && !map[key].IsNull();
}

std::optional<YAML::Node> YamlSection::child(const std::string& key) {
  known_.insert(key);
  if (!has(key)) return std::nullopt;
  const YAML::Node& map = node_;
  return map[key];
}

void YamlSection::read(const std::string& key, double& value) {
  const std::optional<YAML::Node> value_node = child(key);
  if (!value_node) return;
  const YAML::Node& n = *value_node;
  double parsed = 0.0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, parsed))
    fail(key, "must be a number, got " + scalarText(n));
  if (!std::isfinite(parsed)) fail(key, "must be a finite number, got " + scalarText(n));
  value = parsed;
}

void YamlSection::read(const std::string& key, int& value) {
  const std::optional<YAML::Node> value_node = child(key);
  if (!value_node) return;
  const YAML::Node& n = *value_node;
  int parsed = 0;
  if (!n.IsScalar() || !YAML::convert<int>::decode(n, parsed))
    fail(key, "must be an integer, got " + scalarText(n));
  value = parsed;
}

void YamlSection::read(const std::string& key, bool& value) {
  const std::optional<YAML::Node> value_node = child(key);
  if (!value_node) return;
  const YAML::Node& n = *value_node;
  bool parsed = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, parsed))
    fail(key, "must be true or false, got " + scalarText(n));
  value = parsed;
}

void YamlSection::read(const std::string& key, std::string& value) {
  known_.insert(key);
  const YAML::Node& map = node_;
  if (!(map && map.IsMap() && map[key])) return;
  const YAML::Node n = map[key];
  if (n.IsNull()) {
    value.clear();
    return;
  }
  if (!n.IsScalar()) fail(key, "must be a text value, got " + scalarText(n));
  value = n.Scalar();
}

void YamlSection::read(const std::string& key, std::vector<double>& value,
                       std::size_t expected_size) {
  const std::optional<YAML::Node> value_node = child(key);
  if (!value_node) return;
  const YAML::Node& n = *value_node;
  const std::string expected = "must be a list of " + std::to_string(expected_size) + " numbers";
  if (!n.IsSequence() || n.size() != expected_size)
    fail(key, expected + ", got " + scalarText(n) +
                  (n.IsSequence() ? " of " + std::to_string(n.size()) : ""));
  std::vector<double> parsed(expected_size);
  for (std::size_t i = 0; i < expected_size; ++i) {
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], parsed[i]) ||
        !std::isfinite(parsed[i]))
      fail(key, expected + "; element " + std::to_string(i) + " is " + scalarText(n[i]));
  }
  value = std::move(parsed);
}

void YamlSection::readList(const std::string& key, std::vector<double>& value) {
  const std::optional<YAML::Node> value_node = child(key);
  if (!value_node) return;
  const YAML::Node& n = *value_node;
  if (!n.IsSequence()) fail(key, "must be a list of numbers, got " + scalarText(n));
  read(key, value, n.size());
}

void YamlSection::read(const std::string& key, Eigen::Vector3d& value) {
  std::vector<double> v;
  read(key, v, 3);
  if (v.size() == 3) value = Eigen::Vector3d(v[0], v[1], v[2]);
}

YamlSection YamlSection::section(const std::string& key) {
  const std::optional<YAML::Node> n = child(key);
  return YamlSection(n ? *n : YAML::Node(), source_, fullKey(key));
}

void YamlSection::finish(const std::vector<std::string>& also_allowed) const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {  // a YAML complex key ("? [a, b]")
      throw Error(source_ + ": a key" + (path_.empty() ? "" : " under '" + path_ + "'") +
                  " is not a name" + lineOf(entry.first));
    }
    const std::string key = entry.first.as<std::string>();
    if (known_.count(key) ||
        std::find(also_allowed.begin(), also_allowed.end(), key) != also_allowed.end())
      continue;
    std::string best;
    std::size_t best_distance = 4;
    for (const auto& candidate : known_) {
      const std::size_t d = editDistance(key, candidate);
      if (d < best_distance) {
        best_distance = d;
        best = candidate;
      }
    }
    std::string message = source_ + ": unknown key '" + fullKey(key) + "'" + lineOf(entry.first);
    if (!best.empty()) message += "; did you mean '" + fullKey(best) + "'?";
    throw Error(message);
  }
}

YAML::Node parseYaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(source + ": not valid YAML at line " + std::to_string(e.mark.line + 1) + ": " +
                e.msg);
  }
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file for reading");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace storey
