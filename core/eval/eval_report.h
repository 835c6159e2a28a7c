#pragma once
/// The evaluation as JSON (machine-readable, units in the key names) and as a
/// plain-text table for people (angles in degrees there).
#include <string>

#include "eval/evaluation.h"

namespace storey::eval {

/// Pretty-printed JSON document; layout in docs/evaluation.md.
std::string evaluationJson(const EvaluationResult& result);
/// Writes evaluationJson atomically.
void writeEvaluationJson(const std::string& path, const EvaluationResult& result);
/// Human-readable tables (association, ATE, RPE, drift, storeys, map, notes).
std::string evaluationTable(const EvaluationResult& result);

}  // namespace storey::eval
