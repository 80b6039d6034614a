#pragma once
// Flush-to-zero and denormals-are-zero on every thread that traces, for our kernels and Embree alike
// (denormal arithmetic is slow on x86 and Embree's authors recommend these modes).
//
// oneTBB runs each task with the floating-point settings its thread's scheduler (or task_arena)
// captured when it was initialized, whatever the worker thread had set: setting the mode on the
// calling thread reaches the tasks only where it is set before that thread first uses oneTBB, or
// inside an arena initialized after it (FlushToZeroScope::run).
#include <tbb/task_arena.h>

#include <utility>

namespace wideray {

/// Sets FTZ and DAZ on the calling thread.
void enableFlushToZero();

/// Sets FTZ and DAZ on the calling thread; run(f) calls f where every oneTBB task that f starts,
/// on any thread, has them too.
class FlushToZeroScope {
public:
    FlushToZeroScope();

    template <class F>
    decltype(auto) run(F&& f) {
        return arena_.execute(std::forward<F>(f));
    }

private:
    tbb::task_arena arena_;
};

} // namespace wideray
