// Placeholder until the stage lands (owned by the stage's engineer).
#include <iostream>

#include "commands.h"

namespace storey::cli {

int runSimulate(const SimulateOptions&) {
  std::cerr << "storey simulate: not implemented yet\n";
  return 2;
}

}  // namespace storey::cli
