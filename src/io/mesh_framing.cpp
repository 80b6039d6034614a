#include "io/mesh_framing.h"

#include "core/bounds.h"
#include "io/file_extension.h"
#include "io/mesh_io.h"
#include "io/pbrt_parser.h"
#include "io/scene_parser.h"

namespace wideray {

SceneDescription sceneFromMesh(TriangleMesh mesh, int width, int height) {
    SceneDescription scene;
    scene.materials.push_back({"default", MaterialType::Diffuse, glm::vec3(0.8f)});
    mesh.faceMaterial.assign(mesh.triangles.size(), 0);
    mesh.materials.clear();
    Bounds3f b;
    for (const glm::vec3& p : mesh.positions) b.grow(p);
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({});

    glm::vec3 c = b.center();
    float R = 0.5f * glm::length(b.extent());
    scene.camera.position = c + glm::normalize(glm::vec3(0.3f, 0.25f, 1.0f)) * (1.2f * R);
    scene.camera.lookAt = c;
    scene.camera.up = {0.0f, 1.0f, 0.0f};
    scene.camera.fovY = 50.0f;
    scene.image = {width, height, 1};
    Light light;
    light.type = LightType::Point;
    light.position = c + glm::vec3(0.5f * R, 2.0f * R, 0.7f * R);
    light.intensity = 4.0f * R * R;
    scene.lights.push_back(light);
    return scene;
}

SceneDescription sceneFromMesh(const std::filesystem::path& meshFile, int width, int height) {
    SceneDescription scene = sceneFromMesh(loadMesh(meshFile), width, height);
    scene.file = meshFile;
    return scene;
}

bool isSceneFile(const std::filesystem::path& file) {
    const std::string ext = lowercaseExtension(file);
    return ext == ".json" || ext == ".pbrt";
}

std::optional<FrameRange> sceneFileFrames(const std::filesystem::path& file) {
    return lowercaseExtension(file) == ".json" ? loadSceneFrames(file) : std::nullopt;
}

SceneDescription loadSceneOrMesh(const std::filesystem::path& file, int meshWidth, int meshHeight) {
    if (lowercaseExtension(file) == ".pbrt") return loadPbrt(file);
    if (isSceneFile(file)) return loadScene(file);
    return sceneFromMesh(file, meshWidth, meshHeight);
}

} // namespace wideray
