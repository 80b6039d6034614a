#pragma once
// transposeMin (simd/) against reduceMin, for the tests: compiled in the baseline test sources
// (4 lanes), in avx2_checks.cpp (8) and in avx512_checks.cpp (16).
#include <cmath>
#include <random>

#include "simd/simd.h"

namespace wideray::test {
inline namespace WIDERAY_ISA {
using namespace simd;

/// How many lanes of transposeMin differ from reduceMin of their vector, over `rounds` random sets of
/// vectors (with ties among the lanes every fourth round).
inline int transposeMinMismatches(int rounds) {
    constexpr int K = kMaxWidth;
    std::mt19937 random(3);
    std::uniform_real_distribution<float> value(-100.0f, 100.0f);
    int mismatches = 0;
    for (int round = 0; round < rounds; ++round) {
        vfloat<K> v[K];
        for (vfloat<K>& x : v) {
            alignas(64) float lanes[K];
            for (float& l : lanes) l = round % 4 == 0 ? std::round(value(random) / 50.0f) : value(random);
            x = vfloat<K>::load(lanes);
        }
        alignas(64) float minima[K];
        transposeMin(v).store(minima);
        for (int i = 0; i < K; ++i) mismatches += minima[i] != reduceMin(v[i]);
    }
    return mismatches;
}

} // namespace WIDERAY_ISA

/// The same compiled for AVX2 and AVX-512: call only where the CPU has them.
int transposeMinMismatchesAvx2(int rounds);
int transposeMinMismatchesAvx512(int rounds);

} // namespace wideray::test
