#pragma once
// The triangle leaves: blocks of kBlockSize triangles against one ray (all triangles of the block
// in one SIMD test) or against a packet (all rays in one SIMD test, triangle after triangle), with
// the reference's watertight arithmetic either way.
#include "accel/triangle_block.h"
#include "kernels/hit_order.h"
#include "kernels/ray_state.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// One ray's constants for the test of triangle blocks, made once per traversal rather than at every
/// leaf: the watertight constants (TriW = 1, the reference, tests triangle by triangle), or the shear
/// and the origin on the ray's axes broadcast to TriW lanes, with the offsets of a block's coordinate
/// arrays on those axes (a block's arrays are picked by offset, the ray's axes being scalars).
template <int TriW>
struct BlockRay {
    using F = vfloat<TriW>;
    F sx, sy, sz, ox, oy, oz;
    int kx, ky, kz;  ///< where v0's coordinates on the axes kx, ky, kz begin in TriangleBlock::coordinates()

    BlockRay() = default;
    explicit BlockRay(const WatertightRay<float, int32_t>& w)
        : sx(w.sx), sy(w.sy), sz(w.sz), kx(w.kx * TriW), ky(w.ky * TriW), kz(w.kz * TriW) {
        const float o[3] = {w.ox, w.oy, w.oz};
        ox = F(o[w.kx]);
        oy = F(o[w.ky]);
        oz = F(o[w.kz]);
    }
};

template <>
struct BlockRay<1> {
    WatertightRay<float, int32_t> woop;
    BlockRay() = default;
    explicit BlockRay(const WatertightRay<float, int32_t>& w) : woop(w) {}
};

/// Tests one triangle block; closest-hit updates `hit` (and returns false), any-hit returns true
/// at the first hit.
template <int TriW, bool AnyHit>
[[gnu::always_inline]] inline bool intersectBlock(const TriangleBlock<kBlockSize>& block, const BlockRay<TriW>& r,
                                                  const Ray& ray, Hit& hit) {
    if constexpr (TriW == 1) {
        for (int i = 0; i < kBlockSize && block.primId[i] != kInvalidId; ++i) {
            float t = 0, u = 0, v = 0;
            bool h = intersectWatertight(r.woop, true, block.v0x[i], block.v0y[i], block.v0z[i], block.v1x[i],
                                         block.v1y[i], block.v1z[i], block.v2x[i], block.v2y[i], block.v2z[i],
                                         ray.tnear, hit.t, t, u, v);
            if (!h) continue;
            if constexpr (AnyHit) return true;
            if (isCloser(t, 0, block.primId[i], hit)) hit = {t, u, v, block.primId[i], 0};
        }
        return false;
    } else {
        static_assert(TriW == kBlockSize);
        using F = vfloat<TriW>;
        using I = vint<TriW>;
        const float* c = block.coordinates();
        constexpr int v1 = 3 * TriW, v2 = 6 * TriW;
        auto valid = I::loadu(block.primId) != I(int32_t(kInvalidId));
        F t(0.0f), u(0.0f), v(0.0f);
        auto h = intersectWatertightPermuted(
            r.sx, r.sy, r.sz, valid, F::load(c + r.kx) - r.ox, F::load(c + r.ky) - r.oy, F::load(c + r.kz) - r.oz,
            F::load(c + v1 + r.kx) - r.ox, F::load(c + v1 + r.ky) - r.oy, F::load(c + v1 + r.kz) - r.oz,
            F::load(c + v2 + r.kx) - r.ox, F::load(c + v2 + r.ky) - r.oy, F::load(c + v2 + r.kz) - r.oz,
            F(ray.tnear), F(hit.t), t, u, v);
        uint32_t lanes = movemask(h);
        if (!lanes) return false;
        if constexpr (AnyHit) return true;
        alignas(64) float ts[TriW], us[TriW], vs[TriW];
        t.store(ts); u.store(us); v.store(vs);
        for (; lanes; lanes &= lanes - 1) {
            int i = __builtin_ctz(lanes);
            if (isCloser(ts[i], 0, block.primId[i], hit)) hit = {ts[i], us[i], vs[i], block.primId[i], 0};
        }
        return false;
    }
}

/// All K rays against the triangles of one block. Returns the lanes that hit (for any-hit).
template <int K, bool AnyHit>
[[gnu::always_inline]] inline vbool<K> intersectBlockPacket(const TriangleBlock<kBlockSize>& block, const PacketRay<K>& p,
                                     vbool<K> active, PacketHit<K>& h) {
    using F = vfloat<K>;
    using I = vint<K>;
    vbool<K> anyHit(false);
    for (int j = 0; j < kBlockSize && block.primId[j] != kInvalidId; ++j) {
        F t = h.t, u = h.u, v = h.v;
        vbool<K> hit;
        if (p.uniformAxes) {
            // Triangle j's coordinates on the packet's axes, read from the block by offset (an array of
            // the vertex's three coordinates indexed by axis went through the stack).
            constexpr int M = kBlockSize;
            const float* c = block.coordinates() + j;
            const int x = p.kx * M, y = p.ky * M, z = p.kz * M;
            const float *c0 = c, *c1 = c + 3 * M, *c2 = c + 6 * M;
            hit = intersectWatertightPermuted(p.woop.sx, p.woop.sy, p.woop.sz, active, F(c0[x]) - p.okx,
                                              F(c0[y]) - p.oky, F(c0[z]) - p.okz, F(c1[x]) - p.okx,
                                              F(c1[y]) - p.oky, F(c1[z]) - p.okz, F(c2[x]) - p.okx,
                                              F(c2[y]) - p.oky, F(c2[z]) - p.okz, p.tnear, h.t, t, u, v);
        } else {
            hit = intersectWatertight(p.woop, active, F(block.v0x[j]), F(block.v0y[j]), F(block.v0z[j]),
                                      F(block.v1x[j]), F(block.v1y[j]), F(block.v1z[j]), F(block.v2x[j]),
                                      F(block.v2y[j]), F(block.v2z[j]), p.tnear, h.t, t, u, v);
        }
        if (none(hit)) continue;
        if constexpr (AnyHit) {
            anyHit |= hit;
            active = andNot(active, hit);
            continue;
        }
        I prim(int32_t(block.primId[j]));
        vbool<K> closer = hit & ((t < h.t) | ((t == h.t) & (prim < h.primId)));
        h.t = select(closer, t, h.t);
        h.u = select(closer, u, h.u);
        h.v = select(closer, v, h.v);
        h.primId = select(closer, prim, h.primId);
    }
    return anyHit;
}

/// Any-hit: the active lanes that the block occludes, their t set to -inf (how packets mark an
/// occluded ray).
template <int K>
[[gnu::always_inline]] inline vbool<K> occludeByBlock(const TriangleBlock<kBlockSize>& block, const PacketRay<K>& p,
                                                      const vbool<K>& active, PacketHit<K>& h) {
    const vbool<K> occluded = intersectBlockPacket<K, true>(block, p, active, h);
    h.t = select(occluded, vfloat<K>(-__builtin_huge_valf()), h.t);
    return occluded;
}

} // namespace WIDERAY_ISA
} // namespace wideray
