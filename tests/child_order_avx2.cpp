// The AVX2 build of tests/child_order_check.h (compiled with AVX2 flags, see tests/CMakeLists.txt);
// nothing here runs unless the CPU has AVX2.
#define WIDERAY_ISA avx2_test
#include "child_order_check.h"

namespace wideray::test {

ChildOrderResult runPushNearestLastAvx2(const float* distances, uint32_t mask) {
    return runPushNearestLast(distances, mask);
}

} // namespace wideray::test
