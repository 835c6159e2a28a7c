#pragma once
/// Independent jobs (files to write, for example) on up to `threads` threads
/// of their own (in the calling thread when `threads` <= 1), reported in job
/// order on the calling thread: `on_done(i)` is called for
/// job 0, 1, 2, ... as soon as it and every job before it are done. The jobs'
/// results must not depend on each other, so they are the same whatever the
/// number of threads.
///
/// The first job (in order) that throws, or an on_done that throws (a
/// cancelled progress report), stops the jobs not yet started; the exception
/// comes out after every started job has ended.
#include <cstddef>
#include <functional>
#include <vector>

namespace storey {

void runJobs(const std::vector<std::function<void()>>& jobs, int threads,
             const std::function<void(std::size_t)>& on_done = {});

}  // namespace storey
