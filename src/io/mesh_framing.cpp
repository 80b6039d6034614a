#include "io/mesh_framing.h"

#include <map>

#include "core/bounds.h"
#include "core/error.h"
#include "io/file_extension.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/pbrt_parser.h"
#include "io/scene_parser.h"

namespace wideray {

namespace {

/// The benchmark's point light, above and to the side of the model.
Light keyLight(const glm::vec3& c, float R) {
    Light light;
    light.type = LightType::Point;
    light.position = c + glm::vec3(0.5f * R, 2.0f * R, 0.7f * R);
    light.intensity = 4.0f * R * R;
    return light;
}

} // namespace

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
    scene.lights.push_back(keyLight(c, R));
    return scene;
}

SceneDescription showcaseMesh(TriangleMesh mesh, const std::filesystem::path& file, int width, int height) {
    SceneDescription scene;
    scene.file = file;
    Bounds3f b;
    for (const glm::vec3& p : mesh.positions) b.grow(p);
    const glm::vec3 c = b.empty() ? glm::vec3(0.0f) : b.center();
    const float R = b.empty() ? 1.0f : std::max(0.5f * glm::length(b.extent()), 1e-6f);

    // The mesh's own materials, with their images where the mesh has uvs to look them up.
    std::map<std::filesystem::path, std::shared_ptr<const Image>> images;
    for (const MeshMaterial& m : mesh.materials) {
        Material material{m.name, MaterialType::Diffuse, m.diffuse};
        if (!m.diffuseTexture.empty() && !mesh.uvs.empty()) {
            // An image inside the mesh file has a name for messages; one of its own is found by its path.
            std::filesystem::path path = m.diffuseTexture;
            if (!m.diffuseTextureBytes && path.is_relative()) path = file.parent_path() / path;
            auto& image = images[path];
            try {
                if (!image)
                    image = std::make_shared<const Image>(m.diffuseTextureBytes ? readImage(*m.diffuseTextureBytes, path.string(), true)
                                                                               : readImage(path, true));
                Texture texture;
                texture.type = TextureType::Image;
                texture.file = path;
                texture.image = image;
                material.colorTexture = texture;
            } catch (const InputError& e) {
                scene.warnings.push_back(std::string(e.what()) + " (material '" + m.name + "'): its own color instead");
            }
        }
        scene.materials.push_back(std::move(material));
    }
    if (scene.materials.empty() || mesh.faceMaterial.empty()) {
        mesh.faceMaterial.assign(mesh.triangles.size(), uint32_t(scene.materials.size()));
        // A mesh colored per vertex shows its colors as they are; others are grey.
        scene.materials.push_back({"default", MaterialType::Diffuse, glm::vec3(mesh.colors.empty() ? 0.8f : 1.0f)});
    }
    mesh.materials.clear();
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({});

    scene.image = {width, height, 1};
    scene.camera.fovY = 40.0f;
    const float aspect = float(width) / float(height);
    const float halfY = glm::radians(scene.camera.fovY) * 0.5f;
    const float halfAngle = std::min(halfY, std::atan(std::tan(halfY) * aspect));
    const float distance = 1.05f * R / std::sin(halfAngle);
    scene.camera.position = c + glm::normalize(glm::vec3(0.3f, 0.25f, 1.0f)) * distance;
    scene.camera.lookAt = c;
    scene.camera.up = {0.0f, 1.0f, 0.0f};

    const Light key = keyLight(c, R);
    Light fill;
    fill.type = LightType::Point;
    fill.position = scene.camera.position;
    const float keyIrradiance = key.intensity / glm::dot(key.position - c, key.position - c);
    fill.intensity = keyIrradiance / 3.0f * distance * distance;
    scene.lights = {key, fill};
    scene.background = {0.55f, 0.65f, 0.8f};
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

SceneDescription loadSceneOrMesh(const std::filesystem::path& file, int meshWidth, int meshHeight, MeshFraming framing) {
    if (lowercaseExtension(file) == ".pbrt") return loadPbrt(file);
    if (isSceneFile(file)) return loadScene(file);
    if (framing == MeshFraming::Showcase) return showcaseMesh(loadMesh(file), file, meshWidth, meshHeight);
    return sceneFromMesh(file, meshWidth, meshHeight);
}

} // namespace wideray
