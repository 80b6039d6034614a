#pragma once
// 8-wide AVX2 vectors: vfloat8, vint8, vbool8.
#include <immintrin.h>

#include <cstdint>

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace simd {

struct vbool8 {
    __m256 m;
    vbool8() = default;
    vbool8(__m256 v) : m(v) {}
    explicit vbool8(bool b) : m(_mm256_castsi256_ps(_mm256_set1_epi32(b ? -1 : 0))) {}
    friend vbool8 operator&(vbool8 a, vbool8 b) { return _mm256_and_ps(a.m, b.m); }
    friend vbool8 operator|(vbool8 a, vbool8 b) { return _mm256_or_ps(a.m, b.m); }
    friend vbool8 operator^(vbool8 a, vbool8 b) { return _mm256_xor_ps(a.m, b.m); }
    friend vbool8 andNot(vbool8 a, vbool8 b) { return _mm256_andnot_ps(b.m, a.m); }
    vbool8& operator&=(vbool8 b) { return *this = *this & b; }
    vbool8& operator|=(vbool8 b) { return *this = *this | b; }
};
inline uint32_t movemask(vbool8 b) { return uint32_t(_mm256_movemask_ps(b.m)); }
inline bool any(vbool8 b) { return movemask(b) != 0; }
inline bool all(vbool8 b) { return movemask(b) == 0xFF; }
inline bool none(vbool8 b) { return movemask(b) == 0; }
inline vbool8 maskFromBits8(uint32_t bits) {
    __m256i lane = _mm256_set_epi32(128, 64, 32, 16, 8, 4, 2, 1);
    __m256i m = _mm256_and_si256(_mm256_set1_epi32(int(bits)), lane);
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(m, lane));
}

struct vint8 {
    __m256i m;
    vint8() = default;
    vint8(__m256i v) : m(v) {}
    vint8(int32_t s) : m(_mm256_set1_epi32(s)) {}
    static vint8 load(const int32_t* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }
    static vint8 loadu(const void* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
    void store(int32_t* p) const { _mm256_store_si256(reinterpret_cast<__m256i*>(p), m); }
    friend vint8 operator+(vint8 a, vint8 b) { return _mm256_add_epi32(a.m, b.m); }
    friend vint8 operator&(vint8 a, vint8 b) { return _mm256_and_si256(a.m, b.m); }
    friend vbool8 operator==(vint8 a, vint8 b) { return _mm256_castsi256_ps(_mm256_cmpeq_epi32(a.m, b.m)); }
    friend vbool8 operator!=(vint8 a, vint8 b) { return andNot(vbool8(true), a == b); }
    friend vbool8 operator<(vint8 a, vint8 b) { return _mm256_castsi256_ps(_mm256_cmpgt_epi32(b.m, a.m)); }
};
inline vint8 select(vbool8 m, vint8 a, vint8 b) {
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(b.m), _mm256_castsi256_ps(a.m), m.m));
}

struct vfloat8 {
    __m256 m;
    static constexpr int size = 8;
    vfloat8() = default;
    vfloat8(__m256 v) : m(v) {}
    vfloat8(float s) : m(_mm256_set1_ps(s)) {}
    static vfloat8 load(const float* p) { return _mm256_load_ps(p); }
    static vfloat8 loadu(const float* p) { return _mm256_loadu_ps(p); }
    void store(float* p) const { _mm256_store_ps(p, m); }
    friend vfloat8 operator+(vfloat8 a, vfloat8 b) { return _mm256_add_ps(a.m, b.m); }
    friend vfloat8 operator-(vfloat8 a, vfloat8 b) { return _mm256_sub_ps(a.m, b.m); }
    friend vfloat8 operator*(vfloat8 a, vfloat8 b) { return _mm256_mul_ps(a.m, b.m); }
    friend vfloat8 operator/(vfloat8 a, vfloat8 b) { return _mm256_div_ps(a.m, b.m); }
    friend vfloat8 operator-(vfloat8 a) { return _mm256_xor_ps(a.m, _mm256_set1_ps(-0.0f)); }
    friend vbool8 operator<(vfloat8 a, vfloat8 b) { return _mm256_cmp_ps(a.m, b.m, _CMP_LT_OQ); }
    friend vbool8 operator<=(vfloat8 a, vfloat8 b) { return _mm256_cmp_ps(a.m, b.m, _CMP_LE_OQ); }
    friend vbool8 operator>(vfloat8 a, vfloat8 b) { return _mm256_cmp_ps(a.m, b.m, _CMP_GT_OQ); }
    friend vbool8 operator>=(vfloat8 a, vfloat8 b) { return _mm256_cmp_ps(a.m, b.m, _CMP_GE_OQ); }
    friend vbool8 operator==(vfloat8 a, vfloat8 b) { return _mm256_cmp_ps(a.m, b.m, _CMP_EQ_OQ); }
};
inline vfloat8 min(vfloat8 a, vfloat8 b) { return _mm256_min_ps(a.m, b.m); }
inline vfloat8 max(vfloat8 a, vfloat8 b) { return _mm256_max_ps(a.m, b.m); }
inline vfloat8 abs(vfloat8 a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.m); }
inline vfloat8 signBit(vfloat8 a) { return _mm256_and_ps(a.m, _mm256_set1_ps(-0.0f)); }
inline vfloat8 bitXor(vfloat8 a, vfloat8 b) { return _mm256_xor_ps(a.m, b.m); }
inline vfloat8 select(vbool8 m, vfloat8 a, vfloat8 b) { return _mm256_blendv_ps(b.m, a.m, m.m); }
inline vfloat8 fmadd(vfloat8 a, vfloat8 b, vfloat8 c) { return _mm256_fmadd_ps(a.m, b.m, c.m); }
inline vfloat8 fmsub(vfloat8 a, vfloat8 b, vfloat8 c) { return _mm256_fmsub_ps(a.m, b.m, c.m); }
inline vfloat8 fnmadd(vfloat8 a, vfloat8 b, vfloat8 c) { return _mm256_fnmadd_ps(a.m, b.m, c.m); }
inline vfloat8 gather(const float* base, vint8 index) { return _mm256_i32gather_ps(base, index.m, 4); }
inline vint8 gather(const int32_t* base, vint8 index) {
    return _mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index.m, 4);
}
inline float reduceMin(vfloat8 a) {
    __m128 m = _mm_min_ps(_mm256_castps256_ps128(a.m), _mm256_extractf128_ps(a.m, 1));
    m = _mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    m = _mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    return _mm_cvtss_f32(m);
}
/// Lane i: the least lane of v[i] (eight reductions at once: halves folded, then a 4x4 transpose in
/// each 128-bit half).
inline vfloat8 transposeMin(const vfloat8 (&v)[8]) {
    __m256 w[4];
    for (int i = 0; i < 4; ++i)  // lanes 0-3: partial minima of v[i], 4-7: of v[i + 4]
        w[i] = _mm256_min_ps(_mm256_permute2f128_ps(v[i].m, v[i + 4].m, 0x20),
                             _mm256_permute2f128_ps(v[i].m, v[i + 4].m, 0x31));
    const __m256 t0 = _mm256_unpacklo_ps(w[0], w[1]), t1 = _mm256_unpackhi_ps(w[0], w[1]);
    const __m256 t2 = _mm256_unpacklo_ps(w[2], w[3]), t3 = _mm256_unpackhi_ps(w[2], w[3]);
    return _mm256_min_ps(_mm256_min_ps(_mm256_shuffle_ps(t0, t2, 0x44), _mm256_shuffle_ps(t0, t2, 0xEE)),
                         _mm256_min_ps(_mm256_shuffle_ps(t1, t3, 0x44), _mm256_shuffle_ps(t1, t3, 0xEE)));
}
inline vfloat8 fromQuarters8(const vfloat4* q) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(q[0].m), q[1].m, 1);
}
inline vbool8 isFinite(vfloat8 a) { return abs(a) < vfloat8(__builtin_huge_valf()); }

} // namespace simd
} // namespace WIDERAY_ISA
} // namespace wideray
