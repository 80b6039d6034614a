#pragma once
// Elementary functions missing from the SIMD vocabulary, with one name for float and every vector
// width, so that templated shading code compiles for all of them.
#include <cmath>

#include "simd/simd.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace simd {

inline float sqrt(float a) { return std::sqrt(a); }
inline vfloat4 sqrt(vfloat4 a) { return _mm_sqrt_ps(a.m); }
#if defined(__AVX2__)
inline vfloat8 sqrt(vfloat8 a) { return _mm256_sqrt_ps(a.m); }
#endif
#if defined(__AVX512F__)
inline vfloat16 sqrt(vfloat16 a) { return _mm512_sqrt_ps(a.m); }
#endif

template <class F> F clamp(F a, F lowest, F highest) { return min(max(a, lowest), highest); }

} // namespace simd
} // namespace WIDERAY_ISA
} // namespace wideray
