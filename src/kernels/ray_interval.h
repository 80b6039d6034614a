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
    /// Per axis, the origin bound that gives the near plane's least distance (oHi for positive
    /// directions, oLo for negative ones) and the far plane's largest (the other), picked once.
    float oNear[3], oFar[3];
    float tnear;
};

/// One axis of the interval test: narrows [entry, exit] to where rays with origins in [oLo, oHi] and
/// reciprocal directions in [rLo, rHi], all negative or all positive, can be between the slab's near
/// and far planes, widened by `margin`. (plane - o) * rd is monotonic in o, so its extremes are
/// products with the near plane's farthest origin `oNear` and the far plane's nearest `oFar` (oHi
/// and oLo for positive directions, the other way round for negative ones), and either end of
/// [rLo, rHi]: the same roundings as the least and largest of all four endpoint products.
template <class F>
[[gnu::always_inline]] inline void intervalSlab(const F& nearPlane, const F& farPlane, const F& oNear, const F& oFar,
                                                const F& rLo, const F& rHi, const F& margin, F& entry, F& exit) {
    const F n = nearPlane - oNear;
    const F f = farPlane - oFar;
    entry = max(min(n * rLo, n * rHi) - margin, entry);
    exit = min(max(f * rLo, f * rHi) + margin, exit);
}

/// Widens [entry, exit] by 2^-16 relative, far more than the rounding of the interval products, and
/// returns where the interval enters the box.
template <class F>
[[gnu::always_inline]] inline auto intervalEnters(F& entry, F& exit) {
    const F lowerScale(1.0f - 1.0f / 65536.0f), upperScale(kRobustFarScale);
    entry = select(entry > F(0.0f), entry * lowerScale, entry * upperScale);
    exit = select(exit > F(0.0f), exit * upperScale, exit * lowerScale);
    return entry <= exit;
}

/// Interval test of all N children of a node. The bounds are widened by the interval's margin and
/// then by 2^-16 relative, so that no child that one of the rays' own slab tests enters is lost.
template <int N>
[[gnu::always_inline]] inline uint32_t intersectChildrenInterval(const WideNode<N>& node, const RayInterval& r,
                                                                 float tfarMax, float* tEntryOut) {
    constexpr int W = kNodeSimdWidth<N>;
    using F = vfloat<W>;
    uint32_t mask = 0;
    for (int c = 0; c < N; c += W) {
        F entry(r.tnear), exit(tfarMax);
        for (int a = 0; a < 3; ++a)
            intervalSlab(F::load(node.planes(a, r.neg[a]) + c), F::load(node.planes(a, !r.neg[a]) + c), F(r.oNear[a]),
                         F(r.oFar[a]), F(r.rdLo[a]), F(r.rdHi[a]), F(r.margin[a]), entry, exit);
        const auto enters = intervalEnters(entry, exit);
        entry.store(tEntryOut + c);
        mask |= movemask(enters) << c;
    }
    return mask;
}

/// Reciprocal bounds with infinities (zero direction components) clamped, so that 0 * inf cannot
/// appear in the interval products; F is float or a vector of bundles.
template <class F>
inline void clampReciprocals(F& rdLo, F& rdHi) {
    rdLo = max(rdLo, F(-3.0e38f));
    rdHi = min(rdHi, F(3.0e38f));
}

/// The interval's margin along one axis (RayInterval::margin) from its bounds.
template <class F>
inline F intervalMargin(const F& oLo, const F& oHi, const F& rdLo, const F& rdHi) {
    return F(0x1p-21f) * max(abs(oLo), abs(oHi)) * max(abs(rdLo), abs(rdHi));
}

/// Accumulates the bounds of the valid lanes of K-wide packets into a RayInterval.
template <int K>
struct RayBounds {
    using F = vfloat<K>;
    F oLo[3], oHi[3], rLo[3], rHi[3];
    F tn = F(__builtin_huge_valf());

    // Inlined, so that the bounds stay in registers (as calls they went through memory: 6% of 8-ray
    // shadow packets' time from inside the kitchen).
    [[gnu::always_inline]] RayBounds() {
        const F inf(__builtin_huge_valf());
        for (int a = 0; a < 3; ++a) oLo[a] = rLo[a] = inf, oHi[a] = rHi[a] = -inf;
    }

    [[gnu::always_inline]] void add(const PacketRay<K>& p, const vbool<K>& lanes) {
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
    [[gnu::always_inline]] RayInterval interval(const PacketRay<K>& sameOctant) const {
        RayInterval iv;
        iv.neg[0] = sameOctant.negXs; iv.neg[1] = sameOctant.negYs; iv.neg[2] = sameOctant.negZs;
        for (int a = 0; a < 3; ++a) {
            iv.oLo[a] = reduceMin(oLo[a]); iv.oHi[a] = reduceMax(oHi[a]);
            // Infinite reciprocals (zero direction components) clamped, so that 0 * inf cannot appear.
            iv.rdLo[a] = reduceMin(rLo[a]); iv.rdHi[a] = reduceMax(rHi[a]);
            clampReciprocals(iv.rdLo[a], iv.rdHi[a]);
            iv.margin[a] = intervalMargin(iv.oLo[a], iv.oHi[a], iv.rdLo[a], iv.rdHi[a]);
            iv.oNear[a] = iv.neg[a] ? iv.oLo[a] : iv.oHi[a];
            iv.oFar[a] = iv.neg[a] ? iv.oHi[a] : iv.oLo[a];
        }
        iv.tnear = reduceMin(tn);
        return iv;
    }
};

/// The intervals of the P sub-packets of a large packet, lane s for sub-packet s, which share one
/// direction octant: one box is tested against all of them at once (a leaf's, before its sub-packets
/// test it ray by ray). Each lane's test is intersectChildrenInterval's for that sub-packet's interval,
/// and as conservative. Lanes of sub-packets without rays left never enter.
template <int P>
struct SubPacketIntervals {
    static constexpr int W = P < kMaxWidth ? P : kMaxWidth;
    using F = vfloat<W>;
    /// Origin bounds as RayInterval::oNear and oFar, reciprocal direction bounds, margins.
    alignas(64) float oNear[3][P], oFar[3][P], rdLo[3][P], rdHi[3][P], margin[3][P];
    alignas(64) float tnear[P], tfar[P];  ///< tfar: the farthest culling distance of the sub-packet's rays
    bool neg[3];

    /// Bounds the sub-packets in `live` (bit s: sub-packet s) of a packet whose interval is `whole`:
    /// their origins and reciprocal directions as RayBounds::interval bounds a packet's, and the
    /// farthest culling distance of their rays not done. The others never enter.
    template <int K>
    void bound(const PacketRay<K>* packets, const PacketHit<K>* hits, const vbool<K>* valid, const vbool<K>* done,
               uint64_t live, const RayInterval& whole) {
        static_assert(W == K, "one vector of lanes per sub-packet");
        using V = vfloat<K>;
        const V inf(__builtin_huge_valf());
        for (int a = 0; a < 3; ++a) neg[a] = whole.neg[a];
        for (int g = 0; g < P; g += K) {
            // The least (or with Largest, the largest) of a value over each sub-packet's lanes in `lanes`.
            auto reduce = [&]<bool Largest>(auto value, auto lanes, float* out) {
                V q[K];
                for (int s = 0; s < K; ++s) q[s] = select(lanes(g + s), Largest ? -value(g + s) : value(g + s), inf);
                const V r = transposeMin(q);
                (Largest ? -r : r).store(out + g);
            };
            auto validLanes = [&](int s) { return valid[s]; };
            for (int a = 0; a < 3; ++a) {
                const auto o = [&](int s) {
                    const PacketRay<K>& p = packets[s];
                    return a == 0 ? p.ox : a == 1 ? p.oy : p.oz;
                };
                const auto rd = [&](int s) {
                    const PacketRay<K>& p = packets[s];
                    return a == 0 ? p.slab.rdx : a == 1 ? p.slab.rdy : p.slab.rdz;
                };
                float* oLo = neg[a] ? oNear[a] : oFar[a];
                float* oHi = neg[a] ? oFar[a] : oNear[a];
                if (whole.oLo[a] == whole.oHi[a]) {  // one origin for all rays (a pinhole camera's)
                    V(whole.oLo[a]).store(oLo + g);
                    V(whole.oLo[a]).store(oHi + g);
                } else {
                    reduce.template operator()<false>(o, validLanes, oLo);
                    reduce.template operator()<true>(o, validLanes, oHi);
                }
                reduce.template operator()<false>(rd, validLanes, rdLo[a]);
                reduce.template operator()<true>(rd, validLanes, rdHi[a]);
            }
            reduce.template operator()<false>([&](int s) { return packets[s].tnear; }, validLanes, tnear);
            reduce.template operator()<true>([&](int s) { return hits[s].t; },
                                             [&](int s) { return andNot(valid[s], done[s]); }, tfar);
            for (int a = 0; a < 3; ++a) {
                V lo = V::load(rdLo[a] + g), hi = V::load(rdHi[a] + g);
                clampReciprocals(lo, hi);
                lo.store(rdLo[a] + g);
                hi.store(rdHi[a] + g);
                intervalMargin(V::load(oNear[a] + g), V::load(oFar[a] + g), lo, hi).store(margin[a] + g);
            }
        }
        for (int s = 0; s < P; ++s)
            if (!(live >> s & 1)) retire(s);
    }

    void retire(int s) {
        for (int a = 0; a < 3; ++a) oNear[a][s] = oFar[a][s] = rdLo[a][s] = rdHi[a][s] = margin[a][s] = 0.0f;
        tnear[s] = __builtin_huge_valf();
        tfar[s] = -__builtin_huge_valf();
    }

    /// The sub-packets whose interval enters the box (bit s: sub-packet s).
    [[gnu::always_inline]] uint64_t enter(const float (&lower)[3], const float (&upper)[3]) const {
        uint64_t mask = 0;
        for (int c = 0; c < P; c += W) {
            F entry = F::load(tnear + c), exit = F::load(tfar + c);
            for (int a = 0; a < 3; ++a)
                intervalSlab(F(neg[a] ? upper[a] : lower[a]), F(neg[a] ? lower[a] : upper[a]), F::load(oNear[a] + c),
                             F::load(oFar[a] + c), F::load(rdLo[a] + c), F::load(rdHi[a] + c),
                             F::load(margin[a] + c), entry, exit);
            mask |= uint64_t(movemask(intervalEnters(entry, exit))) << c;
        }
        return mask;
    }

    /// Sub-packet s's rays now cull beyond tfarMax (-inf: none is left).
    void narrow(int s, float tfarMax) { tfar[s] = tfarMax; }
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
