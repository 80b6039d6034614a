// SpatialBins, the spatial split's binning: binning a reference's parts as its box cut by the bin planes
// (large nodes) holds in each bin everything the clipped triangle's parts do, and counts the same.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "accel/spatial_bins.h"

namespace wideray {
namespace {

bool contains(const BuildBox& outer, const BuildBox& inner) {
    if (inner.empty()) return true;
    for (int k = 0; k < 3; ++k)
        if (outer.lowerAt(k) > inner.lowerAt(k) || outer.upperAt(k) < inner.upperAt(k)) return false;
    return true;
}

TEST(SpatialBins, BoxCutPartsHoldTheClippedTrianglesParts) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), size(0.0f, 0.6f);
    TriangleMesh mesh;
    std::vector<BuildRef> refs;
    BuildBox node;
    for (uint32_t i = 0; i < 2000; ++i) {
        const glm::vec3 center(unit(random), unit(random), unit(random));
        const float extent = size(random) * size(random);  // mostly small, some across several bins
        BuildBox box;
        for (int v = 0; v < 3; ++v) {
            const glm::vec3 p = center + extent * glm::vec3(unit(random), unit(random), unit(random));
            mesh.positions.push_back(p);
            box.grow(_mm_setr_ps(p.x, p.y, p.z, 0.0f));
        }
        mesh.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
        refs.push_back(makeBuildRef(box.bounds(), i));
        node.grow(box);
    }
    const TriangleSplitter splitter(mesh);
    for (int binCount : {2, 8, 32}) {
        SpatialBinMapping clipped(node, binCount), cut(node, binCount);
        cut.clipTriangles = false;
        SpatialBins exact(binCount), boxes(binCount);
        exact.add(refs.data(), refs.size(), 1, clipped, splitter);
        boxes.add(refs.data(), refs.size(), 1, cut, splitter);
        int tighter = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < binCount; ++b) {
                EXPECT_TRUE(contains(boxes.box(a, b), exact.box(a, b))) << "axis " << a << " bin " << b << " of " << binCount;
                EXPECT_TRUE(contains(node, boxes.box(a, b))) << "axis " << a << " bin " << b << " of " << binCount;
                EXPECT_EQ(boxes.enter[b][a], exact.enter[b][a]);
                EXPECT_EQ(boxes.exit[b][a], exact.exit[b][a]);
                tighter += !contains(exact.box(a, b), boxes.box(a, b));
            }
        EXPECT_GT(tighter, 0) << binCount << " bins: clipping the triangles made no bin smaller";
    }
}

} // namespace
} // namespace wideray
