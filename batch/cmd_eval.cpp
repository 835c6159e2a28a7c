// `storey eval`: fills the evaluation inputs from the options, runs the core
// evaluation, prints the table and writes the JSON.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "eval/eval_report.h"
#include "eval/evaluation.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

/// Default JSON path: "<est stem>.eval.json" next to the estimate.
std::string defaultJsonPath(const std::string& est_path) {
  fs::path path(est_path);
  return (path.parent_path() / (path.stem().string() + ".eval.json")).string();
}

/// storeys.json next to the estimate, when it exists (the layout of `storey run`).
std::string defaultEstimatedStoreys(const std::string& est_path) {
  const fs::path candidate = fs::path(est_path).parent_path() / "storeys.json";
  std::error_code ec;
  return fs::is_regular_file(candidate, ec) ? candidate.string() : std::string();
}

}  // namespace

int runEval(const EvalOptions& options) {
  eval::EvaluationInputs inputs;
  inputs.gt_path = options.gt_path;
  inputs.est_path = options.est_path;
  inputs.mesh_path = options.mesh_path;
  inputs.map_path = options.map_path;
  inputs.true_storeys_path = options.storeys_path;
  inputs.estimated_storeys_path = options.est_storeys_path;
  inputs.planes_path = options.planes_path;
  if (inputs.estimated_storeys_path.empty() && !inputs.true_storeys_path.empty())
    inputs.estimated_storeys_path = defaultEstimatedStoreys(options.est_path);

  eval::EvaluationConfig config;
  config.association.max_time_difference = options.max_time_difference;
  config.rpe_segment_lengths = options.rpe_lengths;
  config.threads = options.threads;

  const eval::EvaluationResult result = eval::evaluate(inputs, config);
  if (options.json_path == "-") {
    std::cout << eval::evaluationJson(result);
    return 0;
  }
  std::cout << eval::evaluationTable(result);
  if (options.json_path != "none") {
    const std::string json_path =
        options.json_path.empty() ? defaultJsonPath(options.est_path) : options.json_path;
    eval::writeEvaluationJson(json_path, result);
    std::cout << "\nWrote " << json_path << "\n";
  }
  return 0;
}

}  // namespace storey::cli
