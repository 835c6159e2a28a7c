// Subcommands whose pipeline stages do not exist yet: they say so and fail.
#include <iostream>

#include "commands.h"

namespace storey::cli {
namespace {

int notImplemented(const char* command, const char* what) {
  std::cerr << "storey " << command << ": not implemented yet (" << what << ")\n";
  return 2;
}

}  // namespace

int runRender(const RenderOptions&) {
  return notImplemented("render", "off-screen VTK renders arrive with the render stage");
}

}  // namespace storey::cli
