// What distributed batch rendering rests on, without MPI: animated cameras (parsing, interpolation,
// round trip), frames cut into runs of tiles and joined again bit for bit, and the messages ranks send.
#include <algorithm>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "backends/wideray_structure.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "io/scene_parser.h"
#include "mpi/part_message.h"
#include "render/frame_parts.h"
#include "render/renderer.h"
#include "render/tile_renderer.h"
#include "temp_dir.h"

namespace wideray {
namespace {

const std::filesystem::path kSourceDir = WIDERAY_SOURCE_DIR;

/// A scene of one sphere with `animation` (JSON) as its "animation".
SceneDescription animatedScene(const std::string& animation) {
    return parseScene(R"({"camera": {"position": [0, 0, 5], "fov": 40}, "animation": )" + animation +
                          R"(, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})",
                      "anim.json");
}

std::string animationError(const std::string& animation) {
    try {
        animatedScene(animation);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(Animation, KeyframesAreMetExactlyAndHeldOutsideTheirFrames) {
    const SceneDescription scene = animatedScene(R"({"frames": [0, 40], "keyframes": [
        {"frame": 5, "position": [0, 0, 5], "look_at": [0, 0, 0]},
        {"frame": 12, "position": [3, 1, 4], "look_at": [0.5, 0, 0], "fov": 30},
        {"frame": 30, "position": [4, 2, -1], "look_at": [0, 0.2, 0]}]})");
    ASSERT_TRUE(scene.animation);
    const Animation& a = *scene.animation;
    EXPECT_EQ(a.firstFrame, 0);
    EXPECT_EQ(a.lastFrame, 40);
    for (const CameraKey& key : a.keys) {
        const Camera c = cameraAtFrame(a, key.frame);
        EXPECT_EQ(c.position, key.camera.position);
        EXPECT_EQ(c.lookAt, key.camera.lookAt);
        EXPECT_EQ(c.fovY, key.camera.fovY);
    }
    EXPECT_EQ(a.keys[1].camera.fovY, 30.0f);
    EXPECT_EQ(a.keys[2].camera.fovY, 40.0f) << "keys not given come from the scene's camera";
    EXPECT_EQ(cameraAtFrame(a, 0).position, a.keys[0].camera.position);
    EXPECT_EQ(cameraAtFrame(a, 40).position, a.keys[2].camera.position);
    // Between keys: continuous (no frame-to-frame jump larger than the keys' spacing suggests), fov linear.
    EXPECT_FLOAT_EQ(cameraAtFrame(a, 21).fovY, 35.0f);
    for (int f = 5; f < 30; ++f)
        EXPECT_LT(glm::length(cameraAtFrame(a, f + 1).position - cameraAtFrame(a, f).position), 1.0f) << f;
}

TEST(Animation, EvenlySpacedCollinearKeysMoveAtConstantSpeed) {
    // Catmull-Rom tangents over frame numbers: keys on a line at even speed are followed exactly.
    const SceneDescription scene = animatedScene(R"({"keyframes": [
        {"frame": 1, "position": [0, 0, 5]}, {"frame": 11, "position": [2, 0, 5]},
        {"frame": 16, "position": [3, 0, 5]}, {"frame": 36, "position": [7, 0, 5]}]})");
    const Animation& a = *scene.animation;
    EXPECT_EQ(a.firstFrame, 1);
    EXPECT_EQ(a.lastFrame, 36);
    for (int f = 1; f <= 36; ++f) EXPECT_NEAR(cameraAtFrame(a, f).position.x, 0.2f * float(f - 1), 1e-5f) << f;
}

TEST(Animation, ACameraListGivesOneCameraPerFrame) {
    const SceneDescription scene = animatedScene(R"({"frames": [10, 12], "cameras": [
        {"position": [0, 0, 5]}, {"position": [1, 0, 5], "fov": 20}, {"position": [2, 0, 5]}]})");
    const Animation& a = *scene.animation;
    EXPECT_EQ(a.firstFrame, 10);
    EXPECT_EQ(a.lastFrame, 12);
    EXPECT_EQ(cameraAtFrame(a, 11).position, glm::vec3(1, 0, 5));
    EXPECT_EQ(cameraAtFrame(a, 11).fovY, 20.0f);
    EXPECT_EQ(cameraAtFrame(a, 12).position, glm::vec3(2, 0, 5));
}

TEST(Animation, BadAnimationsNameTheirKey) {
    auto expectError = [](const std::string& animation, const std::string& fragment) {
        const std::string message = animationError(animation);
        EXPECT_NE(message.find(fragment), std::string::npos) << animation << " gave: " << message;
        EXPECT_EQ(message.rfind("anim.json:", 0), 0u) << message;
    };
    expectError(R"({"keyframes": [{"frame": 3}, {"frame": 3}]})", "animation.keyframes[1].frame: keyframes must come in increasing");
    expectError(R"({"keyframes": [{"position": [1, 0, 0]}]})", "animation.keyframes[0]: missing required key \"frame\"");
    expectError(R"({"keyframes": []})", "animation.keyframes: must not be empty");
    expectError(R"({"frames": [1, 4], "cameras": [{}, {}]})", "animation.frames: covers 4 frames but \"cameras\" lists 2");
    expectError(R"({"frames": [5, 2], "keyframes": [{"frame": 1}]})", "animation.frames[1]: must be in 5..999999");
    expectError(R"({"frames": [1, 2]})", "expected either \"keyframes\" or \"cameras\"");
    expectError(R"({"keyframes": [{"frame": 1}], "cameras": [{}]})", "expected either \"keyframes\" or \"cameras\"");
    expectError(R"({"keyframes": [{"frame": 1, "look_at": [0, 0, 5]}]})", "animation.keyframes[0]: look_at must differ");
    expectError(R"({"keyframes": [{"frame": 1, "speed": 2}]})", "unknown key \"speed\"");
    // Valid keys whose path passes through its look_at point between them.
    expectError(R"({"keyframes": [{"frame": 0, "position": [-1, 0, 0], "look_at": [1, 0, 0]},
                                  {"frame": 2, "position": [1, 0, 0], "look_at": [-1, 0, 0]}]})",
                "animation: the camera at frame 1: look_at must differ from position");
}

TEST(Animation, SurvivesAWriteAndReadBack) {
    const SceneDescription scene = animatedScene(R"({"frames": [2, 30], "keyframes": [
        {"frame": 1, "position": [0, 0, 5]}, {"frame": 9, "position": [3, 1, 4], "fov": 30},
        {"frame": 20, "position": [4, 2, -1], "look_at": [0, 0.2, 0], "shutter": [0, 0.5]}]})");
    const SceneDescription back = parseScene(writeScene(scene), "back.json");
    ASSERT_TRUE(back.animation);
    EXPECT_EQ(back.animation->firstFrame, 2);
    EXPECT_EQ(back.animation->lastFrame, 30);
    for (int f = 0; f <= 31; ++f) {
        const Camera a = cameraAtFrame(*scene.animation, f), b = cameraAtFrame(*back.animation, f);
        EXPECT_EQ(a.position, b.position) << f;
        EXPECT_EQ(a.lookAt, b.lookAt) << f;
        EXPECT_EQ(a.up, b.up) << f;
        EXPECT_EQ(a.fovY, b.fovY) << f;
        EXPECT_EQ(a.shutterClose, b.shutterClose) << f;
    }
    EXPECT_FALSE(parseScene(writeScene(loadScene(kSourceDir / "scenes/default.json")), "x.json").animation);
}

TEST(Animation, FramesAreReadWithoutLoadingMeshes) {
    TempDir dir;
    const std::filesystem::path file = dir.path() / "anim.json";
    std::ofstream(file) << R"({"animation": {"frames": [3, 7], "keyframes": [{"frame": 1, "position": [0, 0, 5]}]},
                               "objects": [{"type": "mesh", "file": "missing.obj"}]})";
    const std::optional<FrameRange> range = loadSceneFrames(file);
    ASSERT_TRUE(range);
    EXPECT_EQ(range->first, 3);
    EXPECT_EQ(range->last, 7);
    EXPECT_THROW(loadScene(file), InputError);
    EXPECT_FALSE(loadSceneFrames(kSourceDir / "scenes/default.json"));
    std::ofstream(file) << R"({"animation": {"keyframes": [{"frame": -1}]}, "objects": []})";
    EXPECT_THROW(loadSceneFrames(file), InputError);
}

TEST(FrameParts, PartsCoverEveryTileOnce) {
    const std::vector<TileRect> tiles(13, TileRect{0, 0, 1, 1});
    for (uint32_t parts : {1u, 2u, 5u, 13u, 14u, 40u}) {
        size_t next = 0;
        for (uint32_t p = 0; p < parts; ++p) {
            const std::span<const TileRect> run = partTiles(tiles, p, parts);
            EXPECT_EQ(run.data(), tiles.data() + next) << parts;
            next += run.size();
            EXPECT_LE(run.size(), (tiles.size() + parts - 1) / parts);
        }
        EXPECT_EQ(next, tiles.size()) << parts;
    }
}

/// The default scene rendered whole, and in `parts` parts joined in a shuffled order.
void expectPartsJoinToTheWholeImage(Aov aov, uint32_t parts, int width, int height) {
    FlushToZeroScope ftz;
    const SceneDescription scene = loadScene(kSourceDir / "scenes/default.json");
    std::unique_ptr<Tracer> tracer = buildWideBvh(std::make_shared<const SceneGeometry>(scene), {})->tracer({"auto"});
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.aov = aov;
    RenderStats wholeStats;
    const Image whole = render(scene, *tracer, options, wholeStats);

    std::vector<uint32_t> order(parts);
    for (uint32_t p = 0; p < parts; ++p) order[p] = p;
    std::shuffle(order.begin(), order.end(), std::mt19937(parts));
    FrameAssembler assembler;
    for (size_t i = 0; i < order.size(); ++i) {
        FramePart part = renderPart(scene, *tracer, options, {7, order[i], parts});
        // Through the bytes a rank would send.
        RankMessage message{RankMessage::Kind::Part, std::move(part), {}, {}};
        RankMessage received = decodeMessage(encodeMessage(message));
        EXPECT_EQ(assembler.add(std::move(received.part)), i + 1 == order.size());
    }
    RenderStats stats;
    const Image joined = assembler.finish(stats);
    EXPECT_TRUE(joined.pixels == whole.pixels) << "aov " << int(aov) << ", " << parts << " parts";
    EXPECT_EQ(stats.totalRays(), wholeStats.totalRays());
    EXPECT_EQ(stats.maxCost, wholeStats.maxCost);
}

TEST(FrameParts, JoinedPartsAreTheWholeImageBitForBit) {
    expectPartsJoinToTheWholeImage(Aov::Color, 1, 120, 90);
    expectPartsJoinToTheWholeImage(Aov::Color, 7, 120, 90);
    expectPartsJoinToTheWholeImage(Aov::Cost, 5, 120, 90);
    expectPartsJoinToTheWholeImage(Aov::Depth, 3, 120, 90);
    expectPartsJoinToTheWholeImage(Aov::Color, 9, 10, 10);  // more parts than tiles
}

TEST(FrameParts, PartsThatDoNotFitTheirFrameAreRefused) {
    FramePart part;
    part.item = {0, 0, 2};
    part.width = 32;
    part.height = 32;
    part.tileSize = 16;
    part.samplesPerPixel = 1;
    part.film.pixels.assign(2 * 16 * 16 * 3, 0.5f);  // the first 2 of 4 tiles
    FrameAssembler assembler;
    EXPECT_FALSE(assembler.add(FramePart(part)));
    EXPECT_THROW(assembler.add(FramePart(part)), std::runtime_error) << "a part twice";
    FramePart other = part;
    other.item.part = 1;
    other.width = 48;
    EXPECT_THROW(assembler.add(std::move(other)), std::runtime_error) << "another size";
    other = part;
    other.item.part = 1;
    other.film.pixels.pop_back();
    EXPECT_THROW(assembler.add(std::move(other)), std::invalid_argument) << "too few values";
}

TEST(PartMessage, RoundTripsAndRefusesTruncatedBytes) {
    RankMessage failure{RankMessage::Kind::Failure, {}, {3, 1, 4}, "scene.json: broken"};
    const RankMessage back = decodeMessage(encodeMessage(failure));
    EXPECT_EQ(back.kind, RankMessage::Kind::Failure);
    EXPECT_EQ(back.item.job, 3u);
    EXPECT_EQ(back.item.parts, 4u);
    EXPECT_EQ(back.error, failure.error);
    EXPECT_EQ(decodeMessage(encodeMessage(RankMessage{})).kind, RankMessage::Kind::Ready);

    RankMessage part{RankMessage::Kind::Part, {}, {}, {}};
    part.part.film.pixels = {1, 2, 3};
    part.part.engine = "wideray";
    std::vector<std::byte> bytes = encodeMessage(part);
    for (size_t n : {size_t(0), size_t(1), bytes.size() / 2, bytes.size() - 1})
        EXPECT_THROW(decodeMessage(std::span(bytes).first(n)), std::runtime_error) << n;
    bytes.push_back(std::byte{0});
    EXPECT_THROW(decodeMessage(bytes), std::runtime_error);
}

} // namespace
} // namespace wideray
