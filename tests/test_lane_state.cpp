#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "lane_state_check.h"
#include "simd/cpu_features.h"

namespace wideray::test {
namespace {

/// Directions of every octant and dominant axis, with zero, negative-zero, tiny and huge components;
/// origins near and far; some invalid rays among them.
std::vector<Ray> awkwardRays() {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), far(-1e6f, 1e6f);
    const float special[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1e30f, -3.0f, 0.5f};
    std::vector<Ray> rays;
    for (int i = 0; i < 4000; ++i) {
        Ray r{};
        r.ox = i % 3 ? unit(random) : far(random);
        r.oy = unit(random);
        r.oz = i % 5 ? unit(random) : far(random);
        r.dx = unit(random);
        r.dy = unit(random);
        r.dz = unit(random);
        if (i % 4 == 1) r.dx = special[i % std::size(special)];
        if (i % 6 == 2) r.dy = special[(i / 6) % std::size(special)];
        if (i % 8 == 3) r.dz = special[(i / 8) % std::size(special)];
        r.tnear = 0.0f;
        r.tfar = i % 97 == 0 ? -1.0f : std::numeric_limits<float>::infinity();  // a few invalid
        rays.push_back(r);
    }
    return rays;
}

/// Packets hand rays over to single-ray traversal with each lane's state taken from the packet's
/// (laneState), and the `single` kernels take their rays' states the same way (forEachRayState); it
/// must be makeSingleRayState's to the bit, or those rays would not give the reference's hits.
TEST(LaneState, EqualsSingleRayStateOnEveryIsa) {
    const std::vector<Ray> rays = awkwardRays();
    EXPECT_EQ(laneStateMismatches(rays.data(), int(rays.size())), 0);
    if (cpuSupports(Isa::Avx2)) {
        EXPECT_EQ(laneStateMismatchesAvx2(rays.data(), int(rays.size())), 0);
    }
}

/// Streams hand rays over to single-ray traversal in the same way (slotState).
TEST(LaneState, StreamSlotStateEqualsSingleRayStateOnEveryIsa) {
    const std::vector<Ray> rays = awkwardRays();
    EXPECT_EQ(streamSlotStateMismatches(rays.data(), int(rays.size())), 0);
    if (cpuSupports(Isa::Avx2)) {
        EXPECT_EQ(streamSlotStateMismatchesAvx2(rays.data(), int(rays.size())), 0);
    }
}

} // namespace
} // namespace wideray::test
