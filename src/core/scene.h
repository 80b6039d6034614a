#pragma once
// A scene as described by a scene file: camera, image settings, lights, materials and objects.
// Meshes are stored once and placed by instances; `flattenTriangles` expands them to world space.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"

namespace wideray {

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 lookAt{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 45.0f;          ///< vertical field of view in degrees
    float aperture = 0.0f;       ///< lens radius; 0 is a pinhole (depth of field is reserved)
    float focusDistance = 0.0f;  ///< 0 means the distance to lookAt
};

struct ImageSettings {
    int width = 640;
    int height = 480;
    int samplesPerPixel = 1;
};

enum class LightType { Point, Directional, Quad, Sphere };

struct Light {
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 position{0.0f};            ///< point, sphere: center; quad: one corner
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< directional: the direction light travels
    glm::vec3 edgeU{1.0f, 0.0f, 0.0f};   ///< quad: corner + s*edgeU + t*edgeV, s,t in [0,1]
    glm::vec3 edgeV{0.0f, 0.0f, 1.0f};
    float radius = 0.0f;                 ///< sphere light radius
    int samples = 1;                     ///< shadow rays per shading point (area lights)
};

enum class MaterialType { Diffuse };

/// A named material. Only Lambertian diffuse for now; `type` leaves room for the Fresnel and Beer
/// materials (conductor, dielectric, ...) that the scene format reserves.
struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    glm::vec3 color{0.8f};
};

/// One placement of a mesh. `material` overrides the mesh's own materials unless it is kMeshMaterials.
struct MeshInstance {
    static constexpr uint32_t kMeshMaterials = UINT32_MAX;
    uint32_t mesh = 0;
    glm::mat4 transform{1.0f};
    uint32_t material = kMeshMaterials;
};

struct Sphere {
    glm::vec3 center{0.0f};
    float radius = 1.0f;
    uint32_t material = 0;
};

struct Scene {
    std::filesystem::path file;  ///< where it was loaded from (for messages)
    Camera camera;
    ImageSettings image;
    glm::vec3 background{0.0f};
    std::vector<Light> lights;
    std::vector<Material> materials;  ///< scene materials first, then those imported from mesh files
    std::vector<TriangleMesh> meshes; ///< each mesh file once; faceMaterial indexes `materials`
    std::vector<MeshInstance> instances;
    std::vector<Sphere> spheres;
};

/// All instanced triangles in world space, in one mesh; faceMaterial indexes scene.materials.
TriangleMesh flattenTriangles(const Scene& scene);

} // namespace wideray
