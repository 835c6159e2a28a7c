#pragma once
/// Reads one YAML mapping into plain struct fields, key by key, and reports
/// what a user can act on: an unknown or mistyped key is a storey::Error
/// naming the file, the full key path and its line. Used by the readers of YAML files (config,
/// calibration, building specs).
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace storey {

class YamlSection {
 public:
  /// `node` must be a map (or null/absent = empty section). `path` is the
  /// dotted key prefix ("" at the top), `source` names the file in errors.
  YamlSection(const YAML::Node& node, std::string source, std::string path);

  bool has(const std::string& key) const;
  /// Reads key into value when present (absent keeps the default).
  void read(const std::string& key, double& value);
  void read(const std::string& key, int& value);
  void read(const std::string& key, bool& value);
  void read(const std::string& key, std::string& value);
  void read(const std::string& key, Eigen::Vector3d& value);
  void read(const std::string& key, std::vector<double>& value, std::size_t expected_size);
  /// A list of numbers of any length.
  void readList(const std::string& key, std::vector<double>& value);
  /// Like read() but the key must be present.
  template <typename T>
  void require(const std::string& key, T& value) {
    if (!has(key)) fail(key, "is required but missing");
    read(key, value);
  }
  /// Sub-mapping (empty when absent); marks the key as known.
  YamlSection section(const std::string& key);
  /// Throws for the first key that no read()/section() asked for, suggesting
  /// the closest known key when one is near. Call after reading every key.
  void finish(const std::vector<std::string>& also_allowed = {}) const;

  /// Throws a storey::Error "<source>: key '<path.key>' (line N) <what>".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  const std::string& source() const { return source_; }
  std::string fullKey(const std::string& key) const;

 private:
  /// The value of `key` when present and not null (marks the key as known).
  std::optional<YAML::Node> child(const std::string& key);
  YAML::Node node_;
  std::string source_;
  std::string path_;
  std::set<std::string> known_;
};

/// Parses YAML text; a syntax error is a storey::Error naming source and line.
YAML::Node parseYaml(const std::string& text, const std::string& source);
/// Reads a whole file (storey::Error when it cannot be opened).
std::string readTextFile(const std::string& path);

}  // namespace storey
