#pragma once
/// Numbers in messages.
#include <iomanip>
#include <sstream>
#include <string>

namespace storey {

/// `x` with `significant` significant digits (std::setprecision's default
/// notation), as error and log messages print measured values.
inline std::string significantText(double x, int significant = 3) {
  std::ostringstream os;
  os << std::setprecision(significant) << x;
  return os.str();
}

}  // namespace storey
