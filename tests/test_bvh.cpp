// BVH invariants: the builder and the wide collapse keep every triangle exactly once, inside every
// box above it, and the SAH build beats a median split.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <functional>
#include <optional>

#include <tbb/global_control.h>

#include "accel/bvh_stats.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "accel/scene_accel.h"
#include "test_data.h"

namespace wideray {
namespace {

TriangleMesh testMesh() {
    TriangleMesh a = makeTorus(1.0f, 0.25f, 96, 48);  // 9216 triangles
    TriangleMesh b = makeIcosphere(4);
    uint32_t offset = uint32_t(a.positions.size());
    for (const glm::vec3& p : b.positions) a.positions.push_back(p * 0.3f + glm::vec3(2.0f, 0.5f, 0.0f));
    for (const glm::uvec3& t : b.triangles) a.triangles.push_back(t + offset);
    a.normals.clear();
    return a;
}

Bounds3f triangleBox(const TriangleMesh& mesh, uint32_t prim) {
    Bounds3f b;
    for (int k = 0; k < 3; ++k) b.grow(mesh.positions[mesh.triangles[prim][k]]);
    return b;
}

template <int N>
void checkWide(const TriangleMesh& mesh, CollapseMethod collapse = CollapseMethod::Sah) {
    BvhBuildConfig config = SceneAccel<N>::defaultConfig();
    config.collapse = collapse;
    SceneAccel<N> accel(std::make_shared<SceneGeometry>(mesh), config);
    const WideBvh<N>& bvh = accel.bvh();
    const auto& blocks = accel.blocks();
    std::vector<int> seen(mesh.triangles.size(), 0);
    std::vector<int> blockSeen(blocks.size(), 0);

    std::function<void(NodeRef, const Bounds3f&)> visit = [&](NodeRef ref, const Bounds3f& box) {
        if (ref.isLeaf()) {
            for (uint32_t b = ref.first(); b < ref.first() + ref.count(); ++b) {
                ++blockSeen[b];
                const TriangleBlock<kBlockSize>& block = blocks[b];
                ASSERT_GT(block.count(), 0);
                for (int lane = 0; lane < block.count(); ++lane) {
                    uint32_t prim = block.primId[lane];
                    ++seen[prim];
                    EXPECT_TRUE(box.contains(triangleBox(mesh, prim))) << "triangle " << prim << " outside its leaf box";
                    const glm::uvec3& t = mesh.triangles[prim];
                    EXPECT_EQ(block.v1x[lane], mesh.positions[t.y].x);
                    EXPECT_EQ(block.v2z[lane], mesh.positions[t.z].z);
                }
            }
            return;
        }
        const WideNode<N>& node = bvh.nodes[ref.index()];
        int innerChildren = 0;
        uint32_t firstInner = 0;
        for (int i = 0; i < N; ++i) {
            NodeRef c = node.child[i];
            if (c.isLeaf() && c.count() == 0) {
                EXPECT_GT(node.lowerX[i], node.upperX[i]) << "an empty slot must have an empty box";
                continue;
            }
            Bounds3f childBox({node.lowerX[i], node.lowerY[i], node.lowerZ[i]},
                              {node.upperX[i], node.upperY[i], node.upperZ[i]});
            EXPECT_TRUE(box.contains(childBox)) << "child box outside its parent";
            if (!c.isLeaf()) {
                if (innerChildren == 0) firstInner = c.index();
                EXPECT_EQ(c.index(), firstInner + innerChildren) << "inner children must be adjacent";
                ++innerChildren;
            }
            visit(c, childBox);
        }
    };
    visit(bvh.root, bvh.bounds);
    for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "triangle " << i;
    for (size_t i = 0; i < blockSeen.size(); ++i) ASSERT_EQ(blockSeen[i], 1) << "block " << i;
}

TEST(Bvh, WideCollapseKeepsEveryTriangleOnceInsideItsBoxes) {
    TriangleMesh mesh = testMesh();
    for (CollapseMethod collapse : {CollapseMethod::Sah, CollapseMethod::Greedy}) {
        checkWide<4>(mesh, collapse);
        checkWide<8>(mesh, collapse);
    }
}

template <int N>
BvhStats wideStats(const TriangleMesh& mesh, CollapseMethod collapse) {
    BvhBuildConfig config = SceneAccel<N>::defaultConfig();
    config.collapse = collapse;
    SceneAccel<N> accel(std::make_shared<SceneGeometry>(mesh), config);
    return wideBvhStats(accel.bvh(), config);
}

/// The cost-driven collapse is the optimum over the same binary tree, so it never costs more than the
/// greedy one; it also fills the nodes more.
template <int N>
void expectSahCollapseAtMostGreedy(const TriangleMesh& mesh, const std::string& name) {
    const BvhStats sah = wideStats<N>(mesh, CollapseMethod::Sah), greedy = wideStats<N>(mesh, CollapseMethod::Greedy);
    EXPECT_LE(sah.sahCost, greedy.sahCost * (1.0 + 1e-6)) << name << " N=" << N;
    EXPECT_GE(sah.childrenPerNode(), greedy.childrenPerNode()) << name << " N=" << N;
    std::printf("  %-40s BVH%d SAH cost %.3f (greedy %.3f), %.2f children per node (greedy %.2f)\n", name.c_str(), N,
                sah.sahCost, greedy.sahCost, sah.childrenPerNode(), greedy.childrenPerNode());
}

TEST(Bvh, SahCollapseCostsAtMostTheGreedyOne) {
    expectSahCollapseAtMostGreedy<4>(testMesh(), "test mesh");
    expectSahCollapseAtMostGreedy<8>(testMesh(), "test mesh");
    expectSahCollapseAtMostGreedy<8>(makeTorus(1.0f, 0.3f, 200, 100), "torus");
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the shared meshes need ../shared/scenes (or WIDERAY_SCENES)";
    for (const char* file : kSharedMeshes) {
        const TriangleMesh mesh = loadMesh(*dir / file);
        expectSahCollapseAtMostGreedy<4>(mesh, file);
        expectSahCollapseAtMostGreedy<8>(mesh, file);
    }
}

TEST(Bvh, SingleTriangleAndTinyMeshes) {
    TriangleMesh one;
    one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    one.triangles = {{0, 1, 2}};
    checkWide<4>(one);
    checkWide<8>(one);
    checkWide<8>(makeCube());
}

TEST(Bvh, IdenticalTrianglesStillGiveABoundedTree) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles.assign(5000, glm::uvec3(0, 1, 2));
    checkWide<8>(mesh);
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh));
    EXPECT_LE(wideBvhStats(accel.bvh(), SceneAccel<8>::defaultConfig()).depth, kMaxBvhDepth);
}

TEST(Bvh, BinaryLeavesRespectTheLeafSize) {
    TriangleMesh mesh = testMesh();
    BvhBuildConfig config;
    BinaryBvh bvh = buildBinaryBvh(triangleRefs(mesh), config);
    size_t total = 0;
    for (const BinaryNode& n : bvh.nodes)
        if (n.isLeaf()) {
            EXPECT_LE(n.count, uint32_t(config.maxLeafSize));
            total += n.count;
        }
    EXPECT_EQ(total, mesh.triangles.size());
}

double sahCost(const TriangleMesh& mesh, SplitMethod split) {
    BvhBuildConfig config;
    config.split = split;
    return binaryBvhStats(buildBinaryBvh(triangleRefs(mesh), config), config).sahCost;
}

TEST(Bvh, SahCostBelowMedianSplit) {
    TriangleMesh mesh = testMesh();
    double sah = sahCost(mesh, SplitMethod::Sah), median = sahCost(mesh, SplitMethod::Median);
    EXPECT_LT(sah, median);
    if (auto dir = sharedScenesDir()) {
        TriangleMesh bunny = loadMesh(*dir / "stanford-bunny/bun_zipper.ply");
        EXPECT_LT(sahCost(bunny, SplitMethod::Sah), sahCost(bunny, SplitMethod::Median));
        TriangleMesh sponza = loadMesh(*dir / "crytek-sponza/sponza.obj");
        EXPECT_LT(sahCost(sponza, SplitMethod::Sah), sahCost(sponza, SplitMethod::Median));
    }
}

/// The same tree whatever the thread count: one thread, then all of them (the build is parallel above
/// 4096 primitives, which the test mesh exceeds).
TEST(Bvh, BuildIsDeterministic) {
    TriangleMesh mesh = testMesh();
    ASSERT_GT(mesh.triangles.size(), 4096u);
    std::optional<SceneAccel<8>> a;
    {
        tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
        a.emplace(std::make_shared<SceneGeometry>(mesh));
    }
    SceneAccel<8> b(std::make_shared<SceneGeometry>(mesh));
    ASSERT_EQ(a->bvh().nodes.size(), b.bvh().nodes.size());
    for (size_t n = 0; n < a->bvh().nodes.size(); ++n) {
        const WideNode<8>&x = a->bvh().nodes[n], &y = b.bvh().nodes[n];
        for (int i = 0; i < 8; ++i) {
            ASSERT_EQ(x.child[i].bits, y.child[i].bits);
            ASSERT_EQ(x.lowerX[i], y.lowerX[i]);
            ASSERT_EQ(x.upperZ[i], y.upperZ[i]);
        }
    }
    ASSERT_EQ(a->blocks().size(), b.blocks().size());
    EXPECT_EQ(0, std::memcmp(a->blocks().data(), b.blocks().data(), a->blocks().size() * sizeof(TriangleBlock<4>)));
}

} // namespace
} // namespace wideray
