#pragma once
// Interval arithmetic over a bundle of rays that share a direction octant: the bounds of their
// origins and reciprocal directions test all N children of a node at once, conservatively for every
// ray of the bundle (Wald, Boulos, Shirley 2007; Embree's frustum test of coherent packets).
#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Bounds of the packet's rays, per axis: origins and reciprocal directions (all of one sign).
struct RayInterval {
    float oLo[3], oHi[3], rdLo[3], rdHi[3];
    /// Per axis, a distance at least the rays' own slab tests widen by: they subtract o * rd rounded
    /// outward by an ulp or two (SlabRay), an absolute |o * rd| * 2^-22 that a margin relative to
    /// the distance would miss near origins far from zero.
    float margin[3];
    bool neg[3];
    float tnear;
};

/// Interval test of all N children of a node. The bounds are widened by the interval's margin and
/// then by 2^-16 relative, far more than the rounding of the interval products, so that no child that
/// one of the rays' own slab tests enters is lost.
template <int N>
[[gnu::always_inline]] inline uint32_t intersectChildrenInterval(const WideNode<N>& node, const RayInterval& r,
                                                                 float tfarMax, float* tEntryOut) {
    constexpr int W = kNodeSimdWidth<N>;
    using F = vfloat<W>;
    uint32_t mask = 0;
    for (int c = 0; c < N; c += W) {
        F entry(r.tnear), exit(tfarMax);
        for (int a = 0; a < 3; ++a) {
            const float* nearPlane = node.planes(a, r.neg[a]) + c;
            const float* farPlane = node.planes(a, !r.neg[a]) + c;
            // (plane - o) * rd over o in [oLo, oHi] and rd in [rdLo, rdHi]: the extremes are among
            // the four endpoint products.
            F nLo = F::load(nearPlane) - F(r.oHi[a]), nHi = F::load(nearPlane) - F(r.oLo[a]);
            F fLo = F::load(farPlane) - F(r.oHi[a]), fHi = F::load(farPlane) - F(r.oLo[a]);
            F rLo(r.rdLo[a]), rHi(r.rdHi[a]);
            const F margin(r.margin[a]);
            F t0 = min(min(nLo * rLo, nLo * rHi), min(nHi * rLo, nHi * rHi)) - margin;
            F t1 = max(max(fLo * rLo, fLo * rHi), max(fHi * rLo, fHi * rHi)) + margin;
            entry = max(t0, entry);
            exit = min(t1, exit);
        }
        const F lowerScale(1.0f - 1.0f / 65536.0f), upperScale(kRobustFarScale);
        entry = select(entry > F(0.0f), entry * lowerScale, entry * upperScale);
        exit = select(exit > F(0.0f), exit * upperScale, exit * lowerScale);
        entry.store(tEntryOut + c);
        mask |= movemask(entry <= exit) << c;
    }
    return mask;
}

/// Accumulates the bounds of the valid lanes of K-wide packets into a RayInterval.
template <int K>
struct RayBounds {
    using F = vfloat<K>;
    F oLo[3], oHi[3], rLo[3], rHi[3];
    F tn = F(__builtin_huge_valf());

    RayBounds() {
        const F inf(__builtin_huge_valf());
        for (int a = 0; a < 3; ++a) oLo[a] = rLo[a] = inf, oHi[a] = rHi[a] = -inf;
    }

    void add(const PacketRay<K>& p, const vbool<K>& lanes) {
        const F inf(__builtin_huge_valf());
        const F* o[3] = {&p.ox, &p.oy, &p.oz};
        const F* rd[3] = {&p.slab.rdx, &p.slab.rdy, &p.slab.rdz};
        for (int a = 0; a < 3; ++a) {
            oLo[a] = min(select(lanes, *o[a], inf), oLo[a]);
            oHi[a] = max(select(lanes, *o[a], -inf), oHi[a]);
            rLo[a] = min(select(lanes, *rd[a], inf), rLo[a]);
            rHi[a] = max(select(lanes, *rd[a], -inf), rHi[a]);
        }
        tn = min(select(lanes, p.tnear, inf), tn);
    }

    /// The interval of the lanes added, which share the direction octant of `sameOctant` (a packet of
    /// uniform octant).
    RayInterval interval(const PacketRay<K>& sameOctant) const {
        RayInterval iv;
        iv.neg[0] = sameOctant.negXs; iv.neg[1] = sameOctant.negYs; iv.neg[2] = sameOctant.negZs;
        for (int a = 0; a < 3; ++a) {
            iv.oLo[a] = reduceMin(oLo[a]); iv.oHi[a] = -reduceMin(-oHi[a]);
            // Infinite reciprocals (zero direction components) clamped, so that 0 * inf cannot appear.
            iv.rdLo[a] = max(reduceMin(rLo[a]), -3.0e38f); iv.rdHi[a] = min(-reduceMin(-rHi[a]), 3.0e38f);
            iv.margin[a] = 0x1p-21f * max(abs(iv.oLo[a]), abs(iv.oHi[a])) * max(abs(iv.rdLo[a]), abs(iv.rdHi[a]));
        }
        iv.tnear = reduceMin(tn);
        return iv;
    }
};

/// Interval bounds are only tight for nearly parallel rays (a camera tile, shadow rays from
/// neighbouring pixels): past about 6 degrees of spread, K-wide packets are faster.
inline bool narrowEnough(const RayInterval& iv) {
    float spread = 0.0f, extent = 0.0f;
    for (int a = 0; a < 3; ++a) {
        float dLo = 1.0f / iv.rdHi[a], dHi = 1.0f / iv.rdLo[a];
        spread = max(spread, dHi - dLo);
        extent = max(extent, max(abs(dLo), abs(dHi)));
    }
    return spread <= 0.1f * extent;
}

} // namespace WIDERAY_ISA
} // namespace wideray
