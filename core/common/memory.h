#pragma once
/// Handing memory the program freed back to the system, so the resident size
/// (RSS) follows what is in use: after a stage frees many small blocks (the
/// odometry's local map, the back end's graph), the C library keeps them for
/// later small allocations, while the next stage allocates large arrays.

namespace storey {

/// Returns the free memory of the C library's heap to the system (glibc's
/// malloc_trim; nothing elsewhere).
void returnFreedMemory();

/// The process's peak resident size so far [MiB] (Linux: VmHWM of
/// /proc/self/status, the highest reading so far: with several threads
/// the kernel's figure can dip by a few pages); -1 where unknown.
double peakResidentMiB();

}  // namespace storey
