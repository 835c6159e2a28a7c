#pragma once
/// Outputs are written under a temporary name next to the target and renamed
/// when complete, so a failure never leaves a half-written file behind.
#include <functional>
#include <iosfwd>
#include <string>

namespace storey {

/// Calls `write` with a stream on "<path>.tmp-<pid>-<n>", then renames it to
/// `path`. On any exception (or a stream error) the temporary is removed and a
/// storey::Error naming `path` is thrown.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);
void writeFileAtomically(const std::string& path, const std::string& content);

/// A temporary name next to `path` for writers that need a file name
/// (libraries that open files themselves); rename with commitTemporary().
std::string temporaryPathFor(const std::string& path);
void commitTemporary(const std::string& temporary_path, const std::string& path);

/// Removes the temporaries ("NAME.tmp-PID-N") under `dir` (recursively)
/// whose writer is no longer running: what a killed process (SIGKILL, power
/// loss) left behind. Returns how many were removed; a missing `dir` is none.
std::size_t removeStaleTemporaries(const std::string& dir);

}  // namespace storey
