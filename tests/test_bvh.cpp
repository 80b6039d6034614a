// BVH invariants: the builder and the wide collapse keep every triangle exactly once (at least once,
// every part of it covered, with spatial splits), inside every box above it, and the SAH build beats
// a median split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>

#include <tbb/global_control.h>

#include "accel/bvh_stats.h"
#include "accel/object_bins.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "accel/scene_accel.h"
#include "accel/triangle_splitter.h"
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

/// The high quality build with spatial splits tried at every node, so that small meshes have many.
template <int N>
BvhBuildConfig highConfig() {
    BvhBuildConfig config = SceneAccel<N>::defaultConfig();
    config.quality = BuildQuality::High;
    config.spatialMinRefs = 0;
    return config;
}

/// Points spread over the triangle: its corners, edge midpoints and an interior grid.
std::vector<glm::vec3> trianglePoints(const TriangleMesh& mesh, uint32_t prim) {
    const glm::vec3 a = mesh.positions[mesh.triangles[prim].x], b = mesh.positions[mesh.triangles[prim].y],
                    c = mesh.positions[mesh.triangles[prim].z];
    std::vector<glm::vec3> points;
    constexpr int kSteps = 6;
    for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
            const float u = float(i) / kSteps, v = float(j) / kSteps;
            points.push_back(a + u * (b - a) + v * (c - a));
        }
    return points;
}

/// Within a few ulps: the sample points themselves are rounded.
bool inside(const Bounds3f& box, const glm::vec3& p) {
    const glm::vec3 slack = (glm::abs(box.lower) + glm::abs(box.upper)) * 1e-6f;
    return glm::all(glm::lessThanEqual(box.lower - slack, p)) && glm::all(glm::lessThanEqual(p, box.upper + slack));
}

template <int N>
void checkWide(const TriangleMesh& mesh, const BvhBuildConfig& config) {
    const BuildQuality quality = config.quality;
    SceneAccel<N> accel(std::make_shared<SceneGeometry>(mesh), config);
    const WideBvh<N>& bvh = accel.bvh();
    const auto& blocks = accel.blocks();
    std::vector<int> seen(mesh.triangles.size(), 0);
    std::vector<int> blockSeen(blocks.size(), 0);
    std::vector<std::vector<Bounds3f>> leafBoxes(mesh.triangles.size());  ///< of the leaves holding each triangle

    std::function<void(NodeRef, const Bounds3f&)> visit = [&](NodeRef ref, const Bounds3f& box) {
        if (ref.isLeaf()) {
            std::vector<uint32_t> leafPrims;
            for (uint32_t b = ref.first(); b < ref.first() + ref.count(); ++b) {
                ++blockSeen[b];
                const TriangleBlock<kBlockSize>& block = blocks[b];
                ASSERT_GT(block.count(), 0);
                for (int lane = 0; lane < block.count(); ++lane) {
                    uint32_t prim = block.primId[lane];
                    leafPrims.push_back(prim);
                    ++seen[prim];
                    leafBoxes[prim].push_back(box);
                    if (quality == BuildQuality::Fast) {
                        EXPECT_TRUE(box.contains(triangleBox(mesh, prim))) << "triangle " << prim << " outside its leaf box";
                    }
                    const glm::uvec3& t = mesh.triangles[prim];
                    EXPECT_EQ(block.v1x[lane], mesh.positions[t.y].x);
                    EXPECT_EQ(block.v2z[lane], mesh.positions[t.z].z);
                }
            }
            // A triangle whose parts reach sibling leaves that the collapse merges is stored once.
            std::sort(leafPrims.begin(), leafPrims.end());
            EXPECT_EQ(std::adjacent_find(leafPrims.begin(), leafPrims.end()), leafPrims.end()) << "a leaf names a triangle twice";
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
    for (size_t i = 0; i < blockSeen.size(); ++i) ASSERT_EQ(blockSeen[i], 1) << "block " << i;
    if (quality == BuildQuality::Fast) {
        for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "triangle " << i;
        return;
    }
    // Spatial splits: each triangle at least once, every point of it inside one of its leaves' boxes
    // (the clipped parts together cover it), and no more references than the budget allows.
    size_t references = 0;
    for (uint32_t prim = 0; prim < seen.size(); ++prim) {
        ASSERT_GE(seen[prim], 1) << "triangle " << prim;
        references += size_t(seen[prim]);
        for (const glm::vec3& p : trianglePoints(mesh, prim)) {
            const bool covered = std::any_of(leafBoxes[prim].begin(), leafBoxes[prim].end(),
                                             [&](const Bounds3f& box) { return inside(box, p); });
            ASSERT_TRUE(covered) << "a point of triangle " << prim << " is in none of its " << seen[prim] << " leaf boxes";
        }
    }
    EXPECT_EQ(references, accel.triangleReferences());
    EXPECT_LE(double(references), double(mesh.triangles.size()) * (1.0 + double(config.replicationBudget)));
    std::printf("  BVH%d high quality: %.3f references per triangle\n", N, double(references) / double(seen.size()));
}

template <int N>
void checkWide(const TriangleMesh& mesh, CollapseMethod collapse = CollapseMethod::Sah,
               BuildQuality quality = BuildQuality::Fast) {
    BvhBuildConfig config = quality == BuildQuality::High ? highConfig<N>() : SceneAccel<N>::defaultConfig();
    config.collapse = collapse;
    checkWide<N>(mesh, config);
}

TEST(Bvh, WideCollapseKeepsEveryTriangleOnceInsideItsBoxes) {
    TriangleMesh mesh = testMesh();
    for (CollapseMethod collapse : {CollapseMethod::Sah, CollapseMethod::Greedy}) {
        checkWide<4>(mesh, collapse);
        checkWide<8>(mesh, collapse);
        checkWide<16>(mesh, collapse);
    }
}

TEST(Bvh, SpatialSplitsCoverEveryTriangleWithinTheBudget) {
    checkWide<4>(testMesh(), CollapseMethod::Sah, BuildQuality::High);
    checkWide<8>(testMesh(), CollapseMethod::Sah, BuildQuality::High);
    checkWide<16>(testMesh(), CollapseMethod::Sah, BuildQuality::High);
    checkWide<8>(makeCube(), CollapseMethod::Sah, BuildQuality::High);
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the shared meshes need ../shared/scenes (or WIDERAY_SCENES)";
    // Long thin triangles across big rooms: where spatial splits clip the most.
    checkWide<8>(loadMesh(*dir / "crytek-sponza/sponza.obj"), CollapseMethod::Sah, BuildQuality::High);
}

/// Small triangles in a row under one long sliver across them all: spatial splits clip the sliver into
/// the small ones' nodes, and the collapse merges those nodes again into leaves.
TriangleMesh slicedSliver(int count) {
    TriangleMesh mesh;
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const uint32_t first = uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c});
        mesh.triangles.push_back({first, first + 1, first + 2});
    };
    for (int i = 0; i < count; ++i) {
        const float x = float(i);
        add({x, 0.0f, 0.0f}, {x + 0.5f, 0.0f, 0.0f}, {x, 0.5f, 0.5f});
    }
    add({0.0f, 0.2f, 0.2f}, {float(count), 0.2f, 0.2f}, {0.0f, 0.25f, 0.25f});
    return mesh;
}

TEST(Bvh, LeavesMergedAcrossASpatialSplitNameEachTriangleOnce) {
    // Traversal made dear: the collapse merges the spatial split's two sides into one leaf.
    BvhBuildConfig config = highConfig<8>();
    config.traversalCost = 16.0f;
    config.compareBuildsBelow = 0;  // keep the spatial tree
    for (int count : {9, 10, 12}) {
        const TriangleMesh mesh = slicedSliver(count);
        const TriangleSplitter splitter(mesh);
        const BinaryBvh binary = buildBinaryBvh(
            triangleRefs(mesh, buildRefCapacity(mesh.triangles.size(), config)), config, &splitter);
        ASSERT_GT(binary.primIndices.size(), mesh.triangles.size()) << count << ": the sliver must be split";
        checkWide<8>(mesh, config);
        checkWide<4>(mesh, config);
        checkWide<16>(mesh, config);
    }
}

/// The high quality build keeps its spatial splits only where the wide tree costs less for them.
TEST(Bvh, HighQualityCostsAtMostTheFastBuild) {
    auto cost = [](const TriangleMesh& mesh, const BvhBuildConfig& config) {
        SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh), config);
        return wideBvhStats(accel.bvh(), config).sahCost;
    };
    auto expectCheaper = [&](const TriangleMesh& mesh, const std::string& name) {
        BvhBuildConfig high = SceneAccel<8>::defaultConfig();
        high.quality = BuildQuality::High;
        const double fast = cost(mesh, SceneAccel<8>::defaultConfig()), spatial = cost(mesh, high);
        EXPECT_LE(spatial, fast) << name;
        std::printf("  %-40s BVH8 SAH cost: fast %.3f, high %.3f\n", name.c_str(), fast, spatial);
    };
    expectCheaper(testMesh(), "test mesh");
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the shared meshes need ../shared/scenes (or WIDERAY_SCENES)";
    for (const char* file : kSharedMeshes) expectCheaper(loadMesh(*dir / file), file);
}

/// A room (floor, ceiling, three walls: two triangles each) with two boxes in it, the Cornell box's
/// layout: large triangles at right angles, which leaves of four keep together badly.
TriangleMesh roomWithBoxes() {
    TriangleMesh mesh;
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const uint32_t first = uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
        mesh.triangles.push_back({first, first + 1, first + 2});
        mesh.triangles.push_back({first, first + 2, first + 3});
    };
    quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});  // floor
    quad({0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0});  // ceiling
    quad({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});  // back
    quad({0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0});  // left
    quad({1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1});  // right
    auto box = [&](glm::vec3 lo, glm::vec3 hi) {
        const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                                {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
        quad(c[0], c[1], c[2], c[3]), quad(c[4], c[7], c[6], c[5]), quad(c[0], c[4], c[5], c[1]);
        quad(c[3], c[2], c[6], c[7]), quad(c[0], c[3], c[7], c[4]), quad(c[1], c[5], c[6], c[2]);
    };
    box({0.15f, 0.0f, 0.2f}, {0.45f, 0.6f, 0.5f});
    box({0.55f, 0.0f, 0.5f}, {0.85f, 0.3f, 0.8f});
    return mesh;
}

/// Below BvhBuildConfig::singlePrimLeavesBelow the high build splits its binary tree down to single
/// triangles and the collapse chooses the leaves, which separates what the binary build's leaf test
/// kept together (without it the high build's cost equals the fast one's on these).
TEST(Bvh, HighQualityLetsTheCollapseChooseTheLeavesOfSmallMeshes) {
    auto cost = [](const TriangleMesh& mesh, BuildQuality quality) {
        BvhBuildConfig config = SceneAccel<8>::defaultConfig();
        config.quality = quality;
        SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh), config);
        return wideBvhStats(accel.bvh(), config).sahCost;
    };
    auto expectCheaper = [&](const TriangleMesh& mesh, const std::string& name) {
        const double fast = cost(mesh, BuildQuality::Fast), high = cost(mesh, BuildQuality::High);
        EXPECT_LT(high, 0.9 * fast) << name;
        std::printf("  %-40s BVH8 SAH cost: fast %.3f, high %.3f\n", name.c_str(), fast, high);
    };
    expectCheaper(roomWithBoxes(), "room with two boxes");
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the shared meshes need ../shared/scenes (or WIDERAY_SCENES)";
    expectCheaper(loadMesh(*dir / "cornell-box/CornellBox-Original.obj"), "Cornell box");
    expectCheaper(loadMesh(*dir / "suzanne/suzanne.obj"), "Suzanne");
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
    expectSahCollapseAtMostGreedy<16>(testMesh(), "test mesh");
    expectSahCollapseAtMostGreedy<8>(makeTorus(1.0f, 0.3f, 200, 100), "torus");
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the shared meshes need ../shared/scenes (or WIDERAY_SCENES)";
    for (const char* file : kSharedMeshes) {
        const TriangleMesh mesh = loadMesh(*dir / file);
        expectSahCollapseAtMostGreedy<4>(mesh, file);
        expectSahCollapseAtMostGreedy<8>(mesh, file);
        expectSahCollapseAtMostGreedy<16>(mesh, file);
    }
}

TEST(Bvh, SingleTriangleAndTinyMeshes) {
    TriangleMesh one;
    one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    one.triangles = {{0, 1, 2}};
    checkWide<4>(one);
    checkWide<8>(one);
    checkWide<16>(one);
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

void expectSameTree(const SceneAccel<8>& a, const SceneAccel<8>& b) {
    ASSERT_EQ(a.bvh().nodes.size(), b.bvh().nodes.size());
    for (size_t n = 0; n < a.bvh().nodes.size(); ++n) {
        const WideNode<8>&x = a.bvh().nodes[n], &y = b.bvh().nodes[n];
        for (int i = 0; i < 8; ++i) {
            ASSERT_EQ(x.child[i].bits, y.child[i].bits);
            ASSERT_EQ(x.lowerX[i], y.lowerX[i]);
            ASSERT_EQ(x.upperZ[i], y.upperZ[i]);
        }
    }
    ASSERT_EQ(a.blocks().size(), b.blocks().size());
    EXPECT_EQ(0, std::memcmp(a.blocks().data(), b.blocks().data(), a.blocks().size() * sizeof(TriangleBlock<4>)));
}

/// The same tree whatever the thread count: one thread, then all of them (the build is parallel above
/// 4096 primitives, which the test mesh exceeds; the dragon's 100k exceed the sizes from which
/// partitions run in parallel and splits are chosen on samples).
void expectSameTreeOnOneAndAllThreads(const TriangleMesh& mesh, const BvhBuildConfig& config) {
    ASSERT_GT(mesh.triangles.size(), 4096u);
    std::optional<SceneAccel<8>> a;
    {
        tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
        a.emplace(std::make_shared<SceneGeometry>(mesh), config);
    }
    SceneAccel<8> b(std::make_shared<SceneGeometry>(mesh), config);
    expectSameTree(*a, b);
}

TEST(Bvh, BuildIsDeterministic) {
    expectSameTreeOnOneAndAllThreads(testMesh(), SceneAccel<8>::defaultConfig());
    expectSameTreeOnOneAndAllThreads(testMesh(), highConfig<8>());
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "the dragon needs ../shared/scenes (or WIDERAY_SCENES)";
    const TriangleMesh dragon = loadMesh(*dir / "stanford-dragon-100k/dragon_100k.ply");
    expectSameTreeOnOneAndAllThreads(dragon, SceneAccel<8>::defaultConfig());
    expectSameTreeOnOneAndAllThreads(dragon, highConfig<8>());
}

/// The SSE sweep over three axes at once picks the plane the scalar sweep per axis picks: least cost
/// (BuildBox::halfArea times blocks, both sides), ties to the lower axis and then the lower bin, planes
/// with an empty side and axes not splittable skipped. Random bins, some empty, some costs tied.
TEST(Bvh, SweepOverThreeAxesEqualsTheScalarSweep) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        const int bins = 2 + int(rng() % 31), axes = 1 + int(rng() % 7), shift = int(rng() % 3);
        AxisBinBoxes<kMaxObjectBins> boxes;
        boxes.clear(bins);
        alignas(16) uint32_t counts[kMaxObjectBins][4] = {};
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < bins; ++b) {
                if (rng() % 3 == 0) continue;  // an empty bin
                counts[b][a] = 1 + rng() % 9;
                // Coordinates on a coarse grid, so that different planes often cost the same.
                auto coord = [&] { return float(rng() % 4); };
                const glm::vec3 p(coord(), coord(), coord()), q(coord(), coord(), coord());
                boxes.grow(a, b, BuildBox(_mm_setr_ps(std::min(p.x, q.x), std::min(p.y, q.y), std::min(p.z, q.z), 0),
                                          _mm_setr_ps(std::max(p.x, q.x), std::max(p.y, q.y), std::max(p.z, q.z), 0)));
            }
        BestPlane expected;
        for (int a = 0; a < 3; ++a) {
            if (!(axes >> a & 1)) continue;
            for (int plane = 0; plane + 1 < bins; ++plane) {
                BuildBox left, right;
                uint32_t nl = 0, nr = 0;
                for (int b = 0; b < bins; ++b) (b <= plane ? left : right).grow(boxes.box(a, b));
                for (int b = 0; b < bins; ++b) (b <= plane ? nl : nr) += counts[b][a];
                if (nl == 0 || nr == 0) continue;
                const uint32_t blockSize = 1u << shift;
                const float cost = left.halfArea() * float((nl + blockSize - 1) / blockSize) +
                                   right.halfArea() * float((nr + blockSize - 1) / blockSize);
                if (cost < expected.cost) expected = {a, plane, cost, nl, nr};
            }
        }
        auto binCounts = [&](int b) { return _mm_load_si128(reinterpret_cast<const __m128i*>(counts[b])); };
        const BestPlane got = sweepPlanes(boxes, bins, axes, uint32_t(shift), binCounts, binCounts);
        ASSERT_EQ(got.axis, expected.axis) << "trial " << trial;
        if (expected.axis < 0) continue;
        EXPECT_EQ(got.bin, expected.bin) << "trial " << trial;
        EXPECT_EQ(got.cost, expected.cost) << "trial " << trial;
        EXPECT_EQ(got.leftCount, expected.leftCount);
        EXPECT_EQ(got.rightCount, expected.rightCount);
    }
}

/// The parallel partition of large nodes gives the serial one's order, not only its sets: the leaves
/// hold their triangles in the same order.
TEST(Bvh, ParallelPartitionEqualsTheSerialOne) {
    const auto geometry = std::make_shared<SceneGeometry>(testMesh());
    for (BvhBuildConfig config : {SceneAccel<8>::defaultConfig(), highConfig<8>()}) {
        config.parallelPartitionMinRefs = std::numeric_limits<uint32_t>::max();
        const SceneAccel<8> serial(geometry, config);
        config.parallelPartitionMinRefs = 2;  // every node with an object split
        const SceneAccel<8> parallel(geometry, config);
        expectSameTree(serial, parallel);
    }
}

} // namespace
} // namespace wideray
