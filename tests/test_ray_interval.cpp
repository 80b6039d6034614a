#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/traverse_packet.h"

namespace wideray::test {
namespace {

/// The interval test of a bundle of rays must enter every child that one of its rays' own slab
/// tests enters (the packets test rays only against the children the interval enters). Origins far
/// from zero with boxes close to them (short distances) are where the rays' absolute rounding
/// margin (|o / d| ulps) exceeds a margin relative to t.
TEST(RayInterval, EntersEveryChildThatOneOfItsRaysEnters) {
    constexpr int K = kMaxWidth;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), jitter(-1e-3f, 1e-3f), scale(0.0f, 3.0f);
    int entered = 0, missed = 0;
    for (int bundle = 0; bundle < 4000; ++bundle) {
        const float reach = std::pow(10.0f, scale(random));  // origins at 1 to 1000
        const float o[3] = {reach * unit(random), reach * unit(random), reach * unit(random)};
        float d[3] = {unit(random), unit(random), unit(random)};
        Ray rays[K];
        for (Ray& r : rays) {
            r = {o[0] + jitter(random), o[1] + jitter(random), o[2] + jitter(random),
                 d[0] + jitter(random), d[1] + jitter(random), d[2] + jitter(random), 0.0f,
                 __builtin_huge_valf()};
            // Same octant for all lanes, as the packets require.
            if ((r.dx < 0) != (d[0] < 0)) r.dx = -r.dx;
            if ((r.dy < 0) != (d[1] < 0)) r.dy = -r.dy;
            if ((r.dz < 0) != (d[2] < 0)) r.dz = -r.dz;
        }
        PacketRay<K> p;
        PacketHit<K> h;
        const vbool<K> valid = loadPacket(rays, K, p, h);
        if (!p.uniformOctant) continue;
        RayBounds<K> bounds;
        bounds.add(p, valid);
        const RayInterval interval = bounds.interval(p);
        // Eight thin boxes just around where the first ray is at a short distance: their faces lie
        // within rounding of the rays.
        WideNode<8> node{};
        for (int c = 0; c < 8; ++c) {
            const float t = 1e-3f * float(c + 1) * reach;
            const float at[3] = {rays[0].ox + t * rays[0].dx, rays[0].oy + t * rays[0].dy, rays[0].oz + t * rays[0].dz};
            float lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                const float side = c % 2 ? 1.0f : -1.0f;  // the ray's point just inside or just outside
                lo[a] = std::nextafter(at[a], at[a] + side * reach);
                hi[a] = std::nextafter(lo[a], __builtin_huge_valf());
            }
            node.lowerX[c] = lo[0]; node.upperX[c] = hi[0];
            node.lowerY[c] = lo[1]; node.upperY[c] = hi[1];
            node.lowerZ[c] = lo[2]; node.upperZ[c] = hi[2];
            node.child[c] = NodeRef::inner(uint32_t(c));
        }
        alignas(64) float tEntry[8];
        const uint32_t byInterval = intersectChildrenInterval<8>(node, interval, __builtin_huge_valf(), tEntry);
        for (int c = 0; c < 8; ++c) {
            const uint32_t byRays = movemask(packetChildEntry<8, K>(node, c, p, h.t, valid) < vfloat<K>(__builtin_huge_valf()));
            if (!byRays) continue;
            ++entered;
            if (!(byInterval >> c & 1)) ++missed;
        }
    }
    EXPECT_GT(entered, 1000);  // the boxes are where the rays are
    EXPECT_EQ(missed, 0);
}

} // namespace
} // namespace wideray::test
