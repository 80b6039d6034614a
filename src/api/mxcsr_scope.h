#pragma once
// Flush-to-zero and denormals-are-zero on the calling thread while a library call traces (the mode
// every wideray thread traces in, core/fp_mode.h), the caller's own mode restored afterwards.
#include <xmmintrin.h>

namespace wideray {

class MxcsrScope {
public:
    MxcsrScope() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
    ~MxcsrScope() { _mm_setcsr(saved_); }
    MxcsrScope(const MxcsrScope&) = delete;
    MxcsrScope& operator=(const MxcsrScope&) = delete;

private:
    static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
    unsigned saved_;
};

} // namespace wideray
