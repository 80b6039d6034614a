#pragma once
// Watertight ray/triangle intersection (Woop, Benthin, Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)). Written once for every width: F is float or vfloat<W>, and the lanes are
// rays (packets) or triangles (one ray against a leaf block). All kernels of an ISA run exactly this
// arithmetic (FMA where the ISA has it, stated explicitly: the compiler never contracts on its own),
// so t is bit-identical across the scalar reference, packet and stream kernels of one ISA.
#include <cstdint>
#include <type_traits>

#include "simd/simd.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

using namespace simd;

/// Per-ray precomputation: the dominant axis kz, the other two (kx, ky) and the shear constants.
template <class F, class I>
struct WatertightRay {
    F ox, oy, oz;
    I kx, ky, kz;
    F sx, sy, sz;
};

template <class F, class I>
inline F permute(const F& x, const F& y, const F& z, const I& k) {
    if constexpr (std::is_same_v<I, int32_t>)
        return k == 0 ? x : (k == 1 ? y : z);
    else
        return select(k == I(0), x, select(k == I(1), y, z));
}

template <class F, class I>
inline WatertightRay<F, I> makeWatertightRay(F ox, F oy, F oz, F dx, F dy, F dz) {
    F ax = abs(dx), ay = abs(dy), az = abs(dz);
    auto xDominant = (ax >= ay) & (ax >= az);
    auto yDominant = andNot(ay >= az, xDominant);
    I kz = select(xDominant, I(0), select(yDominant, I(1), I(2)));
    I kx = select(xDominant, I(1), select(yDominant, I(2), I(0)));
    I ky = select(xDominant, I(2), select(yDominant, I(0), I(1)));
    F dkz = permute(dx, dy, dz, kz);
    auto flip = dkz < F(0.0f);  // keep the winding: swap kx and ky for a negative dominant component
    I kxs = select(flip, ky, kx);
    I kys = select(flip, kx, ky);
    WatertightRay<F, I> r;
    r.ox = ox; r.oy = oy; r.oz = oz;
    r.kx = kxs; r.ky = kys; r.kz = kz;
    r.sx = permute(dx, dy, dz, kxs) / dkz;
    r.sy = permute(dx, dy, dz, kys) / dkz;
    r.sz = F(1.0f) / dkz;
    return r;
}

namespace detail {

/// U, V or W recomputed in double when the float result is exactly zero (the paper's fallback),
/// so that an edge shared by two triangles is resolved consistently.
inline float edgeDouble(float ax, float ay, float bx, float by) {
    return float(double(ax) * double(by) - double(ay) * double(bx));
}

template <class F>
inline void recomputeZeroEdges(F& U, F& V, F& W, const F& Ax, const F& Ay, const F& Bx, const F& By,
                               const F& Cx, const F& Cy, uint32_t lanes) {
    if constexpr (std::is_same_v<F, float>) {
        U = edgeDouble(Cx, Cy, Bx, By);
        V = edgeDouble(Ax, Ay, Cx, Cy);
        W = edgeDouble(Bx, By, Ax, Ay);
    } else {
        alignas(64) float u[F::size], v[F::size], w[F::size], ax[F::size], ay[F::size], bx[F::size],
            by[F::size], cx[F::size], cy[F::size];
        U.store(u); V.store(v); W.store(w);
        Ax.store(ax); Ay.store(ay); Bx.store(bx); By.store(by); Cx.store(cx); Cy.store(cy);
        for (; lanes; lanes &= lanes - 1) {
            int i = __builtin_ctz(lanes);
            u[i] = edgeDouble(cx[i], cy[i], bx[i], by[i]);
            v[i] = edgeDouble(ax[i], ay[i], cx[i], cy[i]);
            w[i] = edgeDouble(bx[i], by[i], ax[i], ay[i]);
        }
        U = F::load(u); V = F::load(v); W = F::load(w);
    }
}

} // namespace detail

/// How far the division-free distance test is widened (relative): more than the rounding of
/// T * (1 / det) and of tfar * |det| together, so that it never rejects a hit that the exact test after
/// the division accepts, and the answer does not depend on the order in which triangles are tested.
constexpr float kDistanceTestSlack = 0x1p-20f;

/// The test proper, on vertex coordinates relative to the ray origin and already permuted to the
/// ray's (kx, ky, kz) axes: a = v0 - o, b = v1 - o, c = v2 - o. Returns the lanes where the ray hits
/// with tnear <= t <= tfar, writing t, u and v there (u, v weight v1 and v2). Both faces are hit.
/// The shear and T use FMA where the ISA has it; the edge functions U, V, W do not, since an FMA would
/// round a shared edge differently for the two triangles that share it (the watertightness).
template <class F, class B>
[[gnu::always_inline]] inline B intersectWatertightPermuted(const F& sx, const F& sy, const F& sz, B valid, const F& akx, const F& aky,
                                     const F& akz, const F& bkx, const F& bky, const F& bkz, const F& ckx,
                                     const F& cky, const F& ckz, const F& tnear, const F& tfar, F& t, F& u, F& v) {
    F Ax = fnmadd(sx, akz, akx);
    F Ay = fnmadd(sy, akz, aky);
    F Bx = fnmadd(sx, bkz, bkx);
    F By = fnmadd(sy, bkz, bky);
    F Cx = fnmadd(sx, ckz, ckx);
    F Cy = fnmadd(sy, ckz, cky);

    F U = Cx * By - Cy * Bx;
    F V = Ax * Cy - Ay * Cx;
    F W = Bx * Ay - By * Ax;
    const F zero(0.0f);
    B zeroEdge = valid & ((U == zero) | (V == zero) | (W == zero));
    if (any(zeroEdge)) detail::recomputeZeroEdges(U, V, W, Ax, Ay, Bx, By, Cx, Cy, movemask(zeroEdge));

    B hasNegative = (U < zero) | (V < zero) | (W < zero);
    B hasPositive = (U > zero) | (V > zero) | (W > zero);
    valid = andNot(valid, hasNegative & hasPositive);
    F det = U + V + W;
    valid = andNot(valid, det == zero);
    if (none(valid)) return valid;

    // tnear <= T / det <= tfar without dividing (the paper's form: T against t * det with the sign of
    // det), widened by kDistanceTestSlack; the division follows only for candidates that pass. T sums
    // in det's order, so that where the vertices' sheared depths are equal (and exact), T is exactly
    // that depth times det, and t exact.
    F T = fmadd(W, sz * ckz, fmadd(V, sz * bkz, U * (sz * akz)));
    F absDet = abs(det);
    F signedT = bitXor(T, signBit(det));
    F lo = tnear * absDet, hi = tfar * absDet;
    const F slack(kDistanceTestSlack);
    valid = valid & (signedT >= fnmadd(abs(lo), slack, lo)) & (signedT <= fmadd(abs(hi), slack, hi));
    if (none(valid)) return valid;

    F rcpDet = F(1.0f) / det;
    F tHit = T * rcpDet;
    valid = valid & (tHit >= tnear) & (tHit <= tfar);
    t = select(valid, tHit, t);
    u = select(valid, V * rcpDet, u);
    v = select(valid, W * rcpDet, v);
    return valid;
}

/// The test for a ray (or rays, lane by lane) whose axes may differ per lane.
template <class F, class I, class B>
[[gnu::always_inline]] inline B intersectWatertight(const WatertightRay<F, I>& r, B valid, const F& v0x, const F& v0y, const F& v0z,
                             const F& v1x, const F& v1y, const F& v1z, const F& v2x, const F& v2y,
                             const F& v2z, const F& tnear, const F& tfar, F& t, F& u, F& v) {
    F ax = v0x - r.ox, ay = v0y - r.oy, az = v0z - r.oz;
    F bx = v1x - r.ox, by = v1y - r.oy, bz = v1z - r.oz;
    F cx = v2x - r.ox, cy = v2y - r.oy, cz = v2z - r.oz;
    return intersectWatertightPermuted(r.sx, r.sy, r.sz, valid, permute(ax, ay, az, r.kx), permute(ax, ay, az, r.ky),
                                       permute(ax, ay, az, r.kz), permute(bx, by, bz, r.kx), permute(bx, by, bz, r.ky),
                                       permute(bx, by, bz, r.kz), permute(cx, cy, cz, r.kx), permute(cx, cy, cz, r.ky),
                                       permute(cx, cy, cz, r.kz), tnear, tfar, t, u, v);
}

} // namespace WIDERAY_ISA
} // namespace wideray
