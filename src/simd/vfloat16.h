#pragma once
// 16-wide AVX-512 (F/VL/BW/DQ) vectors: vfloat16, vint16, vbool16 (a k-mask).
#include <immintrin.h>

#include <cstdint>

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace simd {

struct vbool16 {
    __mmask16 m;
    vbool16() = default;
    vbool16(__mmask16 v) : m(v) {}
    explicit vbool16(bool b) : m(b ? 0xFFFF : 0) {}
    friend vbool16 operator&(vbool16 a, vbool16 b) { return __mmask16(a.m & b.m); }
    friend vbool16 operator|(vbool16 a, vbool16 b) { return __mmask16(a.m | b.m); }
    friend vbool16 operator^(vbool16 a, vbool16 b) { return __mmask16(a.m ^ b.m); }
    friend vbool16 andNot(vbool16 a, vbool16 b) { return __mmask16(a.m & ~b.m); }
    vbool16& operator&=(vbool16 b) { return *this = *this & b; }
    vbool16& operator|=(vbool16 b) { return *this = *this | b; }
};
inline uint32_t movemask(vbool16 b) { return b.m; }
inline bool any(vbool16 b) { return b.m != 0; }
inline bool all(vbool16 b) { return b.m == 0xFFFF; }
inline bool none(vbool16 b) { return b.m == 0; }
inline vbool16 maskFromBits16(uint32_t bits) { return __mmask16(bits); }

struct vint16 {
    __m512i m;
    vint16() = default;
    vint16(__m512i v) : m(v) {}
    vint16(int32_t s) : m(_mm512_set1_epi32(s)) {}
    static vint16 load(const int32_t* p) { return _mm512_load_si512(p); }
    static vint16 loadu(const void* p) { return _mm512_loadu_si512(p); }
    void store(int32_t* p) const { _mm512_store_si512(p, m); }
    friend vint16 operator+(vint16 a, vint16 b) { return _mm512_add_epi32(a.m, b.m); }
    friend vint16 operator&(vint16 a, vint16 b) { return _mm512_and_si512(a.m, b.m); }
    friend vbool16 operator==(vint16 a, vint16 b) { return _mm512_cmpeq_epi32_mask(a.m, b.m); }
    friend vbool16 operator!=(vint16 a, vint16 b) { return _mm512_cmpneq_epi32_mask(a.m, b.m); }
    friend vbool16 operator<(vint16 a, vint16 b) { return _mm512_cmplt_epi32_mask(a.m, b.m); }
};
inline vint16 select(vbool16 m, vint16 a, vint16 b) { return _mm512_mask_blend_epi32(m.m, b.m, a.m); }

struct vfloat16 {
    __m512 m;
    static constexpr int size = 16;
    vfloat16() = default;
    vfloat16(__m512 v) : m(v) {}
    vfloat16(float s) : m(_mm512_set1_ps(s)) {}
    static vfloat16 load(const float* p) { return _mm512_load_ps(p); }
    static vfloat16 loadu(const float* p) { return _mm512_loadu_ps(p); }
    void store(float* p) const { _mm512_store_ps(p, m); }
    friend vfloat16 operator+(vfloat16 a, vfloat16 b) { return _mm512_add_ps(a.m, b.m); }
    friend vfloat16 operator-(vfloat16 a, vfloat16 b) { return _mm512_sub_ps(a.m, b.m); }
    friend vfloat16 operator*(vfloat16 a, vfloat16 b) { return _mm512_mul_ps(a.m, b.m); }
    friend vfloat16 operator/(vfloat16 a, vfloat16 b) { return _mm512_div_ps(a.m, b.m); }
    friend vfloat16 operator-(vfloat16 a) {
        return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.m), _mm512_set1_epi32(INT32_MIN)));
    }
    friend vbool16 operator<(vfloat16 a, vfloat16 b) { return _mm512_cmp_ps_mask(a.m, b.m, _CMP_LT_OQ); }
    friend vbool16 operator<=(vfloat16 a, vfloat16 b) { return _mm512_cmp_ps_mask(a.m, b.m, _CMP_LE_OQ); }
    friend vbool16 operator>(vfloat16 a, vfloat16 b) { return _mm512_cmp_ps_mask(a.m, b.m, _CMP_GT_OQ); }
    friend vbool16 operator>=(vfloat16 a, vfloat16 b) { return _mm512_cmp_ps_mask(a.m, b.m, _CMP_GE_OQ); }
    friend vbool16 operator==(vfloat16 a, vfloat16 b) { return _mm512_cmp_ps_mask(a.m, b.m, _CMP_EQ_OQ); }
};
/// AVX-512 min/max, like SSE's, return the second operand when either is NaN.
inline vfloat16 min(vfloat16 a, vfloat16 b) { return _mm512_min_ps(a.m, b.m); }
inline vfloat16 max(vfloat16 a, vfloat16 b) { return _mm512_max_ps(a.m, b.m); }
inline vfloat16 abs(vfloat16 a) { return _mm512_abs_ps(a.m); }
inline vfloat16 signBit(vfloat16 a) {
    return _mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(a.m), _mm512_set1_epi32(INT32_MIN)));
}
inline vfloat16 bitXor(vfloat16 a, vfloat16 b) {
    return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.m), _mm512_castps_si512(b.m)));
}
inline vfloat16 select(vbool16 m, vfloat16 a, vfloat16 b) { return _mm512_mask_blend_ps(m.m, b.m, a.m); }
inline vfloat16 fmadd(vfloat16 a, vfloat16 b, vfloat16 c) { return _mm512_fmadd_ps(a.m, b.m, c.m); }
inline vfloat16 fmsub(vfloat16 a, vfloat16 b, vfloat16 c) { return _mm512_fmsub_ps(a.m, b.m, c.m); }
inline vfloat16 fnmadd(vfloat16 a, vfloat16 b, vfloat16 c) { return _mm512_fnmadd_ps(a.m, b.m, c.m); }
// The masked forms: GCC 12 warns that the unmasked ones read an uninitialized source.
inline vfloat16 gather(const float* base, vint16 index) {
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), 0xFFFF, index.m, base, 4);
}
inline vint16 gather(const int32_t* base, vint16 index) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xFFFF, index.m, base, 4);
}
/// Writes the lanes of `values` selected by `mask` contiguously to out, and whatever fills the rest of
/// 16 lanes after them (out has room for 16); returns how many are selected. Compressing in a register
/// and storing whole is much faster than the masked compress to memory on Zen 4.
inline int compressStore(int32_t* out, vint16 values, vbool16 mask) {
    _mm512_storeu_si512(out, _mm512_maskz_compress_epi32(mask.m, values.m));
    return __builtin_popcount(mask.m);
}
inline int compressStore(float* out, vfloat16 values, vbool16 mask) {
    _mm512_storeu_ps(out, _mm512_maskz_compress_ps(mask.m, values.m));
    return __builtin_popcount(mask.m);
}
inline float reduceMin(vfloat16 a) { return _mm512_reduce_min_ps(a.m); }
/// Lane i: the least lane of v[i] (sixteen reductions at once: 128-bit blocks folded twice, then a
/// 4x4 transpose in each block and the blocks put in order).
inline vfloat16 transposeMin(const vfloat16 (&v)[16]) {
    __m512 w[8], x[4];
    for (int i = 0; i < 8; ++i)  // blocks 0-1: partial minima of v[i], 2-3: of v[i + 8]
        w[i] = _mm512_min_ps(_mm512_shuffle_f32x4(v[i].m, v[i + 8].m, 0x44),
                             _mm512_shuffle_f32x4(v[i].m, v[i + 8].m, 0xEE));
    for (int i = 0; i < 4; ++i)  // blocks: v[i], v[i + 8], v[i + 4], v[i + 12]
        x[i] = _mm512_min_ps(_mm512_shuffle_f32x4(w[i], w[i + 4], 0x88), _mm512_shuffle_f32x4(w[i], w[i + 4], 0xDD));
    const __m512 t0 = _mm512_unpacklo_ps(x[0], x[1]), t1 = _mm512_unpackhi_ps(x[0], x[1]);
    const __m512 t2 = _mm512_unpacklo_ps(x[2], x[3]), t3 = _mm512_unpackhi_ps(x[2], x[3]);
    const __m512 m = _mm512_min_ps(_mm512_min_ps(_mm512_shuffle_ps(t0, t2, 0x44), _mm512_shuffle_ps(t0, t2, 0xEE)),
                                   _mm512_min_ps(_mm512_shuffle_ps(t1, t3, 0x44), _mm512_shuffle_ps(t1, t3, 0xEE)));
    return _mm512_shuffle_f32x4(m, m, 0xD8);
}
inline vfloat16 fromQuarters16(const vfloat4* q) {
    __m512 v = _mm512_castps128_ps512(q[0].m);
    v = _mm512_insertf32x4(v, q[1].m, 1);
    v = _mm512_insertf32x4(v, q[2].m, 2);
    return _mm512_insertf32x4(v, q[3].m, 3);
}
inline vbool16 isFinite(vfloat16 a) { return abs(a) < vfloat16(__builtin_huge_valf()); }

} // namespace simd
} // namespace WIDERAY_ISA
} // namespace wideray
