// The AVX2 builds of the tests' per-ISA checks (compiled with AVX2 flags, see tests/CMakeLists.txt);
// nothing here runs unless the CPU has AVX2.
#define WIDERAY_ISA avx2_test
#include "child_order_check.h"
#include "lane_state_check.h"
#include "transpose_min_check.h"

namespace wideray::test {

ChildOrderResult runPushNearestLastAvx2(const float* distances, uint32_t mask) {
    return runPushNearestLast(distances, mask);
}

int laneStateMismatchesAvx2(const Ray* rays, int count) { return laneStateMismatches(rays, count); }

int streamSlotStateMismatchesAvx2(const Ray* rays, int count) { return streamSlotStateMismatches(rays, count); }

int transposeMinMismatchesAvx2(const float* values, int rounds) { return transposeMinMismatches(values, rounds); }

} // namespace wideray::test
