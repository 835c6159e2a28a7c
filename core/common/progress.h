#pragma once
/// Progress reporting from long-running core work to a face (terminal bar in
/// the CLI, progress dialog in the plugin).
#include <functional>
#include <string>

namespace storey {

/// Called with the fraction done in [0, 1] and the current stage's name.
/// Returns false to ask the work to stop; the callee then throws storey::Cancelled.
using ProgressFn = std::function<bool(double fraction, const std::string& stage)>;

}  // namespace storey
