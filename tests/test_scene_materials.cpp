// Scene files: the material types, textures, fog and render settings, their errors and round trips.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_parser.h"
#include "shading/material_model.h"
#include "temp_dir.h"

namespace wideray {
namespace {

namespace fs = std::filesystem;

const fs::path kSceneFile = "memory/materials.json";

/// A scene of one sphere with the given materials (a JSON object) and extra top-level keys.
std::string sceneWithMaterials(const std::string& materials, const std::string& extra = "") {
    return R"({"materials": )" + materials + "," + extra + (extra.empty() ? "" : ",") +
           R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})";
}

std::string sceneWithMaterial(const std::string& material) { return sceneWithMaterials(R"({"m": )" + material + "}"); }

Material parseMaterial(const std::string& material, const fs::path& file = kSceneFile) {
    const SceneDescription scene = parseScene(sceneWithMaterial(material), file);
    return scene.materials.at(0);
}

void expectError(const std::string& text, const std::string& location, const std::string& fragment) {
    try {
        parseScene(text, kSceneFile);
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const InputError& e) {
        EXPECT_EQ(e.location(), location) << e.what();
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

void expectMaterialError(const std::string& material, const std::string& location, const std::string& fragment) {
    expectError(sceneWithMaterial(material), "materials.m" + (location.empty() ? "" : "." + location), fragment);
}

/// A 2x1 PNG, black on the left and white on the right.
void writeBlackWhitePng(const fs::path& path) {
    Image image(2, 1, 3);
    for (int c = 0; c < 3; ++c) image.at(1, 0)[c] = 1.0f;
    writeImage(image, path, true);
}

// ---- material types

TEST(SceneMaterials, Diffuse) {
    const Material m = parseMaterial(R"({"type": "diffuse", "color": [0.1, 0.2, 0.3]})");
    EXPECT_EQ(m.type, MaterialType::Diffuse);
    EXPECT_EQ(m.color, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FALSE(m.colorTexture);
}

TEST(SceneMaterials, Plastic) {
    const Material m = parseMaterial(R"({"type": "plastic", "color": [0.5, 0, 0], "specular": 0.3, "shininess": 100})");
    EXPECT_EQ(m.type, MaterialType::Plastic);
    EXPECT_EQ(m.color, glm::vec3(0.5f, 0.0f, 0.0f));
    EXPECT_EQ(m.specular, 0.3f);
    EXPECT_EQ(m.shininess, 100.0f);
    const Material defaults = parseMaterial(R"({"type": "plastic"})");
    EXPECT_EQ(defaults.specular, Material{}.specular);
    EXPECT_EQ(defaults.shininess, Material{}.shininess);
    expectMaterialError(R"({"type": "plastic", "specular": 1.5})", "specular", "must be in [0, 1]");
    expectMaterialError(R"({"type": "plastic", "shininess": 0})", "shininess", "must be positive");
    expectMaterialError(R"({"type": "plastic", "ior": 1.5})", "ior", "unknown key \"ior\"");
}

TEST(SceneMaterials, MirrorReflectsEverythingByDefault) {
    EXPECT_EQ(parseMaterial(R"({"type": "mirror"})").type, MaterialType::Mirror);
    EXPECT_EQ(parseMaterial(R"({"type": "mirror"})").color, glm::vec3(1.0f));
    EXPECT_EQ(parseMaterial(R"({"type": "mirror", "color": [0.9, 0.8, 0.7]})").color, glm::vec3(0.9f, 0.8f, 0.7f));
    expectMaterialError(R"({"type": "mirror", "color": [1.1, 1, 1]})", "color", "components must be in [0, 1]");
}

TEST(SceneMaterials, ConductorFromPreset) {
    const Material m = parseMaterial(R"({"type": "conductor", "preset": "gold", "roughness": 0.2})");
    EXPECT_EQ(m.type, MaterialType::Conductor);
    EXPECT_EQ(m.eta, conductorPreset("gold")->eta);
    EXPECT_EQ(m.k, conductorPreset("gold")->k);
    EXPECT_EQ(m.roughness, 0.2f);
    for (const std::string& name : conductorPresetNames())
        EXPECT_EQ(parseMaterial(R"({"type": "conductor", "preset": ")" + name + "\"}").eta, conductorPreset(name)->eta);
}

TEST(SceneMaterials, ConductorFromComplexIor) {
    const Material m = parseMaterial(R"({"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.1]})");
    EXPECT_EQ(m.eta, glm::vec3(0.2f, 0.9f, 1.1f));
    EXPECT_EQ(m.k, glm::vec3(3.9f, 2.4f, 2.1f));
    EXPECT_EQ(m.roughness, 0.0f);
}

TEST(SceneMaterials, ConductorErrors) {
    expectMaterialError(R"({"type": "conductor", "preset": "gould"})", "preset",
                        "unknown conductor preset \"gould\" (did you mean \"gold\"?) (valid presets: aluminium, copper, gold, silver)");
    expectMaterialError(R"({"type": "conductor", "preset": "brass"})", "preset", "valid presets: aluminium, copper, gold, silver");
    expectMaterialError(R"({"type": "conductor"})", "", "needs \"preset\" or both \"eta\" and \"k\"");
    expectMaterialError(R"({"type": "conductor", "preset": "gold", "k": [1, 1, 1]})", "", "cannot be combined");
    expectMaterialError(R"({"type": "conductor", "eta": [1, 1, 1]})", "", "missing required key \"k\"");
    expectMaterialError(R"({"type": "conductor", "eta": [1, 0, 1], "k": [1, 1, 1]})", "eta", "eta components must be positive");
    expectMaterialError(R"({"type": "conductor", "eta": [1, 1, 1], "k": [1, -1, 1]})", "k", "must not be negative");
    expectMaterialError(R"({"type": "conductor", "preset": "gold", "roughness": 2})", "roughness", "must be in [0, 1]");
    expectMaterialError(R"({"type": "conductor", "preset": 3})", "preset", "expected a string");
}

TEST(SceneMaterials, Dielectric) {
    const Material m = parseMaterial(R"({"type": "dielectric", "ior": 1.33, "absorption": [0.5, 0.1, 0], "roughness": 0.1})");
    EXPECT_EQ(m.type, MaterialType::Dielectric);
    EXPECT_EQ(m.ior, 1.33f);
    EXPECT_EQ(m.absorption, glm::vec3(0.5f, 0.1f, 0.0f));
    EXPECT_EQ(m.roughness, 0.1f);
    const Material glass = parseMaterial(R"({"type": "dielectric"})");
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.absorption, glm::vec3(0.0f));
    EXPECT_EQ(parseMaterial(R"({"type": "dielectric", "absorption": [20, 30, 40]})").absorption, glm::vec3(20, 30, 40));
}

TEST(SceneMaterials, DielectricErrors) {
    expectMaterialError(R"({"type": "dielectric", "ior": 0})", "ior", "an index of refraction must be positive");
    expectMaterialError(R"({"type": "dielectric", "ior": -1.5})", "ior", "an index of refraction must be positive");
    expectMaterialError(R"({"type": "dielectric", "absorption": [0, -1, 0]})", "absorption", "must not be negative");
    expectMaterialError(R"({"type": "dielectric", "color": [1, 1, 1]})", "color", "unknown key \"color\"");
    expectMaterialError(R"({"type": "dielectric", "roughness": -0.1})", "roughness", "must be in [0, 1]");
}

TEST(SceneMaterials, UnknownTypeListsTheTypes) {
    expectMaterialError(R"({"type": "glossy"})", "type",
                        "unknown material type \"glossy\" (expected diffuse, plastic, mirror, conductor, dielectric)");
    expectMaterialError(R"({"type": "mirorr"})", "type", "did you mean \"mirror\"?");
}

// ---- textures

TEST(SceneMaterials, ColorTextures) {
    const Material m = parseMaterial(
        R"({"type": "diffuse", "color": {"type": "checker", "colors": [[0, 0, 0], [0.5, 0.6, 0.7]], "scale": 4}})");
    ASSERT_TRUE(m.colorTexture);
    EXPECT_EQ(m.colorTexture->type, TextureType::Checker);
    EXPECT_EQ(m.colorTexture->color1, glm::vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(m.colorTexture->scale, 4.0f);

    const std::pair<const char*, TextureType> patterns[] = {{"fbm", TextureType::Fbm},
                                                            {"turbulence", TextureType::Turbulence},
                                                            {"marble", TextureType::Marble}};
    for (const auto& [name, type] : patterns) {
        const Material p = parseMaterial(R"({"type": "plastic", "color": {"type": ")" + std::string(name) +
                                         R"(", "scale": 2, "octaves": 6}})");
        ASSERT_TRUE(p.colorTexture) << name;
        EXPECT_EQ(p.colorTexture->type, type);
        EXPECT_EQ(p.colorTexture->octaves, 6);
        EXPECT_EQ(p.colorTexture->color0, glm::vec3(0.0f));  // default blend: black to white
        EXPECT_EQ(p.colorTexture->color1, glm::vec3(1.0f));
    }
    EXPECT_EQ(parseMaterial(R"({"type": "mirror", "color": {"type": "noise"}})").colorTexture->type, TextureType::Noise);
}

TEST(SceneMaterials, RoughnessTextures) {
    const Material m = parseMaterial(
        R"({"type": "conductor", "preset": "copper", "roughness": {"type": "turbulence", "values": [0.05, 0.4]}})");
    ASSERT_TRUE(m.roughnessTexture);
    EXPECT_EQ(m.roughnessTexture->type, TextureType::Turbulence);
    EXPECT_EQ(m.roughnessTexture->color0, glm::vec3(0.05f));
    EXPECT_EQ(m.roughnessTexture->color1, glm::vec3(0.4f));
}

TEST(SceneMaterials, TextureErrors) {
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "wood"}})", "color.type",
                        "unknown texture type \"wood\" (expected checker, noise, fbm, turbulence, marble, image)");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "marbel"}})", "color.type", "did you mean \"marble\"?");
    expectMaterialError(R"({"type": "diffuse", "color": {"scale": 2}})", "color", "missing required key \"type\"");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "checker", "octaves": 3}})", "color.octaves", "unknown key");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "noise", "scale": 0}})", "color.scale", "must be positive");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "fbm", "octaves": 0}})", "color.octaves", "must be in 1..16");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "checker", "colors": [[0, 0, 0]]}})", "color.colors",
                        "expected an array of 2 colors");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "checker", "colors": [[0, 0, 0], [2, 0, 0]]}})",
                        "color.colors[1]", "components must be in [0, 1]");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "checker", "values": [0, 1]}})", "color.values",
                        "unknown key \"values\"");
    expectMaterialError(R"({"type": "dielectric", "roughness": {"type": "checker", "colors": [[0, 0, 0], [1, 1, 1]]}})",
                        "roughness.colors", "unknown key \"colors\"");
    expectMaterialError(R"({"type": "dielectric", "roughness": {"type": "checker", "values": [0, 3]}})",
                        "roughness.values[1]", "must be in [0, 1]");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "image"}})", "color", "missing required key \"file\"");
    expectMaterialError(R"({"type": "diffuse", "color": {"type": "image", "file": "missing.png"}})", "color.file",
                        "cannot load texture");
    expectMaterialError(R"({"type": "diffuse", "color": "red"})", "color", "expected an array of 3 numbers");
}

TEST(SceneMaterials, ImageTexturesLoadRelativeToTheSceneOnce) {
    TempDir dir;
    writeBlackWhitePng(dir.path() / "textures/bw.png");
    const std::string text = sceneWithMaterials(
        R"({"a": {"type": "diffuse", "color": {"type": "image", "file": "textures/bw.png"}},
            "b": {"type": "plastic", "color": {"type": "image", "file": "textures/bw.png"}},
            "c": {"type": "conductor", "preset": "silver", "roughness": {"type": "image", "file": "textures/bw.png"}}})");
    const SceneDescription scene = parseScene(text, dir.path() / "scene.json");
    const Material& a = scene.materials.at(0);
    ASSERT_TRUE(a.colorTexture);
    EXPECT_EQ(a.colorTexture->type, TextureType::Image);
    EXPECT_EQ(a.colorTexture->file, fs::absolute(dir.path() / "textures/bw.png").lexically_normal());
    ASSERT_TRUE(a.colorTexture->image);
    EXPECT_EQ(a.colorTexture->image->width, 2);
    EXPECT_EQ(a.colorTexture->image, scene.materials.at(1).colorTexture->image);  // loaded once
    EXPECT_EQ(materialColor(a, {}, {0.25f, 0.5f}), glm::vec3(0.0f));
    EXPECT_EQ(materialColor(a, {}, {0.75f, 0.5f}), glm::vec3(1.0f));
    EXPECT_EQ(materialRoughness(scene.materials.at(2), {}, {0.75f, 0.5f}), 1.0f);
}

// ---- fog and render settings

TEST(SceneMaterials, FogAndRenderSettings) {
    const SceneDescription defaults = parseScene(sceneWithMaterials("{}"), kSceneFile);
    EXPECT_EQ(defaults.fog.density, 0.0f);
    EXPECT_EQ(defaults.render.maxDepth, 8);
    EXPECT_EQ(defaults.render.minThroughput, 0.01f);
    EXPECT_FALSE(defaults.render.polarized);

    const SceneDescription scene = parseScene(
        sceneWithMaterials("{}", R"("fog": {"density": 0.05, "color": [0.7, 0.8, 0.9]},
                                   "render": {"max_depth": 12, "min_throughput": 0.001, "polarized": true})"),
        kSceneFile);
    EXPECT_EQ(scene.fog.density, 0.05f);
    EXPECT_EQ(scene.fog.color, glm::vec3(0.7f, 0.8f, 0.9f));
    EXPECT_EQ(scene.render.maxDepth, 12);
    EXPECT_EQ(scene.render.minThroughput, 0.001f);
    EXPECT_TRUE(scene.render.polarized);
}

TEST(SceneMaterials, FogAndRenderErrors) {
    expectError(sceneWithMaterials("{}", R"("fog": {"color": [1, 1, 1]})"), "fog", "missing required key \"density\"");
    expectError(sceneWithMaterials("{}", R"("fog": {"density": -1})"), "fog.density", "must not be negative");
    expectError(sceneWithMaterials("{}", R"("fog": {"density": 1, "colour": [1, 1, 1]})"), "fog.colour", "did you mean \"color\"?");
    expectError(sceneWithMaterials("{}", R"("render": {"max_depth": 2.5})"), "render.max_depth", "expected an integer");
    expectError(sceneWithMaterials("{}", R"("render": {"max_depth": -1})"), "render.max_depth", "must be in 0..1024");
    expectError(sceneWithMaterials("{}", R"("render": {"min_throughput": 2})"), "render.min_throughput", "must be in [0, 1]");
    expectError(sceneWithMaterials("{}", R"("render": {"polarized": 1})"), "render.polarized", "expected true or false, got a number");
}

// ---- round trip

void expectSameTexture(const std::optional<Texture>& a, const std::optional<Texture>& b) {
    ASSERT_EQ(bool(a), bool(b));
    if (!a) return;
    EXPECT_EQ(a->type, b->type);
    EXPECT_EQ(a->color0, b->color0);
    EXPECT_EQ(a->color1, b->color1);
    EXPECT_EQ(a->scale, b->scale);
    EXPECT_EQ(a->octaves, b->octaves);
    EXPECT_EQ(a->file, b->file);
    EXPECT_EQ(bool(a->image), bool(b->image));
}

TEST(SceneMaterials, RoundTrip) {
    TempDir dir;
    writeBlackWhitePng(dir.path() / "bw.png");
    const std::string text = sceneWithMaterials(
        R"({"diffuse": {"type": "diffuse", "color": {"type": "checker", "colors": [[0.1, 0.2, 0.3], [0.9, 0.8, 0.7]], "scale": 3}},
            "plastic": {"type": "plastic", "color": [0.7, 0.1, 0.1], "specular": 0.25, "shininess": 40},
            "marble": {"type": "plastic", "color": {"type": "marble", "scale": 0.5, "octaves": 7}},
            "mirror": {"type": "mirror", "color": {"type": "image", "file": "bw.png"}},
            "gold": {"type": "conductor", "preset": "gold", "roughness": {"type": "fbm", "values": [0.1, 0.3]}},
            "metal": {"type": "conductor", "eta": [1.1, 1.2, 1.3], "k": [2.1, 2.2, 2.3], "roughness": 0.15},
            "glass": {"type": "dielectric", "ior": 1.52, "absorption": [0.3, 0.01, 0.2], "roughness": {"type": "image", "file": "bw.png"}}})",
        R"("fog": {"density": 0.125, "color": [0.3, 0.4, 0.5]},
           "render": {"max_depth": 3, "min_throughput": 0.05, "polarized": true})");
    const SceneDescription first = parseScene(text, dir.path() / "scene.json");
    const SceneDescription second = parseScene(writeScene(first), "elsewhere/copy.json");
    EXPECT_EQ(writeScene(second), writeScene(first));
    EXPECT_EQ(second.fog.density, first.fog.density);
    EXPECT_EQ(second.fog.color, first.fog.color);
    EXPECT_EQ(second.render.maxDepth, first.render.maxDepth);
    EXPECT_EQ(second.render.minThroughput, first.render.minThroughput);
    EXPECT_EQ(second.render.polarized, first.render.polarized);
    ASSERT_EQ(second.materials.size(), first.materials.size());
    for (size_t i = 0; i < first.materials.size(); ++i) {
        const Material &a = first.materials[i], &b = second.materials[i];
        SCOPED_TRACE(a.name);
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.type, b.type);
        EXPECT_EQ(a.color, b.color);
        EXPECT_EQ(a.specular, b.specular);
        EXPECT_EQ(a.shininess, b.shininess);
        EXPECT_EQ(a.eta, b.eta);
        EXPECT_EQ(a.k, b.k);
        EXPECT_EQ(a.ior, b.ior);
        EXPECT_EQ(a.absorption, b.absorption);
        EXPECT_EQ(a.roughness, b.roughness);
        expectSameTexture(a.colorTexture, b.colorTexture);
        expectSameTexture(a.roughnessTexture, b.roughnessTexture);
    }
}

} // namespace
} // namespace wideray
