// The scalar reference over the wide BVH against brute force: same primitive, same t, bit for bit.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include "core/fp_mode.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "accel/scene_accel.h"
#include "kernels/kernel_registry.h"
#include "ray_sets.h"
#include "test_data.h"

namespace wideray {
namespace {

/// Brute force costs rays x triangles; big meshes get a sample of rays so that the suite stays fast
/// (and the sanitizer build, ten times slower, a smaller one).
size_t rayBudget(const TriangleMesh& mesh, size_t wanted) {
#ifdef WIDERAY_SANITIZE
    const double budget = 5e7;
#else
    const double budget = 5e8;
#endif
    return std::max<size_t>(200, std::min(wanted, size_t(budget / double(std::max<size_t>(1, mesh.triangles.size())))));
}

/// quality High: spatial splits tried at every node (a triangle in several leaves, clipped boxes).
template <int N>
void expectMatchesBruteForce(const TriangleMesh& mesh, size_t rayCount, uint32_t seed,
                             BuildQuality quality = BuildQuality::Fast) {
    FlushToZeroScope ftz;
    BvhBuildConfig config = SceneAccel<N>::defaultConfig();
    config.quality = quality;
    config.spatialMinRefs = 0;
    SceneAccel<N> accel(std::make_shared<SceneGeometry>(mesh), config);
    std::vector<Ray> rays = testing::randomRays(mesh, rayCount, seed);
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> occluded(rays.size());
    // The baseline reference: the brute force below shares its arithmetic (no FMA).
    const Kernel<N> reference = referenceKernel<N>(Isa::Sse42);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        reference.intersect(accel.view(), rays.data() + r.begin(), hits.data() + r.begin(), r.size(), nullptr);
        reference.occluded(accel.view(), rays.data() + r.begin(), occluded.data() + r.begin(), r.size(), nullptr);
    });
    std::vector<Hit> expected(rays.size());
    tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) { expected[i] = testing::bruteForceHit(mesh, rays[i]); });
    size_t mismatches = 0, hitCount = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        hitCount += expected[i].valid();
        bool same = hits[i].primId == expected[i].primId && (!expected[i].valid() || hits[i].t == expected[i].t);
        bool occlusionAgrees = bool(occluded[i]) == expected[i].valid();
        if ((!same || !occlusionAgrees) && ++mismatches <= 5)
            ADD_FAILURE() << "ray " << i << ": BVH prim " << hits[i].primId << " t " << hits[i].t << ", brute force prim "
                          << expected[i].primId << " t " << expected[i].t << ", occluded " << int(occluded[i]);
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(hitCount, rays.size() / 3) << "the ray set should mostly hit";
}

TEST(Traversal, MatchesBruteForceOnGeneratedMeshes) {
    for (const TriangleMesh& mesh : {makeIcosphere(4), makeTorus(1.0f, 0.3f, 64, 32), makeCube()}) {
        expectMatchesBruteForce<4>(mesh, rayBudget(mesh, 100000), 1);
        expectMatchesBruteForce<8>(mesh, rayBudget(mesh, 100000), 2);
        expectMatchesBruteForce<8>(mesh, rayBudget(mesh, 100000), 5, BuildQuality::High);
        expectMatchesBruteForce<16>(mesh, rayBudget(mesh, 100000), 7, BuildQuality::High);
    }
}

class SharedMeshTraversal : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedMeshTraversal, MatchesBruteForce) {
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "needs ../shared/scenes (or WIDERAY_SCENES)";
    TriangleMesh mesh = loadMesh(*dir / GetParam());
    expectMatchesBruteForce<8>(mesh, rayBudget(mesh, 100000), 3);
    expectMatchesBruteForce<4>(mesh, rayBudget(mesh, 20000), 4);
    expectMatchesBruteForce<8>(mesh, rayBudget(mesh, 20000), 6, BuildQuality::High);
    expectMatchesBruteForce<16>(mesh, rayBudget(mesh, 20000), 8, BuildQuality::High);
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, SharedMeshTraversal,
                         ::testing::ValuesIn(kSharedMeshes));

TEST(Traversal, InvalidRaysMissAndAreNotOccluded) {
    TriangleMesh mesh = makeIcosphere(2);
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh));
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Ray> rays = {
        {0, 0, -5, nan, 0, 1, 0, inf}, {0, 0, -5, 0, 0, inf, 0, inf}, {nan, 0, -5, 0, 0, 1, 0, inf},
        {0, 0, -5, 0, 0, 0, 0, inf},   {0, 0, -5, 0, 0, 1, 10, 1},    {0, 0, -5, 0, 0, 1, nan, inf},
    };
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> occluded(rays.size(), 1);
    referenceKernel<8>(Isa::Sse42).intersect(accel.view(), rays.data(), hits.data(), rays.size(), nullptr);
    referenceKernel<8>(Isa::Sse42).occluded(accel.view(), rays.data(), occluded.data(), rays.size(), nullptr);
    for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_FALSE(hits[i].valid()) << "ray " << i;
        EXPECT_EQ(occluded[i], 0) << "ray " << i;
    }
}

TEST(Traversal, TfarLimitsHitsAndOcclusion) {
    TriangleMesh mesh = makeQuad();  // y = 0 plane, [-1,1]^2
    SceneAccel<4> accel(std::make_shared<SceneGeometry>(mesh));
    Ray below{0.25f, 1.0f, 0.25f, 0, -1, 0, 0, 0.999f}, reach{0.25f, 1.0f, 0.25f, 0, -1, 0, 0, 1.0f};
    Hit hit;
    uint8_t occ = 0;
    referenceKernel<4>(Isa::Sse42).intersect(accel.view(), &below, &hit, 1, nullptr);
    EXPECT_FALSE(hit.valid());
    referenceKernel<4>(Isa::Sse42).occluded(accel.view(), &below, &occ, 1, nullptr);
    EXPECT_EQ(occ, 0);
    referenceKernel<4>(Isa::Sse42).intersect(accel.view(), &reach, &hit, 1, nullptr);
    EXPECT_TRUE(hit.valid());
    EXPECT_EQ(hit.t, 1.0f);
    referenceKernel<4>(Isa::Sse42).occluded(accel.view(), &reach, &occ, 1, nullptr);
    EXPECT_EQ(occ, 1);
}

} // namespace
} // namespace wideray
