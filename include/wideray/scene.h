#pragma once
/// A scene of triangle meshes, their instances and spheres, built into a wide BVH and traced one ray,
/// one packet or one stream at a time.
///
///     wideray::Scene scene;
///     uint32_t mesh = scene.addTriangleMesh(positions, indices);  // xyz per vertex, 3 indices per triangle
///     scene.build();
///     wideray::Hit hit = scene.intersect(wideray::Ray{0, 0, -5, 0, 0, 1});
///
/// Building is not thread-safe; once built, a scene may be traced from any number of the caller's
/// threads at once. Every error is a wideray::Error.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "wideray/error.h"
#include "wideray/export.h"
#include "wideray/options.h"
#include "wideray/ray.h"

namespace wideray {

class WIDERAY_API Scene {
public:
    explicit Scene(const SceneOptions& options = {});
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    /// Adds a mesh placed as it is and returns its geomId. `positions` holds x, y, z per vertex,
    /// `indices` three vertex indices per triangle; hits name triangles by their index in it.
    uint32_t addTriangleMesh(std::span<const float> positions, std::span<const uint32_t> indices,
                             Sharing sharing = Sharing::Copy);
    /// Places the mesh `meshId` (an id addTriangleMesh returned) once more, moved by `transform`, and
    /// returns the instance's geomId; its hits name the mesh's triangles. Meshes placed many times keep
    /// one copy and a BVH of their own (two-level instancing).
    uint32_t addInstance(uint32_t meshId, const Transform& transform);
    /// Adds spheres (x, y, z per center, one radius each) and returns their geomId; a hit's primId is
    /// the sphere's index (u and v are 0: the hit point is origin + t * direction).
    uint32_t addSpheres(std::span<const float> centers, std::span<const float> radii);

    /// Builds the acceleration structure of everything added so far (again after later additions).
    void build();
    bool built() const;

    /// Closest hit of one ray (a miss: t = infinity, ids kInvalidId).
    Hit intersect(const Ray& ray) const;
    /// Whether anything lies within [tnear, tfar] of the ray.
    bool occluded(const Ray& ray) const;

    /// Packets of K = 4, 8 or 16 rays; lanes that are not valid report a miss and not occluded.
    template <int K>
    HitPacket<K> intersect(const RayPacket<K>& rays) const;
    template <int K>
    std::array<bool, K> occluded(const RayPacket<K>& rays) const;

    /// Streams of any length: hits[i] for rays[i], sizes equal.
    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence = Coherence::Incoherent,
                   Threading threading = Threading::Caller) const;
    /// occluded[i] = 1 if anything lies within [tnear, tfar] of rays[i], else 0.
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence = Coherence::Incoherent,
                  Threading threading = Threading::Caller) const;

    /// The box around everything built: min x, y, z, then max x, y, z.
    std::array<float, 6> bounds() const;
    /// Triangles and spheres built (instances count their mesh's triangles once).
    uint64_t primitiveCount() const;
    /// Bytes of the acceleration structure.
    size_t bytes() const;
    /// The structure and kernels in words ("BVH8 fast, avx512: packet16 / stream").
    std::string description() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

extern template WIDERAY_API HitPacket<4> Scene::intersect<4>(const RayPacket<4>&) const;
extern template WIDERAY_API HitPacket<8> Scene::intersect<8>(const RayPacket<8>&) const;
extern template WIDERAY_API HitPacket<16> Scene::intersect<16>(const RayPacket<16>&) const;
extern template WIDERAY_API std::array<bool, 4> Scene::occluded<4>(const RayPacket<4>&) const;
extern template WIDERAY_API std::array<bool, 8> Scene::occluded<8>(const RayPacket<8>&) const;
extern template WIDERAY_API std::array<bool, 16> Scene::occluded<16>(const RayPacket<16>&) const;

} // namespace wideray
