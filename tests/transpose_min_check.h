#pragma once
// transposeMin (simd/) against reduceMin, for the tests: compiled in the baseline test sources
// (4 lanes), in avx2_checks.cpp (8) and in avx512_checks.cpp (16). The values come from the caller,
// so that no standard-library code is instantiated with AVX flags here (the linker could hand that
// copy to baseline code).
#include "simd/simd.h"

namespace wideray::test {

/// Values for `rounds` checks of the widest vectors: 16 x 16 floats per round.
constexpr int kTransposeMinValuesPerRound = 16 * 16;

inline namespace WIDERAY_ISA {
using namespace simd;

/// How many lanes of transposeMin differ from reduceMin of their vector, over `rounds` sets of this
/// ISA's widest vectors read from `values`.
inline int transposeMinMismatches(const float* values, int rounds) {
    constexpr int K = kMaxWidth;
    int mismatches = 0;
    for (int round = 0; round < rounds; ++round) {
        vfloat<K> v[K];
        for (int i = 0; i < K; ++i) v[i] = vfloat<K>::loadu(values + round * kTransposeMinValuesPerRound + i * K);
        alignas(64) float minima[K];
        transposeMin(v).store(minima);
        for (int i = 0; i < K; ++i) mismatches += minima[i] != reduceMin(v[i]);
    }
    return mismatches;
}

} // namespace WIDERAY_ISA

/// The same compiled for AVX2 and AVX-512: call only where the CPU has them.
int transposeMinMismatchesAvx2(const float* values, int rounds);
int transposeMinMismatchesAvx512(const float* values, int rounds);

} // namespace wideray::test
