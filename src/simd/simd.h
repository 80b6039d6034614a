#pragma once
// Width-generic SIMD vocabulary: vfloat<W>, vint<W>, vbool<W>. W = 1 maps to float, int32_t and
// bool, so one kernel template compiles as scalar code and as 4/8/16-wide SIMD. The wide types exist
// only in translation units compiled for an ISA that has them.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "simd/vfloat4.h"
#if defined(__AVX2__)
#include "simd/vfloat8.h"
#endif
#if defined(__AVX512F__)
#include "simd/vfloat16.h"
#endif

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace simd {

// Scalar operations with the exact semantics of the vector ones (NaN picks the second operand).
inline float min(float a, float b) { return a < b ? a : b; }
inline float max(float a, float b) { return a > b ? a : b; }
inline float abs(float a) { return std::fabs(a); }
inline float select(bool m, float a, float b) { return m ? a : b; }
inline int32_t select(bool m, int32_t a, int32_t b) { return m ? a : b; }
inline float bitXor(float a, float b) {
    uint32_t x, y;
    std::memcpy(&x, &a, 4);
    std::memcpy(&y, &b, 4);
    x ^= y;
    float r;
    std::memcpy(&r, &x, 4);
    return r;
}
/// a * b + c, a * b - c and c - a * b: fused (one rounding) where the ISA has FMA (AVX2, AVX-512),
/// two roundings on the SSE4.2 baseline. Every width of one ISA rounds alike, which is what keeps each
/// kernel bit-identical to the scalar reference of its own ISA.
#if defined(__FMA__)
inline float fmadd(float a, float b, float c) { return __builtin_fmaf(a, b, c); }
inline float fmsub(float a, float b, float c) { return __builtin_fmaf(a, b, -c); }
inline float fnmadd(float a, float b, float c) { return __builtin_fmaf(-a, b, c); }
#else
inline float fmadd(float a, float b, float c) { return a * b + c; }
inline float fmsub(float a, float b, float c) { return a * b - c; }
inline float fnmadd(float a, float b, float c) { return c - a * b; }
#endif
inline float signBit(float a) { return std::signbit(a) ? -0.0f : 0.0f; }
inline bool isFinite(float a) { return abs(a) < __builtin_huge_valf(); }
inline bool any(bool b) { return b; }
inline bool all(bool b) { return b; }
inline bool none(bool b) { return !b; }
inline bool andNot(bool a, bool b) { return a && !b; }
inline uint32_t movemask(bool b) { return b ? 1u : 0u; }

template <int W> struct Types;
template <> struct Types<1> { using Float = float; using Int = int32_t; using Bool = bool; };
template <> struct Types<4> { using Float = vfloat4; using Int = vint4; using Bool = vbool4; };
#if defined(__AVX2__)
template <> struct Types<8> { using Float = vfloat8; using Int = vint8; using Bool = vbool8; };
#endif
#if defined(__AVX512F__)
template <> struct Types<16> { using Float = vfloat16; using Int = vint16; using Bool = vbool16; };
#endif

/// The largest lane of a vector: the least of its negated lanes, negated (the same value).
template <class V>
inline float reduceMax(const V& a) {
    return -reduceMin(-a);
}

/// Writes the lanes of `values` selected by `mask` contiguously to out (which has room for all lanes);
/// returns how many.
template <class T, class V, class B>
inline int compressStore(T* out, const V& values, const B& mask) {
    alignas(64) T v[sizeof(V) / sizeof(T)];
    values.store(v);
    int n = 0;
    for (uint32_t bits = movemask(mask); bits; bits &= bits - 1) out[n++] = v[__builtin_ctz(bits)];
    return n;
}

/// The widest vector this translation unit's ISA has.
#if defined(__AVX512F__)
constexpr int kMaxWidth = 16;
#elif defined(__AVX2__)
constexpr int kMaxWidth = 8;
#else
constexpr int kMaxWidth = 4;
#endif

template <int W> using vfloat = typename Types<W>::Float;
template <int W> using vint = typename Types<W>::Int;
template <int W> using vbool = typename Types<W>::Bool;

/// The W-wide mask whose lane i is bit i of `bits`.
template <int W>
inline vbool<W> maskFromBits(uint32_t bits) {
    if constexpr (W == 4) return maskFromBits4(bits);
#if defined(__AVX2__)
    else if constexpr (W == 8) return maskFromBits8(bits);
#endif
#if defined(__AVX512F__)
    else if constexpr (W == 16) return maskFromBits16(bits);
#endif
}

/// A W-wide vector whose lanes [4j, 4j + 4) are quarters[j].
template <int W>
inline vfloat<W> fromQuarters(const vfloat4* quarters) {
    if constexpr (W == 4) return quarters[0];
#if defined(__AVX2__)
    else if constexpr (W == 8) return fromQuarters8(quarters);
#endif
#if defined(__AVX512F__)
    else if constexpr (W == 16) return fromQuarters16(quarters);
#endif
}

} // namespace simd
} // namespace WIDERAY_ISA
} // namespace wideray
