// Placeholder until the stage lands (owned by the stage's engineer).
#include <iostream>

#include "commands.h"

namespace storey::cli {

int runInfo(const InfoOptions&) {
  std::cerr << "storey info: not implemented yet\n";
  return 2;
}

}  // namespace storey::cli
