#pragma once
/// Reads a log to its end the way `storey run` does (fuzz targets).
#include <cstdint>
#include <memory>
#include <string>

#include "io/log_reader.h"

namespace storey::fuzz {

/// Opens `path` with openLog (the default input options) and reads every message.
inline void openAndDrainLog(const std::string& path) {
  std::unique_ptr<LogReader> reader = openLog(path, InputConfig{}, SensorConfig{});
  LogMessage message;
  while (reader->next(message)) {
  }
  reader->stats();
  reader->describe();
}

}  // namespace storey::fuzz
