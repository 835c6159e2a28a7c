#pragma once
/// Every parameter of the pipeline: the aggregate of the stages' own config
/// structs (each beside its stage, defaults in the struct, units beside each
/// field, its own validate()). The YAML file (resources/config/default.yaml),
/// the CLI and the plugin only fill these. Only the pipeline and the faces
/// include this header; a stage takes its own config.
#include <string>

#include "backend/backend_config.h"
#include "config/render_config.h"
#include "io/calibration_file.h"
#include "io/input_config.h"
#include "map/map_config.h"
#include "odometry/odometry_config.h"
#include "storeys/storeys_config.h"
#include "types/sensor.h"

namespace storey {

struct Config {
  SensorConfig sensor;
  InputConfig input;
  OdometryConfig odometry;
  BackendConfig backend;
  MapConfig map;          ///< map assembly (map/map_config.h)
  StoreysConfig storeys;  ///< storey segmentation (storeys/storeys_config.h)
  RenderConfig render;    ///< off-screen PNG renders (render/)

  /// Checks value ranges of every section (each stage's validate(), in file
  /// order); throws storey::Error naming the key at fault.
  void validate() const;
};

/// Loads a configuration file over the defaults. Every key is optional; an
/// unknown key, a wrong type or a value out of range is a storey::Error that
/// names the file, the key and its line.
Config loadConfig(const std::string& path);
/// The whole configuration as YAML, every key present (the run report keeps
/// it; a test checks that resources/config/default.yaml has the same keys).
std::string configToYaml(const Config& config);
/// Applies a YAML text (same rules) over `config`; `source` names it in errors.
void applyConfigYaml(Config& config, const std::string& yaml_text, const std::string& source);

/// Reads a calibration file (io/calibration_file.h) over `config`'s sensor and
/// topics; all or nothing. Throws storey::Error naming the file and the key.
void applyCalibrationFile(Config& config, const std::string& path);
/// The configuration of a run: built-in defaults, then the config file (when
/// `config_path` is not empty), then the calibration file (when not empty).
Config loadRunConfig(const std::string& config_path, const std::string& calibration_path);
/// The calibration part of a configuration (sensor and topics).
Calibration calibrationOf(const Config& config);

}  // namespace storey
