// FlushToZeroScope: the mode reaches every oneTBB task started inside run(), on every thread, even
// where the calling thread had used oneTBB before (oneTBB runs tasks with the mode its scheduler
// captured when it was initialized, not with the worker thread's own).
#include <gtest/gtest.h>

#include <atomic>
#include <xmmintrin.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/fp_mode.h"

namespace wideray {
namespace {

constexpr unsigned kFtzDaz = 0x8040;

/// Tasks (of many chunks, so that workers take some) whose MXCSR has FTZ and DAZ, and all tasks.
std::pair<int, int> tasksWithFlushToZero() {
    std::atomic<int> with{0}, all{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, 1 << 16, 16), [&](const tbb::blocked_range<int>&) {
        if ((_mm_getcsr() & kFtzDaz) == kFtzDaz) ++with;
        ++all;
    });
    return {with.load(), all.load()};
}

TEST(FlushToZero, ReachesEveryTaskStartedInsideRun) {
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved & ~kFtzDaz);
    tasksWithFlushToZero();  // this thread's scheduler is initialized without the mode
    {
        FlushToZeroScope ftz;
        EXPECT_EQ(_mm_getcsr() & kFtzDaz, kFtzDaz);
        const auto [with, all] = ftz.run([] { return tasksWithFlushToZero(); });
        EXPECT_EQ(with, all);
        // A denormal read as zero inside a task.
        ftz.run([] {
            tbb::parallel_for(0, 64, [](int) {
                volatile float tiny = 1e-40f;
                EXPECT_EQ(tiny * 1.0f, 0.0f);
            });
        });
    }
    _mm_setcsr(saved);
}

} // namespace
} // namespace wideray
