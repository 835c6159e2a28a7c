#pragma once
/// The one exception type of the project: a message a user can act on
/// (the file, the place in it, what was expected).
#include <stdexcept>
#include <string>

namespace storey {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace storey

namespace storey {

/// Config validation: throws Error("key '<key>' <what>") unless `ok`.
inline void requireKey(bool ok, const std::string& key, const std::string& what) {
  if (!ok) throw Error("key '" + key + "' " + what);
}

/// Thrown when a ProgressFn asked long-running work to stop.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled by the user") {}
};

}  // namespace storey
