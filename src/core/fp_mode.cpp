#include "core/fp_mode.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <tbb/task_scheduler_observer.h>

namespace wideray {

void enableFlushToZero() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

struct FlushToZeroScope::Observer : tbb::task_scheduler_observer {
    Observer() { observe(true); }
    ~Observer() override { observe(false); }
    void on_scheduler_entry(bool) override { enableFlushToZero(); }
};

FlushToZeroScope::FlushToZeroScope() : observer_(std::make_unique<Observer>()) { enableFlushToZero(); }
FlushToZeroScope::~FlushToZeroScope() = default;

} // namespace wideray
