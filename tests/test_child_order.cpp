#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "child_order_check.h"
#include "simd/cpu_features.h"

namespace wideray::test {
namespace {

/// The slots of `mask` farthest first by childOrderKey<N>: the order pushNearestLast must push them in.
template <int N>
std::vector<int> orderByKey(const float* distances, uint32_t mask) {
    std::vector<int> slots;
    for (int i = 0; i < N; ++i)
        if (mask >> i & 1) slots.push_back(i);
    std::sort(slots.begin(), slots.end(), [&](int a, int b) {
        return childOrderKey<N>(distances[a], a) > childOrderKey<N>(distances[b], b);
    });
    return slots;
}

/// All slots but the nearest pushed in `slots`' order with their distances, the nearest returned, the
/// entry below untouched.
void expectPushedInOrder(const ChildOrderResult& r, const std::vector<int>& slots, const float* distances,
                         uint32_t mask, const char* isa) {
    ASSERT_EQ(r.pushed, int(slots.size()) - 1) << isa << " mask " << mask;
    for (int k = 0; k < r.pushed; ++k) {
        EXPECT_EQ(r.refs[k], 100u + uint32_t(slots[k])) << isa << " mask " << mask << " entry " << k;
        EXPECT_EQ(std::memcmp(&r.distances[k], &distances[slots[k]], sizeof(float)), 0)
            << isa << " mask " << mask << " entry " << k;
    }
    EXPECT_EQ(r.next, 100u + uint32_t(slots.back())) << isa << " mask " << mask;
    EXPECT_EQ(r.below, 7u) << isa;
}

/// Every slot mask with three or more children, against distances drawn with many ties (equal
/// values, -0 and +0, neighbouring floats, infinity, negatives): the children go onto the stack by
/// childOrderKey, farthest first, the nearest is returned, and the entry below is untouched. The
/// baseline (insertion) and, where the CPU has it, the AVX2 build (sorting network) must agree.
TEST(ChildOrder, NearestLastByKeyOnEveryIsa) {
    const float pool[] = {-2.0f, -0.0f, 0.0f, 0.5f, std::nextafter(0.5f, 1.0f), 1.0f, 1.0f, 3.0f,
                          std::numeric_limits<float>::infinity(), 1e30f};
    std::mt19937 random(7);
    std::uniform_int_distribution<int> pick(0, int(std::size(pool)) - 1);
    std::uniform_real_distribution<float> spread(-1.0f, 100.0f);
    const bool avx2 = cpuSupports(Isa::Avx2);
    size_t checked = 0;
    for (int round = 0; round < 40; ++round) {
        float distances[8];
        for (float& d : distances) d = round % 2 ? pool[pick(random)] : spread(random);
        for (uint32_t mask = 0; mask < 256; ++mask) {
            if (__builtin_popcount(mask) < 3) continue;
            const std::vector<int> slots = orderByKey<8>(distances, mask);
            expectPushedInOrder(runPushNearestLast(distances, mask), slots, distances, mask, "baseline");
            if (avx2) expectPushedInOrder(runPushNearestLastAvx2(distances, mask), slots, distances, mask, "avx2");
            ++checked;
        }
    }
    EXPECT_EQ(checked, 40u * 219u);
}

/// 16-wide nodes (four bits of the key for the slot): random masks of three or more children against
/// distances with ties, farthest first by childOrderKey<16>, by insertion (baseline) and, where the
/// CPU has it, by the AVX-512 sorting network.
TEST(ChildOrder, SixteenWideNodesNearestLastByKey) {
    const bool avx512 = cpuSupports(Isa::Avx512);
    const float pool[] = {-0.0f, 0.0f, 0.5f, std::nextafter(0.5f, 1.0f), 1.0f, 1.0f, 3.0f,
                          std::numeric_limits<float>::infinity()};
    std::mt19937 random(11);
    std::uniform_int_distribution<int> pick(0, int(std::size(pool)) - 1);
    std::uniform_int_distribution<uint32_t> masks(0, 0xFFFF);
    for (int round = 0; round < 2000; ++round) {
        float distances[16];
        for (float& d : distances) d = pool[pick(random)];
        const uint32_t mask = masks(random);
        if (__builtin_popcount(mask) < 3) continue;
        const std::vector<int> slots = orderByKey<16>(distances, mask);
        expectPushedInOrder(runPushNearestLast<16>(distances, mask), slots, distances, mask, "baseline");
        if (avx512)
            expectPushedInOrder(runPushNearestLast16Avx512(distances, mask), slots, distances, mask, "avx512");
    }
    // Slot 15 still orders by distance first, and ties by slot.
    EXPECT_LT(childOrderKey<16>(1.0f, 15), childOrderKey<16>(2.0f, 0));
    EXPECT_LT(childOrderKey<16>(1.0f, 9), childOrderKey<16>(1.0f, 10));
}

TEST(ChildOrder, KeyIncreasesWithDistance) {
    const float ordered[] = {-std::numeric_limits<float>::max(), -1.0f, -1e-30f, -0.0f, 0.0f, 1e-30f, 1.0f,
                             std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity()};
    for (size_t i = 0; i + 1 < std::size(ordered); ++i)
        EXPECT_LE(childOrderKey(ordered[i], 0), childOrderKey(ordered[i + 1], 0)) << ordered[i] << " " << ordered[i + 1];
    EXPECT_LT(childOrderKey(1.0f, 7), childOrderKey(2.0f, 0));
    EXPECT_LT(childOrderKey(1.0f, 2), childOrderKey(1.0f, 3));  // ties go to the lower slot
}

} // namespace
} // namespace wideray::test
