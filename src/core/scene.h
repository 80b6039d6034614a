#pragma once
// A scene as described by a scene file: camera, image settings, lights, materials and objects.
// Meshes are stored once and placed by instances; geometry/scene_geometry.h builds the geometry
// that renderers and acceleration structures use from it.
#include <cstdint>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/environment.h"
#include "core/mesh.h"
#include "core/texture.h"

namespace wideray {

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 lookAt{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 45.0f;          ///< vertical field of view in degrees
    float aperture = 0.0f;       ///< lens radius; 0 is a pinhole
    float focusDistance = 0.0f;  ///< 0 means the distance to lookAt
    float shutterOpen = 0.0f, shutterClose = 0.0f;  ///< the times within [0, 1] the camera's rays sample
};

/// The camera at one frame of an animation (core/camera_path.h interpolates between keys).
struct CameraKey {
    int frame = 0;
    Camera camera;
};

/// A camera path over a range of frames: `render` writes one image per frame (NAME_0001.png, ...).
struct Animation {
    int firstFrame = 1, lastFrame = 1;  ///< inclusive
    std::vector<CameraKey> keys;        ///< at least one, frames strictly increasing
};

struct ImageSettings {
    int width = 640;
    int height = 480;
    int samplesPerPixel = 1;
};

enum class LightType { Point, Directional, Quad, Triangle, Sphere };

struct Light {
    LightType type = LightType::Point;
    bool isArea() const { return type == LightType::Quad || type == LightType::Triangle || type == LightType::Sphere; }
    /// Quads and triangles emit on the side edgeU x edgeV points to.
    bool isPlanar() const { return type == LightType::Quad || type == LightType::Triangle; }
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 position{0.0f};            ///< point, sphere: center; quad, triangle: one corner
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< directional: the direction light travels
    glm::vec3 edgeU{1.0f, 0.0f, 0.0f};   ///< quad: corner + s*edgeU + t*edgeV, s,t in [0,1] (triangle: s+t <= 1)
    glm::vec3 edgeV{0.0f, 0.0f, 1.0f};
    float radius = 0.0f;                 ///< sphere light radius
    int samples = 1;                     ///< shadow rays per shading point (area lights)
};

enum class MaterialType { Diffuse, Plastic, Mirror, Conductor, Dielectric };

/// A named material. Each type reads only its own fields; src/shading/material_model.h shades them.
struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    glm::vec3 color{0.8f};                  ///< diffuse, plastic: albedo; mirror: reflectance
    std::optional<Texture> colorTexture{};  ///< replaces `color` where set
    float specular = 0.5f;                  ///< plastic: weight of the Blinn-Phong highlight
    float shininess = 64.0f;                ///< plastic: Blinn-Phong exponent
    glm::vec3 eta{1.0f}, k{0.0f};           ///< conductor: complex index of refraction eta + ik per channel
    float ior = 1.5f;                       ///< dielectric: index of refraction (the outside is vacuum)
    glm::vec3 absorption{0.0f};             ///< dielectric: Beer absorption coefficient per unit length
    float roughness = 0.0f;                 ///< conductor, dielectric: 0 is smooth, up to 1 for glossy
    std::optional<Texture> roughnessTexture{};  ///< replaces `roughness` where set
    int samples = 1;                        ///< conductor, dielectric: rays a glossy lobe branches into
};

/// One placement of a mesh. `material` overrides the mesh's own materials unless it is kMeshMaterials.
struct MeshInstance {
    static constexpr uint32_t kMeshMaterials = UINT32_MAX;
    uint32_t mesh = 0;
    glm::mat4 transform{1.0f};
    uint32_t material = kMeshMaterials;
    /// Moving instances: the transform at time 1 (`transform` is at time 0), interpolated linearly
    /// entry by entry in between, as Embree does.
    std::optional<glm::mat4> endTransform{};
};

struct Sphere {
    glm::vec3 center{0.0f};
    float radius = 1.0f;
    uint32_t material = 0;
};

/// The analytic primitives, each in its canonical object space (docs/scene-format.md) and placed by
/// an affine transform: quadrics (the ends at y = -1 and 1 closed by caps where `capped`), the general
/// quadric by its coefficients within [-1, 1]^3, the torus around the y axis, and blobs.
enum class AnalyticShape : uint8_t { Ellipsoid, Cylinder, Cone, Paraboloid, Hyperboloid, TwoSheetHyperboloid, Quadric, Torus, Blob };

/// A ball of a blob: its field strength * (1 - r^2 / radius^2)^3 within `radius` of `center`, 0
/// beyond (Wyvill's soft objects).
struct BlobBall {
    glm::vec3 center{0.0f};
    float radius = 1.0f;
    float strength = 1.0f;  ///< negative strengths carve
};

struct AnalyticObject {
    AnalyticShape shape = AnalyticShape::Ellipsoid;
    glm::mat4 transform{1.0f};  ///< object to world, affine and invertible
    std::optional<glm::mat4> endTransform{};  ///< moving objects: at time 1, as MeshInstance's
    /// Quadric: A..J of A x^2 + B y^2 + C z^2 + D xy + E xz + F yz + G x + H y + I z + J = 0.
    std::array<float, 10> coefficients{};
    float majorRadius = 1.0f, minorRadius = 0.25f;  ///< torus
    std::vector<BlobBall> balls;                      ///< blob: the surface where their field sum is `threshold`
    float threshold = 0.5f;
    bool capped = true;
    uint32_t material = 0;
};

/// Constructive solid geometry: a tree of set operations over closed solids. Difference is the first
/// operand minus all the others; xor is inside where an odd number of its operands are.
enum class CsgOperation : uint8_t { Union, Intersection, Difference, Xor };

/// A node of a CSG tree: an operation over other nodes, or a leaf solid: an analytic primitive
/// (closed: quadrics capped, no general quadric) or a closed triangle mesh placed by an instance.
struct CsgNode {
    enum class Kind : uint8_t { Operation, Analytic, Mesh };
    Kind kind = Kind::Operation;
    CsgOperation operation = CsgOperation::Union;
    uint32_t solid = 0;              ///< Analytic: index into CsgObject::analytics; Mesh: into CsgObject::meshes
    std::vector<uint32_t> operands;  ///< Operation: node indices, at least two
};

/// One CSG object of the scene; its surfaces keep the materials of the solids they come from.
struct CsgObject {
    std::vector<CsgNode> nodes;  ///< nodes[0] is the root
    std::vector<AnalyticObject> analytics;
    std::vector<MeshInstance> meshes;  ///< SceneDescription::meshes placed in world space
};

/// Musgrave's ridged multifractal over [-1, 1]^2 (io/terrain.h): the generated shape "terrain" and
/// the height-field primitive.
struct TerrainParameters {
    int resolution = 128;    ///< cells per side
    int octaves = 6;
    float lacunarity = 2.0f; ///< frequency ratio of successive octaves
    float gain = 2.0f;       ///< how strongly the ridges of one octave weight the next
    float offset = 1.0f;     ///< where the ridges lie: offset - |noise|
    float roughness = 1.0f;  ///< H: octave i is weighted by lacunarity^(-i H)
    float frequency = 2.0f;  ///< of the first octave, over [-1, 1]
    float height = 0.25f;    ///< the heights are scaled to [0, height]
    uint32_t seed = 0;       ///< moves the noise domain
};

/// A height field traced directly (geometry/heightfield_geometry.h): heights over [-1, 1]^2 in
/// object space, placed by an affine transform.
struct HeightField {
    TerrainParameters terrain;
    std::vector<float> heights;  ///< (resolution + 1)^2, x fastest
    glm::mat4 transform{1.0f};
    uint32_t material = 0;
};

/// A homogeneous medium filling the box around the scene's objects and lights: light over a distance
/// d keeps exp(-density d) of itself, and the fog scatters the lights' light towards the viewer.
struct Fog {
    float density = 0.0f;  ///< extinction per unit length; 0: no fog
    glm::vec3 color{1.0f};  ///< the fraction of the extinguished light that is scattered (the albedo)
};

/// How light is gathered: Whitted-style recursion (direct light at diffuse surfaces, specular and
/// glossy paths followed) or unidirectional path tracing (src/shading/path_vertex.h).
enum class Integrator { Whitted, Path };

struct RenderSettings {
    Integrator integrator = Integrator::Whitted;
    int maxDepth = 8;             ///< bounces of reflection and refraction (path: scattering events)
    float minThroughput = 0.01f;  ///< Whitted: paths carrying less are ended
    bool polarized = false;       ///< track s and p polarization through Fresnel events
};

struct SceneDescription {
    std::filesystem::path file;  ///< where it was loaded from (for messages)
    Camera camera;
    std::optional<Animation> animation;  ///< a moving camera; none: one still image
    ImageSettings image;
    glm::vec3 background{0.0f};           ///< the radiance of every direction that leaves the scene...
    std::optional<EnvironmentMap> environment;  ///< ...unless an environment map gives it per direction
    Fog fog;
    RenderSettings render;
    std::vector<Light> lights;
    std::vector<Material> materials;  ///< scene materials first, then those imported from mesh files
    std::vector<TriangleMesh> meshes; ///< each mesh file once; faceMaterial indexes `materials`
    std::vector<MeshInstance> instances;
    std::vector<Sphere> spheres;
    std::vector<AnalyticObject> analytics;
    std::vector<HeightField> heightFields;
    std::vector<CsgObject> csgs;
    /// What the loader approximated or left out (pbrt import), "FILE:LINE: what", one line each.
    std::vector<std::string> warnings;
};

} // namespace wideray
