#pragma once
// Interval arithmetic over a bundle of rays that share a direction octant: the bounds of their
// origins and reciprocal directions test all N children of a node at once, conservatively for every
// ray of the bundle (Wald, Boulos, Shirley 2007; Embree's frustum test of coherent packets).
#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Reciprocal bounds with infinities (zero direction components) clamped, so that 0 * inf cannot
/// appear in the interval products; F is float or a vector of bundles.
template <class F>
inline void clampReciprocals(F& rdLo, F& rdHi) {
    rdLo = max(rdLo, F(-3.0e38f));
    rdHi = min(rdHi, F(3.0e38f));
}

/// One axis of a bundle's interval test in the slab test's form, t = plane * rd - org * rd, one FMA
/// per plane: entries with the bundle's reciprocal of least magnitude and its origin farthest along
/// the direction (the least (plane - o) * rd where the plane is ahead of the origins), exits with
/// the reciprocal of greatest magnitude and the nearest origin (the largest). Where an entry plane is
/// behind some origins, their rays' distance to it is negative and so is the bundle's, which their
/// tnear >= 0 (see narrowEnough) bounds; an exit plane behind every origin culls all rays.
/// The products with the origins are rounded outward and widened by a margin, 2^-20 max |o| max
/// |rd|: at least four times what each ray's own test adds (o * rd rounded outward by two ulps or
/// less, SlabRay), and covering this product's rounding and, in the baseline without FMA, the
/// rounding of plane * rd where it cancels with o * rd. The roundings relative to t are left to
/// intervalEnters' 2^-16. Origins whose products overflow give infinities that never cull, or NaN
/// slabs, which drop out of the min/max as in the rays' own test.
template <class F>
struct IntervalAxis {
    F nearRd, nearOrgRd;  ///< entry t = nearPlane * nearRd - nearOrgRd
    F farRd, farOrgRd;    ///< exit t = farPlane * farRd - farOrgRd
};

/// The interval axis of rays with origins in [oLo, oHi] and reciprocals in [rdLo, rdHi], all negative
/// (neg) or all positive.
template <class F>
[[gnu::always_inline]] inline IntervalAxis<F> makeIntervalAxis(bool neg, const F& oLo, const F& oHi, F rdLo, F rdHi) {
    clampReciprocals(rdLo, rdHi);
    const F margin = F(0x1p-20f) * max(abs(oLo), abs(oHi)) * max(abs(rdLo), abs(rdHi));
    const F oNear = neg ? oLo : oHi, oFar = neg ? oHi : oLo;
    const F nearRd = neg ? rdHi : rdLo, farRd = neg ? rdLo : rdHi;
    return {nearRd, roundedUp(oNear * nearRd) + margin, farRd, roundedDown(oFar * farRd) - margin};
}

/// Bounds of the packet's rays, per axis: origins and reciprocal directions (all of one sign), and
/// the interval test they make.
struct RayInterval {
    float oLo[3], oHi[3], rdLo[3], rdHi[3];
    bool neg[3];
    IntervalAxis<float> axis[3];
    float tnear;
};

/// One axis of the interval test: narrows [entry, exit] to where the bundle's rays can be between the
/// slab's near and far planes.
template <class F>
[[gnu::always_inline]] inline void intervalSlab(const F& nearPlane, const F& farPlane, const F& nearRd,
                                                const F& nearOrgRd, const F& farRd, const F& farOrgRd, F& entry,
                                                F& exit) {
    entry = max(fmsub(nearPlane, nearRd, nearOrgRd), entry);
    exit = min(fmsub(farPlane, farRd, farOrgRd), exit);
}

/// Widens [entry, exit] by 2^-16 relative, far more than the rounding of the interval products, and
/// returns where the interval enters the box. The entry is at least the bundle's tnear, never
/// negative; an exit below zero culls with the widening as without.
template <class F>
[[gnu::always_inline]] inline auto intervalEnters(F& entry, F& exit) {
    entry = entry * F(1.0f - 1.0f / 65536.0f);
    exit = exit * F(kRobustFarScale);
    return entry <= exit;
}

/// Interval test of all N children of a node, widened (IntervalAxis, intervalEnters) so that no
/// child that one of the rays' own slab tests enters is lost.
template <int N>
[[gnu::always_inline]] inline uint32_t intersectChildrenInterval(const WideNode<N>& node, const RayInterval& r,
                                                                 float tfarMax, float* tEntryOut) {
    constexpr int W = kNodeSimdWidth<N>;
    using F = vfloat<W>;
    uint32_t mask = 0;
    for (int c = 0; c < N; c += W) {
        F entry(r.tnear), exit(tfarMax);
        for (int a = 0; a < 3; ++a) {
            const IntervalAxis<float>& x = r.axis[a];
            intervalSlab(F::load(node.planes(a, r.neg[a]) + c), F::load(node.planes(a, !r.neg[a]) + c), F(x.nearRd),
                         F(x.nearOrgRd), F(x.farRd), F(x.farOrgRd), entry, exit);
        }
        const auto enters = intervalEnters(entry, exit);
        entry.store(tEntryOut + c);
        mask |= movemask(enters) << c;
    }
    return mask;
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
            iv.rdLo[a] = reduceMin(rLo[a]); iv.rdHi[a] = reduceMax(rHi[a]);
            iv.axis[a] = makeIntervalAxis(iv.neg[a], iv.oLo[a], iv.oHi[a], iv.rdLo[a], iv.rdHi[a]);
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
    /// The interval axes (IntervalAxis), one lane per sub-packet.
    alignas(64) float nearRd[3][P], nearOrgRd[3][P], farRd[3][P], farOrgRd[3][P];
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
            auto reduce = [&]<bool Largest>(auto value, auto lanes) {
                V q[K];
                for (int s = 0; s < K; ++s) q[s] = select(lanes(g + s), Largest ? -value(g + s) : value(g + s), inf);
                const V r = transposeMin(q);
                return Largest ? -r : r;
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
                const bool oneOrigin = whole.oLo[a] == whole.oHi[a];  // a pinhole camera's
                const V oLo = oneOrigin ? V(whole.oLo[a]) : reduce.template operator()<false>(o, validLanes);
                const V oHi = oneOrigin ? V(whole.oLo[a]) : reduce.template operator()<true>(o, validLanes);
                const IntervalAxis<V> x = makeIntervalAxis(neg[a], oLo, oHi, reduce.template operator()<false>(rd, validLanes),
                                                           reduce.template operator()<true>(rd, validLanes));
                x.nearRd.store(nearRd[a] + g);
                x.nearOrgRd.store(nearOrgRd[a] + g);
                x.farRd.store(farRd[a] + g);
                x.farOrgRd.store(farOrgRd[a] + g);
            }
            reduce.template operator()<false>([&](int s) { return packets[s].tnear; }, validLanes).store(tnear + g);
            reduce.template operator()<true>([&](int s) { return hits[s].t; },
                                             [&](int s) { return andNot(valid[s], done[s]); })
                .store(tfar + g);
        }
        for (int s = 0; s < P; ++s)
            if (!(live >> s & 1)) retire(s);
    }

    void retire(int s) {
        for (int a = 0; a < 3; ++a) nearRd[a][s] = nearOrgRd[a][s] = farRd[a][s] = farOrgRd[a][s] = 0.0f;
        tnear[s] = __builtin_huge_valf();
        tfar[s] = -__builtin_huge_valf();
    }

    /// The sub-packets whose interval enters the box (bit s: sub-packet s).
    [[gnu::always_inline]] uint64_t enter(const float (&lower)[3], const float (&upper)[3]) const {
        uint64_t mask = 0;
        for (int c = 0; c < P; c += W) {
            F entry = F::load(tnear + c), exit = F::load(tfar + c);
            for (int a = 0; a < 3; ++a)
                intervalSlab(F(neg[a] ? upper[a] : lower[a]), F(neg[a] ? lower[a] : upper[a]), F::load(nearRd[a] + c),
                             F::load(nearOrgRd[a] + c), F::load(farRd[a] + c), F::load(farOrgRd[a] + c), entry, exit);
            mask |= uint64_t(movemask(intervalEnters(entry, exit))) << c;
        }
        return mask;
    }

    /// Sub-packet s's rays now cull beyond tfarMax (-inf: none is left).
    void narrow(int s, float tfarMax) { tfar[s] = tfarMax; }
};

/// Interval bounds are only tight for nearly parallel rays (a camera tile, shadow rays from
/// neighbouring pixels): past about 6 degrees of spread, K-wide packets are faster. Rays that start
/// behind their origin (tnear < 0) are left to their own tests (see IntervalAxis).
inline bool narrowEnough(const RayInterval& iv) {
    if (!(iv.tnear >= 0.0f)) return false;
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
