#pragma once
/// A test suite fixture with the simulator's `tiny` building simulated once
/// per suite into a temporary folder (sim/ inside it), and the run
/// configuration with the simulated sensors' calibration.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "config/config.h"
#include "sim/simulator.h"
#include "support/temp_dir.h"

namespace storey::test {

class TinySimulation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    sim::SimulationOptions options;
    options.threads = 2;
    sim::simulate(sim::loadBuildingSpec("tiny"), options, dir_->file("sim"));
  }
  static void TearDownTestSuite() { dir_.reset(); }
  /// Defaults + the simulated calibration.
  static Config simConfig() {
    Config c;
    applyCalibrationFile(c, simFile(sim::kCalibrationFile));
    return c;
  }
  static std::string simFile(const std::string& name) { return dir_->file("sim/" + name); }
  static std::string bag() { return simFile(sim::kBagFile); }
  static std::string file(const std::string& name) { return dir_->file(name); }

 private:
  static inline std::unique_ptr<TempDir> dir_;
};

}  // namespace storey::test
