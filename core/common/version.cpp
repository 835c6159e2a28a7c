#include "common/version.h"

#ifndef STOREY_VERSION
#error "STOREY_VERSION must be defined (core/common/CMakeLists.txt: the project's version)"
#endif

namespace storey {

const char* storeyVersion() {
  return STOREY_VERSION;
}

}  // namespace storey
