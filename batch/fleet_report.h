#pragma once
/// The fleet report of `storey batch`: FLEET_OUT/fleet.json and fleet.html
/// (style inline; the only files it references are each log's elevation
/// render and report.html, by relative path). One row per log of the plan
/// with its status and figures read from its state.json and its run's
/// report.json; totals; the failures with their one-line errors.
#include <nlohmann/json.hpp>
#include <string>

#include "fleet_state.h"

namespace storey::cli {

/// The report as JSON (the content of fleet.json; format in docs/batch.md).
nlohmann::json fleetJson(const FleetPlan& plan);
/// fleet.html from fleet.json's content.
std::string fleetHtml(const nlohmann::json& fleet);
/// Writes fleet.json and fleet.html atomically into the plan's FLEET_OUT;
/// returns the JSON.
nlohmann::json writeFleetReport(const FleetPlan& plan);
/// "4 logs: 3 done, 1 failed" and one line per failure.
std::string fleetSummaryText(const nlohmann::json& fleet);

}  // namespace storey::cli
