// Renders: independent of the thread count, the kernel and the build quality, and stable against a
// stored reference image.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "core/error.h"
#include "core/fp_mode.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "render/render_memory.h"
#include "render/renderer.h"
#include "io/scene_parser.h"
#include "backends/wideray_structure.h"
#include "render_helpers.h"
#include "test_data.h"

namespace wideray {
namespace {

const std::filesystem::path kSourceDir = WIDERAY_SOURCE_DIR;

Image renderDefault(int threads, Aov aov, int width, int height, RenderStats* statsOut = nullptr) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.aov = aov;
    return renderWithReference(loadScene(kSourceDir / "scenes/default.json"), threads, options, statsOut);
}

TEST(Render, DefaultSceneIsIdenticalWithOneAndTwoThreads) {
    for (Aov aov : {Aov::Color, Aov::Cost}) {
        Image one = renderDefault(1, aov, 200, 150), two = renderDefault(2, aov, 200, 150);
        ASSERT_EQ(one.pixels.size(), two.pixels.size());
        EXPECT_TRUE(one.pixels == two.pixels) << "aov " << int(aov);
    }
}

TEST(Render, DefaultSceneMatchesStoredReference) {
    Image image = renderDefault(2, Aov::Color, 160, 120);
    Image reference = readImage(kSourceDir / "tests/data/default_160x120.png", true);
    ASSERT_EQ(reference.width, 160);
    ASSERT_EQ(reference.height, 120);
    ASSERT_EQ(reference.channels, 3);
    // Compared in 8-bit sRGB steps, as stored: allow rounding, and a few pixels of larger change.
    std::filesystem::path written = std::filesystem::temp_directory_path() / "wideray_render_test.png";
    writeImage(image, written, true);
    Image roundTrip = readImage(written, true);
    std::filesystem::remove(written);
    double sum = 0;
    size_t large = 0;
    for (size_t i = 0; i < reference.pixels.size(); ++i) {
        double d = std::abs(double(roundTrip.pixels[i]) - double(reference.pixels[i]));
        sum += d;
        large += d > 0.02;
    }
    EXPECT_LT(sum / double(reference.pixels.size()), 0.002);
    EXPECT_LT(large, reference.pixels.size() / 200);
}

TEST(Render, AovsAreMeaningful) {
    RenderStats stats;
    Image cost = renderDefault(2, Aov::Cost, 64, 48, &stats);
    EXPECT_GT(stats.maxCost, 1u);
    EXPECT_EQ(stats.shadowRays, 0u);
    Image depth = renderDefault(2, Aov::Depth, 64, 48);
    ASSERT_EQ(depth.channels, 1);
    float center = depth.at(32, 24)[0];
    EXPECT_GT(center, 1.0f) << "the back of the room is several units away";
    Image normal = renderDefault(2, Aov::Normal, 64, 48);
    for (float v : normal.pixels) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
}

} // namespace
} // namespace wideray

namespace wideray {
namespace {

/// Every kernel, with and without the shadow cache, renders exactly the reference's image.
TEST(Render, KernelsAndShadowCacheRenderTheReferenceImage) {
    FlushToZeroScope ftz;
    SceneDescription scene = loadScene(kSourceDir / "scenes/metals.json");
    std::shared_ptr<const Structure> bvh = buildWideBvh(std::make_shared<const SceneGeometry>(scene), {});
    RenderOptions options;
    options.width = 96;
    options.height = 72;
    auto renderWith = [&](const std::string& kernel, bool cache) {
        std::unique_ptr<Tracer> tracer = bvh->tracer({kernel, std::nullopt, cache});
        RenderStats stats;
        Image image = render(scene, *tracer, options, stats);
        if (cache) {
            EXPECT_NE(tracer->statsReport(), "") << "reflections cast cached shadow rays";
        }
        return image;
    };
    Image reference = renderWith("scalar", false);
    for (const char* k : {"auto", "single", "packet4", "stream", "drst"})
        for (bool cache : {false, true}) {
            if (cache && std::string(k) != "single") continue;
            EXPECT_TRUE(renderWith(k, cache).pixels == reference.pixels) << k << " cache " << cache;
        }
}

} // namespace
} // namespace wideray

namespace wideray {
namespace {

/// Spatial splits change the tree, never a hit: the same primitive at the same t, so the same image.
TEST(Render, HighQualityBuildRendersTheSameImage) {
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "needs ../shared/scenes (or WIDERAY_SCENES)";
    FlushToZeroScope ftz;
    SceneDescription scene = loadSceneOrMesh((*dir / "crytek-sponza/sponza.obj").string(), 96, 72);
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    RenderOptions options;
    options.width = 96;
    options.height = 72;
    auto renderWith = [&](const char* quality) {
        StructureOptions structure;
        structure.quality = quality;
        std::shared_ptr<const Structure> bvh = buildWideBvh(geometry, structure);
        RenderStats stats;
        return render(scene, *bvh->tracer({"auto"}), options, stats);
    };
    const Image fast = renderWith("fast"), high = renderWith("high");
    EXPECT_TRUE(fast.pixels == high.pixels);
}

TEST(RenderMemory, OversizeImagesAreRefusedWithTheEstimate) {
    constexpr uint64_t kGiB = uint64_t(1) << 30;
    RenderOptions huge;
    huge.width = huge.height = 65536;
    try {
        checkRenderFits(huge, "big.json", 24 * kGiB);
        ADD_FAILURE() << "a 65536x65536 image passed on a 24 GiB machine";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "big.json: 65536x65536 needs 96.0 GiB for its film and image; this machine has 24.0 GiB");
    }
    RenderOptions hd;
    hd.width = 1920, hd.height = 1080;
    EXPECT_NO_THROW(checkRenderFits(hd, "hd.json", 24 * kGiB));
    EXPECT_EQ(renderBytes(hd), uint64_t(2) * 1920 * 1080 * 3 * 4);
    hd.aov = Aov::Cost;
    EXPECT_EQ(renderBytes(hd), uint64_t(2) * 1920 * 1080 * 4 * 4);
    EXPECT_GT(physicalMemoryBytes(), kGiB / 4);
}

} // namespace
} // namespace wideray
