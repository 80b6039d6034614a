#pragma once
// Ray against the N child boxes of a wide node (the slab test, Kay and Kajiya 1986), with the
// reciprocal direction precomputed once per ray and near/far planes chosen once from its signs.
#include <cstdint>

#include "accel/wide_bvh.h"
#include "simd/simd.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Far distances are scaled up by 1 + 2^-16, far more than the slab test's rounding error (Ize 2013,
/// "Robust BVH Ray Traversal"), so that a box is never culled before a triangle inside it.
constexpr float kRobustFarScale = 1.0f + 1.0f / 65536.0f;

struct BoxRay {
    float ox, oy, oz;
    float rdx, rdy, rdz;
    bool negX, negY, negZ;
};

inline BoxRay makeBoxRay(float ox, float oy, float oz, float dx, float dy, float dz) {
    return {ox, oy, oz, 1.0f / dx, 1.0f / dy, 1.0f / dz, dx < 0.0f || std::signbit(dx),
            dy < 0.0f || std::signbit(dy), dz < 0.0f || std::signbit(dz)};
}

/// The slab test, the one every kernel runs: entry and exit distances of rays (origin o, reciprocal
/// direction rd; scalars or vectors) through boxes given by their near and far planes. NaN slabs
/// (0 * inf) drop out: min/max return their second operand.
template <class F>
[[gnu::always_inline]] inline void slabInterval(const F& nearX, const F& farX, const F& nearY, const F& farY,
                                                const F& nearZ, const F& farZ, const F& ox, const F& oy, const F& oz,
                                                const F& rdx, const F& rdy, const F& rdz, const F& tnear,
                                                const F& tfar, F& tEntry, F& tExit) {
    using simd::max;
    using simd::min;
    F tx0 = (nearX - ox) * rdx, tx1 = (farX - ox) * rdx;
    F ty0 = (nearY - oy) * rdy, ty1 = (farY - oy) * rdy;
    F tz0 = (nearZ - oz) * rdz, tz1 = (farZ - oz) * rdz;
    tEntry = max(tx0, max(ty0, max(tz0, tnear)));
    tExit = min(tx1, min(ty1, min(tz1, tfar))) * F(kRobustFarScale);
}

/// The traversal stack's sorted insert: `e` goes into stack[base, sp), kept farthest first by
/// `distance`, so that the nearest entry is popped first. Equal distances keep their push order.
template <class Entry>
[[gnu::always_inline]] inline void pushSorted(Entry* stack, int base, int& sp, const Entry& e) {
    int j = sp++;
    for (; j > base && stack[j - 1].distance < e.distance; --j) stack[j] = stack[j - 1];
    stack[j] = e;
}

/// Tests all N children; returns the bit mask of those hit and writes their entry distances.
/// W = 1 loops over the children with scalar floats (the reference); otherwise SIMD tests of W
/// children at a time (W = N where the ISA is that wide).
template <int N, int W>
inline uint32_t intersectChildren(const WideNode<N>& node, const BoxRay& r, float tnear, float tfar,
                                  float* tEntryOut) {
    const float* nx = r.negX ? node.upperX : node.lowerX;
    const float* fx = r.negX ? node.lowerX : node.upperX;
    const float* ny = r.negY ? node.upperY : node.lowerY;
    const float* fy = r.negY ? node.lowerY : node.upperY;
    const float* nz = r.negZ ? node.upperZ : node.lowerZ;
    const float* fz = r.negZ ? node.lowerZ : node.upperZ;
    if constexpr (W == 1) {
        uint32_t mask = 0;
        for (int i = 0; i < N; ++i) {
            float tEntry, tExit;
            slabInterval(nx[i], fx[i], ny[i], fy[i], nz[i], fz[i], r.ox, r.oy, r.oz, r.rdx, r.rdy, r.rdz, tnear, tfar,
                         tEntry, tExit);
            tEntryOut[i] = tEntry;
            mask |= uint32_t(tEntry <= tExit) << i;
        }
        return mask;
    } else {
        static_assert(N % W == 0);
        using F = simd::vfloat<W>;
        uint32_t mask = 0;
        for (int c = 0; c < N; c += W) {
            F tEntry, tExit;
            slabInterval(F::load(nx + c), F::load(fx + c), F::load(ny + c), F::load(fy + c), F::load(nz + c),
                         F::load(fz + c), F(r.ox), F(r.oy), F(r.oz), F(r.rdx), F(r.rdy), F(r.rdz), F(tnear), F(tfar),
                         tEntry, tExit);
            tEntry.store(tEntryOut + c);
            mask |= simd::movemask(tEntry <= tExit) << c;
        }
        return mask;
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
