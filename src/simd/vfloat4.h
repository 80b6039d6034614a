#pragma once
// 4-wide SSE4.2 vectors: vfloat4, vint4, vbool4.
#include <nmmintrin.h>
#if defined(__FMA__)
#include <immintrin.h>
#endif

#include <cstdint>

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace simd {

struct vbool4 {
    __m128 m;
    vbool4() = default;
    vbool4(__m128 v) : m(v) {}
    explicit vbool4(bool b) : m(_mm_castsi128_ps(_mm_set1_epi32(b ? -1 : 0))) {}
    friend vbool4 operator&(vbool4 a, vbool4 b) { return _mm_and_ps(a.m, b.m); }
    friend vbool4 operator|(vbool4 a, vbool4 b) { return _mm_or_ps(a.m, b.m); }
    friend vbool4 operator^(vbool4 a, vbool4 b) { return _mm_xor_ps(a.m, b.m); }
    friend vbool4 andNot(vbool4 a, vbool4 b) { return _mm_andnot_ps(b.m, a.m); }  ///< a & ~b
    vbool4& operator&=(vbool4 b) { return *this = *this & b; }
    vbool4& operator|=(vbool4 b) { return *this = *this | b; }
};
inline uint32_t movemask(vbool4 b) { return uint32_t(_mm_movemask_ps(b.m)); }
inline bool any(vbool4 b) { return movemask(b) != 0; }
inline bool all(vbool4 b) { return movemask(b) == 0xF; }
inline bool none(vbool4 b) { return movemask(b) == 0; }
inline vbool4 maskFromBits4(uint32_t bits) {
    __m128i lane = _mm_set_epi32(8, 4, 2, 1);
    __m128i m = _mm_and_si128(_mm_set1_epi32(int(bits)), lane);
    return _mm_castsi128_ps(_mm_cmpeq_epi32(m, lane));
}

struct vint4 {
    __m128i m;
    vint4() = default;
    vint4(__m128i v) : m(v) {}
    vint4(int32_t s) : m(_mm_set1_epi32(s)) {}
    static vint4 load(const int32_t* p) { return _mm_load_si128(reinterpret_cast<const __m128i*>(p)); }
    static vint4 loadu(const void* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
    void store(int32_t* p) const { _mm_store_si128(reinterpret_cast<__m128i*>(p), m); }
    friend vint4 operator+(vint4 a, vint4 b) { return _mm_add_epi32(a.m, b.m); }
    friend vint4 operator&(vint4 a, vint4 b) { return _mm_and_si128(a.m, b.m); }
    friend vbool4 operator==(vint4 a, vint4 b) { return _mm_castsi128_ps(_mm_cmpeq_epi32(a.m, b.m)); }
    friend vbool4 operator!=(vint4 a, vint4 b) { return andNot(vbool4(true), a == b); }
    friend vbool4 operator<(vint4 a, vint4 b) { return _mm_castsi128_ps(_mm_cmplt_epi32(a.m, b.m)); }
};
inline vint4 select(vbool4 m, vint4 a, vint4 b) {
    return _mm_castps_si128(_mm_blendv_ps(_mm_castsi128_ps(b.m), _mm_castsi128_ps(a.m), m.m));
}

struct vfloat4 {
    __m128 m;
    static constexpr int size = 4;
    vfloat4() = default;
    vfloat4(__m128 v) : m(v) {}
    vfloat4(float s) : m(_mm_set1_ps(s)) {}
    static vfloat4 load(const float* p) { return _mm_load_ps(p); }
    static vfloat4 loadu(const float* p) { return _mm_loadu_ps(p); }
    void store(float* p) const { _mm_store_ps(p, m); }
    friend vfloat4 operator+(vfloat4 a, vfloat4 b) { return _mm_add_ps(a.m, b.m); }
    friend vfloat4 operator-(vfloat4 a, vfloat4 b) { return _mm_sub_ps(a.m, b.m); }
    friend vfloat4 operator*(vfloat4 a, vfloat4 b) { return _mm_mul_ps(a.m, b.m); }
    friend vfloat4 operator/(vfloat4 a, vfloat4 b) { return _mm_div_ps(a.m, b.m); }
    friend vfloat4 operator-(vfloat4 a) { return _mm_xor_ps(a.m, _mm_set1_ps(-0.0f)); }
    friend vbool4 operator<(vfloat4 a, vfloat4 b) { return _mm_cmplt_ps(a.m, b.m); }
    friend vbool4 operator<=(vfloat4 a, vfloat4 b) { return _mm_cmple_ps(a.m, b.m); }
    friend vbool4 operator>(vfloat4 a, vfloat4 b) { return _mm_cmpgt_ps(a.m, b.m); }
    friend vbool4 operator>=(vfloat4 a, vfloat4 b) { return _mm_cmpge_ps(a.m, b.m); }
    friend vbool4 operator==(vfloat4 a, vfloat4 b) { return _mm_cmpeq_ps(a.m, b.m); }
};
/// min/max return b when either is NaN, exactly like the scalar `a < b ? a : b`.
inline vfloat4 min(vfloat4 a, vfloat4 b) { return _mm_min_ps(a.m, b.m); }
inline vfloat4 max(vfloat4 a, vfloat4 b) { return _mm_max_ps(a.m, b.m); }
inline vfloat4 abs(vfloat4 a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a.m); }
inline vfloat4 signBit(vfloat4 a) { return _mm_and_ps(a.m, _mm_set1_ps(-0.0f)); }
inline vfloat4 bitXor(vfloat4 a, vfloat4 b) { return _mm_xor_ps(a.m, b.m); }
inline vfloat4 select(vbool4 m, vfloat4 a, vfloat4 b) { return _mm_blendv_ps(b.m, a.m, m.m); }
#if defined(__FMA__)
inline vfloat4 fmadd(vfloat4 a, vfloat4 b, vfloat4 c) { return _mm_fmadd_ps(a.m, b.m, c.m); }
inline vfloat4 fmsub(vfloat4 a, vfloat4 b, vfloat4 c) { return _mm_fmsub_ps(a.m, b.m, c.m); }
inline vfloat4 fnmadd(vfloat4 a, vfloat4 b, vfloat4 c) { return _mm_fnmadd_ps(a.m, b.m, c.m); }
#else
inline vfloat4 fmadd(vfloat4 a, vfloat4 b, vfloat4 c) { return a * b + c; }
inline vfloat4 fmsub(vfloat4 a, vfloat4 b, vfloat4 c) { return a * b - c; }
inline vfloat4 fnmadd(vfloat4 a, vfloat4 b, vfloat4 c) { return c - a * b; }
#endif
inline vfloat4 gather(const float* base, vint4 index) {
    alignas(16) int32_t i[4];
    index.store(i);
    return _mm_setr_ps(base[i[0]], base[i[1]], base[i[2]], base[i[3]]);
}
inline vint4 gather(const int32_t* base, vint4 index) {
    alignas(16) int32_t i[4];
    index.store(i);
    return _mm_setr_epi32(base[i[0]], base[i[1]], base[i[2]], base[i[3]]);
}
inline float reduceMin(vfloat4 a) {
    __m128 m = _mm_min_ps(a.m, _mm_shuffle_ps(a.m, a.m, _MM_SHUFFLE(2, 3, 0, 1)));
    m = _mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    return _mm_cvtss_f32(m);
}
/// Lane i: the least lane of v[i] (four reductions at once, by a transpose).
inline vfloat4 transposeMin(const vfloat4 (&v)[4]) {
    __m128 a = v[0].m, b = v[1].m, c = v[2].m, d = v[3].m;
    _MM_TRANSPOSE4_PS(a, b, c, d);
    return _mm_min_ps(_mm_min_ps(a, b), _mm_min_ps(c, d));
}
inline vbool4 isFinite(vfloat4 a) { return abs(a) < vfloat4(__builtin_huge_valf()); }

} // namespace simd
} // namespace WIDERAY_ISA
} // namespace wideray
