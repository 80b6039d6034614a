#include "core/fp_mode.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

namespace wideray {

void enableFlushToZero() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

FlushToZeroScope::FlushToZeroScope() {
    enableFlushToZero();
    arena_.initialize();  // captures the mode just set, for the tasks run inside it
}

} // namespace wideray
