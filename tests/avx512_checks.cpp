// The AVX-512 builds of the tests' per-ISA checks (compiled with AVX-512 flags, see
// tests/CMakeLists.txt); nothing here runs unless the CPU has AVX-512.
#define WIDERAY_ISA avx512_test
#include "child_order_check.h"
#include "transpose_min_check.h"

namespace wideray::test {

ChildOrderResult runPushNearestLast16Avx512(const float* distances, uint32_t mask) {
    return runPushNearestLast<16>(distances, mask);
}

int transposeMinMismatchesAvx512(const float* values, int rounds) { return transposeMinMismatches(values, rounds); }

} // namespace wideray::test
