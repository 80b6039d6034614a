#pragma once
// Ray against the N child boxes of a wide node (the slab test, Kay and Kajiya 1986), with the
// reciprocal direction precomputed once per ray and near/far planes chosen once from its signs.
#include <cstdint>
#include <type_traits>

#include "accel/wide_bvh.h"
#include "simd/simd.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Far distances are scaled up by 1 + 2^-16, far more than the slab test's rounding error (Ize 2013,
/// "Robust BVH Ray Traversal"), so that a box is never culled before a triangle inside it.
constexpr float kRobustFarScale = 1.0f + 1.0f / 65536.0f;

/// What the slab test needs of a ray (F = float) or of K rays (vfloat<K>): the reciprocal direction
/// and org * rdir, the latter rounded outward by at least an ulp: up where it is subtracted at entry
/// planes, down at exit planes. Then t = plane * rdir - org * rdir is one FMA per plane, and the
/// rounding of org * rdir can only move an entry earlier or an exit later; the rounding of rdir is a
/// relative error of t (it multiplies plane - org), which kRobustFarScale covers like the FMA's own.
/// Zero direction components make infinite reciprocals: each plane's t is then an infinity of the
/// right sign or NaN, and the NaN slabs drop out of the min/max.
template <class F>
struct SlabRay {
    F rdx, rdy, rdz;
    F upX, upY, upZ;        ///< org * rdir rounded up: subtracted at entry planes
    F downX, downY, downZ;  ///< rounded down: subtracted at exit planes
};

/// x moved up (roundedUp) or down (roundedDown) by at least an ulp and at most two: |x| * 2^-23 is at
/// least an ulp of x, and exact. Infinities the other way give NaN.
template <class F>
[[gnu::always_inline]] inline F roundedUp(const F& x) {
    return x + simd::abs(x) * F(0x1p-23f);
}
template <class F>
[[gnu::always_inline]] inline F roundedDown(const F& x) {
    return x - simd::abs(x) * F(0x1p-23f);
}

template <class F>
inline SlabRay<F> makeSlabRay(F ox, F oy, F oz, F rdx, F rdy, F rdz) {
    const F x = ox * rdx, y = oy * rdy, z = oz * rdz;
    return {rdx, rdy, rdz, roundedUp(x), roundedUp(y), roundedUp(z), roundedDown(x), roundedDown(y), roundedDown(z)};
}

/// One ray's box test: its slab constants, and which of each axis' planes (WideNode::planes index
/// 2 * axis + upper) is its near one, chosen once from the direction's signs.
struct BoxRay {
    SlabRay<float> slab;
    int nearPlane[3], farPlane[3];
};

/// The box test of a ray with these slab constants: near planes from the reciprocal direction's
/// signs (1 / d has d's sign, zeros included).
inline BoxRay makeBoxRay(const SlabRay<float>& slab) {
    BoxRay r;
    r.slab = slab;
    const float rd[3] = {slab.rdx, slab.rdy, slab.rdz};
    for (int a = 0; a < 3; ++a) {
        const int negative = std::signbit(rd[a]) ? 1 : 0;
        r.nearPlane[a] = 2 * a + negative;
        r.farPlane[a] = 2 * a + 1 - negative;
    }
    return r;
}

inline BoxRay makeBoxRay(float ox, float oy, float oz, float dx, float dy, float dz) {
    return makeBoxRay(makeSlabRay(ox, oy, oz, 1.0f / dx, 1.0f / dy, 1.0f / dz));
}

/// The slab test, the one every kernel runs: entry and exit distances of rays through boxes given by
/// their near and far planes, one FMA per plane (see SlabRay). NaN slabs drop out: min/max return
/// their second operand.
template <class F>
[[gnu::always_inline]] inline void slabInterval(const F& nearX, const F& farX, const F& nearY, const F& farY,
                                                const F& nearZ, const F& farZ, const SlabRay<F>& r, const F& tnear,
                                                const F& tfar, F& tEntry, F& tExit) {
    using simd::fmsub;
    using simd::max;
    using simd::min;
    F tx0 = fmsub(nearX, r.rdx, r.upX), tx1 = fmsub(farX, r.rdx, r.downX);
    F ty0 = fmsub(nearY, r.rdy, r.upY), ty1 = fmsub(farY, r.rdy, r.downY);
    F tz0 = fmsub(nearZ, r.rdz, r.upZ), tz1 = fmsub(farZ, r.rdz, r.downZ);
    tEntry = max(tx0, max(ty0, max(tz0, tnear)));
    tExit = min(tx1, min(ty1, min(tz1, tfar))) * F(kRobustFarScale);
}

/// The same slab constants broadcast to W lanes (one ray against W boxes).
template <int W>
inline SlabRay<simd::vfloat<W>> broadcast(const SlabRay<float>& r) {
    using F = simd::vfloat<W>;
    return {F(r.rdx), F(r.rdy), F(r.rdz), F(r.upX), F(r.upY), F(r.upZ), F(r.downX), F(r.downY), F(r.downZ)};
}

/// The traversal stack's sorted insert: `e` goes into stack[base, sp), kept farthest first by
/// `distance`, so that the nearest entry is popped first. Equal distances keep their push order.
template <class Entry>
[[gnu::always_inline]] inline void pushSorted(Entry* stack, int base, int& sp, const Entry& e) {
    int j = sp++;
    for (; j > base && stack[j - 1].distance < e.distance; --j) stack[j] = stack[j - 1];
    stack[j] = e;
}

/// One ray's test of the N children of wide nodes, set up once per traversal: the six plane arrays
/// picked by the ray's octant and the slab constants broadcast to W lanes. W = 1 loops over the
/// children with scalar floats (the reference); otherwise SIMD tests of W children at a time (W = N
/// where the ISA is that wide).
template <int N, int W>
struct ChildBoxTest {
    using F = std::conditional_t<W == 1, float, simd::vfloat<W>>;
    SlabRay<F> slab;
    int nx, fx, ny, fy, nz, fz;  ///< offsets of the near and far plane arrays in WideNode::planes

    explicit ChildBoxTest(const BoxRay& r)
        : nx(r.nearPlane[0] * N), fx(r.farPlane[0] * N), ny(r.nearPlane[1] * N), fy(r.farPlane[1] * N),
          nz(r.nearPlane[2] * N), fz(r.farPlane[2] * N) {
        if constexpr (W == 1)
            slab = r.slab;
        else
            slab = broadcast<W>(r.slab);
    }

    /// Returns the bit mask of the children hit and writes their entry distances.
    [[gnu::always_inline]] uint32_t operator()(const WideNode<N>& node, float tnear, float tfar,
                                               float* tEntryOut) const {
        return test<true>(node, tnear, tfar, tEntryOut);
    }

    /// The mask alone, for traversals that do not order the children.
    [[gnu::always_inline]] uint32_t hits(const WideNode<N>& node, float tnear, float tfar) const {
        return test<false>(node, tnear, tfar, nullptr);
    }

private:
    template <bool StoreEntries>
    [[gnu::always_inline]] uint32_t test(const WideNode<N>& node, float tnear, float tfar, float* tEntryOut) const {
        const float* planes = node.lowerX;  // the six plane arrays, N floats each (WideNode::planes)
        if constexpr (W == 1) {
            uint32_t mask = 0;
            for (int i = 0; i < N; ++i) {
                float tEntry, tExit;
                slabInterval(planes[nx + i], planes[fx + i], planes[ny + i], planes[fy + i], planes[nz + i],
                             planes[fz + i], slab, tnear, tfar, tEntry, tExit);
                if constexpr (StoreEntries) tEntryOut[i] = tEntry;
                mask |= uint32_t(tEntry <= tExit) << i;
            }
            return mask;
        } else {
            static_assert(N % W == 0);
            uint32_t mask = 0;
            for (int c = 0; c < N; c += W) {
                F tEntry, tExit;
                slabInterval(F::load(planes + nx + c), F::load(planes + fx + c), F::load(planes + ny + c),
                             F::load(planes + fy + c), F::load(planes + nz + c), F::load(planes + fz + c), slab,
                             F(tnear), F(tfar), tEntry, tExit);
                if constexpr (StoreEntries) tEntry.store(tEntryOut + c);
                mask |= simd::movemask(tEntry <= tExit) << c;
            }
            return mask;
        }
    }
};

} // namespace WIDERAY_ISA
} // namespace wideray
