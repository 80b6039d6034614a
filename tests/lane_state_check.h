#pragma once
// laneState (kernels/ray_state.h) against makeSingleRayState, for the tests: compiled in the baseline
// test sources (4-wide packets) and, in avx2_checks.cpp, with AVX2 flags (8-wide packets).
#include <cstring>

#include "kernels/ray_state.h"
#include "kernels/traverse_stream.h"

namespace wideray::test {
inline namespace WIDERAY_ISA {

/// How many valid rays of `rays` have a state from forEachRayState (made this ISA's width of rays at a
/// time, as the `single` kernels make them) that differs in any bit from makeSingleRayState of the ray.
inline int laneStateMismatches(const Ray* rays, int count) {
    int mismatches = 0;
    forEachRayState<kMaxWidth>(rays, size_t(count), [&](size_t i, const SingleRayState* fromLanes) {
        if (!fromLanes) return;
        const SingleRayState own = makeSingleRayState(rays[i]);
        mismatches += std::memcmp(fromLanes, &own, sizeof(SingleRayState)) != 0;
    });
    return mismatches;
}

/// The same for the stream slots that loadStream fills from `rays` (slotState).
inline int streamSlotStateMismatches(const Ray* rays, int count) {
    StreamWorkspace ws;
    const size_t n = loadStream<kMaxWidth>(rays, size_t(count), ws);
    int mismatches = 0;
    for (size_t slot = 0; slot < n; ++slot) {
        const SingleRayState fromStream = slotState(ws, int32_t(slot)), own = makeSingleRayState(rays[ws.rayOf[slot]]);
        mismatches += std::memcmp(&fromStream, &own, sizeof(SingleRayState)) != 0;
    }
    return mismatches;
}

} // namespace WIDERAY_ISA

/// The same compiled for AVX2 (avx2_checks.cpp): call only where the CPU has it.
int laneStateMismatchesAvx2(const Ray* rays, int count);
int streamSlotStateMismatchesAvx2(const Ray* rays, int count);

} // namespace wideray::test
