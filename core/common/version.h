#pragma once
/// Storey's version (the CMake project's VERSION), for reports, file headers
/// and `storey --version`.

namespace storey {

/// e.g. "0.1.0".
const char* storeyVersion();

}  // namespace storey
