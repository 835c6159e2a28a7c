#pragma once
/// When the back end solves the whole keyframe graph instead of the newest
/// keyframes (docs/method/backend.md, "Solving"). A whole-graph solve costs
/// about as much as the graph is large, so a fixed interval would make its
/// cost per keyframe grow with the log. The interval is therefore
/// GraphConfig::full_every optimisations or GraphConfig::full_every_share of
/// the graph's keyframes, whichever is more: once the graph is large, a
/// whole-graph solve comes after the graph grew by that share, and the
/// whole-graph work per keyframe stays bounded (about 1 / full_every_share
/// keyframes' worth of solving) however long the walk.
#include "backend/backend_config.h"

namespace storey::backend {

/// Optimisations between two whole-graph solves for a graph of `keyframes`.
int wholeGraphInterval(const GraphConfig& config, int keyframes);

/// True when the optimisation due now is a whole-graph one: always with no
/// window (window_keyframes 0), for the first optimisation (`since_whole` < 0:
/// none yet), then when `since_whole` optimisations ran since the last
/// whole-graph one reach wholeGraphInterval().
bool wholeGraphSolveDue(const GraphConfig& config, int since_whole, int keyframes);

}  // namespace storey::backend
