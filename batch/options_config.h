#pragma once
/// The configuration a subcommand runs with: files named on the command line,
/// then the topic overrides.
#include "commands.h"
#include "config/config.h"

namespace storey::cli {

Config configFromOptions(const CommonOptions& options);

}  // namespace storey::cli
