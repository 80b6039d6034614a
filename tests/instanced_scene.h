#pragma once
// A scene of instanced meshes for the two-level instancing tests: a field of tori and icospheres
// turned, scaled unevenly and one mirrored, on a floor that is instanced once, with a sphere.
#include <glm/gtc/matrix_transform.hpp>

#include "core/scene.h"
#include "io/mesh_generators.h"

namespace wideray::testing {

inline SceneDescription instancedScene(int side = 5) {
    SceneDescription scene;
    scene.materials = {{"grey"}, {"red"}};
    scene.meshes = {makeTorus(0.8f, 0.3f, 32, 16), makeIcosphere(2), makeQuad()};
    scene.meshes[0].faceMaterial.assign(scene.meshes[0].triangles.size(), 0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(2.2f * float(i - side / 2), 0.0f, 2.2f * float(j - side / 2)));
            m = glm::rotate(m, 0.4f * float(i + 3 * j), glm::normalize(glm::vec3(1.0f, float(i), 0.5f)));
            m = glm::scale(m, glm::vec3(1.0f, 0.6f + 0.1f * float(j), (i + j) % 7 == 3 ? -0.8f : 0.8f));  // one mirrored
            scene.instances.push_back({uint32_t((i + j) % 2), m, (i * j) % 3 == 1 ? 1u : MeshInstance::kMeshMaterials});
        }
    scene.instances.push_back({2, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, -1.2f, 0)), glm::vec3(8.0f)),
                               MeshInstance::kMeshMaterials});
    scene.spheres.push_back({{0.0f, 1.6f, 0.0f}, 0.7f, 1});
    scene.camera.position = {1.5f, 5.0f, 9.0f};
    scene.camera.lookAt = {0.0f, 0.0f, 0.0f};
    scene.lights.push_back({});
    scene.lights[0].position = {2.0f, 6.0f, 3.0f};
    return scene;
}

} // namespace wideray::testing
