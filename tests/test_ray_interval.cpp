#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/traverse_packet.h"
#include "simd/cpu_features.h"
#include "transpose_min_check.h"

namespace wideray::test {
namespace {

/// The interval test of a bundle of rays must enter every child that one of its rays' own slab
/// tests enters (the packets test rays only against the children the interval enters). Origins far
/// from zero with boxes close to them (short distances) are where the rays' absolute rounding
/// margin (|o / d| ulps) exceeds a margin relative to t. Bundles with rays that start behind their
/// origin (tnear < 0) are not narrow enough for the interval test, which assumes tnear >= 0.
TEST(RayInterval, EntersEveryChildThatOneOfItsRaysEnters) {
    constexpr int K = kMaxWidth;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), jitter(-1e-3f, 1e-3f), scale(0.0f, 3.0f);
    int entered = 0, missed = 0;
    for (int bundle = 0; bundle < 4000; ++bundle) {
        const float reach = std::pow(10.0f, scale(random));  // origins at 1 to 1000
        const float o[3] = {reach * unit(random), reach * unit(random), reach * unit(random)};
        float d[3] = {unit(random), unit(random), unit(random)};
        const bool behind = bundle % 5 == 0;
        Ray rays[K];
        for (Ray& r : rays) {
            r = {o[0] + jitter(random), o[1] + jitter(random), o[2] + jitter(random),
                 d[0] + jitter(random), d[1] + jitter(random), d[2] + jitter(random), behind ? -reach : 0.0f,
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
        if (behind) {
            EXPECT_FALSE(narrowEnough(interval));
            continue;
        }
        ASSERT_TRUE(narrowEnough(interval));
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

/// The sub-packets' interval test at a leaf (SubPacketIntervals::enter) must enter every box that one
/// of the sub-packet's rays enters, and (to be worth its cost) miss most boxes that none of them
/// enters. Sub-packets of rays from one origin (a camera's) and from spread origins (shadow rays'),
/// with hits at various distances, against boxes around points along the rays and between them.
TEST(SubPacketIntervals, EnterEveryBoxThatOneOfTheirRaysEnters) {
    constexpr int K = kMaxWidth, P = 256 / K;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.0f, 1.0f);
    int entered = 0, missed = 0, notEntered = 0, culled = 0;
    for (int packet = 0; packet < 200; ++packet) {
        const bool oneOrigin = packet % 2 == 0;
        const float o[3] = {10.0f * unit(random), 10.0f * unit(random), 10.0f * unit(random)};
        const float d[3] = {unit(random), unit(random), unit(random)};
        Ray rays[K * P];
        for (int i = 0; i < K * P; ++i) {
            const float u = float(i % 16) / 16.0f - 0.5f, v = float(i / 16) / 16.0f - 0.5f;  // a 16x16 tile
            Ray& r = rays[i];
            r = {o[0], o[1], o[2], d[0] + 0.1f * u, d[1] + 0.1f * v, d[2] + 0.05f * u * v, 0.0f, __builtin_huge_valf()};
            if (!oneOrigin) r.ox += u, r.oy += v, r.oz += 0.5f * u;
            if ((r.dx < 0) != (d[0] < 0)) r.dx = -r.dx;
            if ((r.dy < 0) != (d[1] < 0)) r.dy = -r.dy;
            if ((r.dz < 0) != (d[2] < 0)) r.dz = -r.dz;
        }
        PacketRay<K> packets[P];
        PacketHit<K> hits[P];
        vbool<K> valid[P], done[P];
        RayBounds<K> all;
        for (int s = 0; s < P; ++s) {
            valid[s] = loadPacket(rays + s * K, K, packets[s], hits[s]);
            done[s] = vbool<K>(false);
            hits[s].t = vfloat<K>(packet % 3 == 0 ? 30.0f * fraction(random) : __builtin_huge_valf());
            all.add(packets[s], valid[s]);
        }
        if (!packets[0].uniformOctant) continue;
        const RayInterval whole = all.interval(packets[0]);
        SubPacketIntervals<P> sub;
        const uint64_t live = P == 64 ? ~uint64_t(0) : (uint64_t(1) << P) - 1;
        sub.bound(packets, hits, valid, done, live, whole);
        for (int box = 0; box < 50; ++box) {
            const Ray& r = rays[std::uniform_int_distribution<int>(0, K * P - 1)(random)];
            const float t = 40.0f * fraction(random), size = 0.02f + 0.5f * fraction(random);
            float lower[3], upper[3];
            const float at[3] = {r.ox + t * r.dx, r.oy + t * r.dy, r.oz + t * r.dz};
            for (int a = 0; a < 3; ++a) {
                lower[a] = at[a] - size * fraction(random);
                upper[a] = at[a] + size * fraction(random);
            }
            const uint64_t byInterval = sub.enter(lower, upper);
            for (int s = 0; s < P; ++s) {
                const vfloat<K> entries = packetBoxEntry(lower[0], lower[1], lower[2], upper[0], upper[1], upper[2],
                                                         packets[s], hits[s].t, valid[s]);
                const bool byRays = any(entries < vfloat<K>(__builtin_huge_valf()));
                const bool byBound = byInterval >> s & 1;
                if (byRays) ++entered, missed += !byBound;
                else ++notEntered, culled += !byBound;
            }
        }
    }
    EXPECT_GT(entered, 2000);
    EXPECT_EQ(missed, 0);
    EXPECT_GT(culled, notEntered / 2);
}

/// transposeMin gives each vector's least lane, as reduceMin does one vector at a time, on every ISA
/// (with ties among the lanes every fourth round).
TEST(SubPacketIntervals, TransposeMinIsEachVectorsMinimum) {
    constexpr int kRounds = 100;
    std::mt19937 random(3);
    std::uniform_real_distribution<float> value(-100.0f, 100.0f);
    std::vector<float> values(kRounds * kTransposeMinValuesPerRound);
    for (size_t i = 0; i < values.size(); ++i) {
        const bool ties = i / kTransposeMinValuesPerRound % 4 == 0;
        values[i] = ties ? std::round(value(random) / 50.0f) : value(random);
    }
    EXPECT_EQ(transposeMinMismatches(values.data(), kRounds), 0);
    if (cpuSupports(Isa::Avx2)) {
        EXPECT_EQ(transposeMinMismatchesAvx2(values.data(), kRounds), 0);
    }
    if (cpuSupports(Isa::Avx512)) {
        EXPECT_EQ(transposeMinMismatchesAvx512(values.data(), kRounds), 0);
    }
}

} // namespace
} // namespace wideray::test
