#pragma once
// Flush-to-zero and denormals-are-zero on every thread that traces, for our kernels and Embree alike
// (denormal arithmetic is slow on x86 and Embree's authors recommend these modes).
#include <memory>

namespace wideray {

/// Sets FTZ and DAZ on the calling thread.
void enableFlushToZero();

/// While alive, every oneTBB worker thread entering the scheduler sets FTZ and DAZ (and so does the
/// thread that creates it).
class FlushToZeroScope {
public:
    FlushToZeroScope();
    ~FlushToZeroScope();

private:
    struct Observer;
    std::unique_ptr<Observer> observer_;
};

} // namespace wideray
