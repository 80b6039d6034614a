#include "geometry/instance_geometry.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "geometry/object_space.h"
#include "geometry/scene_geometry.h"

namespace wideray {

std::vector<bool> twoLevelMeshes(const SceneDescription& scene, Instancing instancing) {
    std::vector<uint32_t> uses(scene.meshes.size(), 0);
    std::vector<bool> moves(scene.meshes.size(), false);
    for (const MeshInstance& instance : scene.instances) {
        ++uses.at(instance.mesh);
        if (instance.endTransform) moves[instance.mesh] = true;
    }
    std::vector<bool> twoLevel(scene.meshes.size(), false);
    for (size_t m = 0; m < uses.size(); ++m) {
        const uint64_t copies = uint64_t(uses[m] > 0 ? uses[m] - 1 : 0) * scene.meshes[m].triangles.size();
        twoLevel[m] = uses[m] > 0 && !scene.meshes[m].triangles.empty() &&
                      (moves[m] || instancing == Instancing::TwoLevel ||
                       (instancing == Instancing::Auto && copies >= kAutoTwoLevelTriangles));
    }
    return twoLevel;
}

InstanceGeometry::InstanceGeometry(const SceneDescription& scene, const std::vector<bool>& twoLevel) {
    std::vector<uint32_t> meshIndex(scene.meshes.size(), kInvalidId);
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& instance = scene.instances[i];
        if (!twoLevel[instance.mesh]) continue;
        if (meshIndex[instance.mesh] == kInvalidId) {
            meshIndex[instance.mesh] = uint32_t(meshes_.size());
            meshes_.push_back(std::make_shared<const SceneGeometry>(scene.meshes[instance.mesh]));
        }
        const SceneGeometry& mesh = *meshes_[meshIndex[instance.mesh]];
        if (instancedTriangles_ + mesh.triangleCount() > kInvalidId)
            throw std::length_error("InstanceGeometry: more than 2^32 - 1 instanced triangles (" +
                                    std::to_string(instancedTriangles_ + mesh.triangleCount()) + ")");
        const Bounds3f box = mesh.bounds();
        placements_.push_back({meshIndex[instance.mesh], instance.transform, instance.endTransform, instance.material, i,
                               uint32_t(instancedTriangles_),
                               motionBounds(instance.transform, instance.endTransform, glm::dvec3(box.lower), glm::dvec3(box.upper))});
        instancedTriangles_ += mesh.triangleCount();
    }
}

InstanceGeometry::~InstanceGeometry() = default;

Bounds3f InstanceGeometry::bounds() const {
    Bounds3f b;
    for (const Placement& p : placements_) b.grow(p.bounds);
    return b;
}

uint32_t InstanceGeometry::instanceOf(uint32_t primId) const {
    auto it = std::upper_bound(placements_.begin(), placements_.end(), primId,
                               [](uint32_t prim, const Placement& p) { return prim < p.firstPrim; });
    return uint32_t(it - placements_.begin()) - 1;
}

SurfacePoint InstanceGeometry::surface(const Ray& ray, const Hit& hit) const {
    const Placement& p = placements_[instanceOf(hit.primId)];
    const SceneGeometry& mesh = *meshes_[p.mesh];
    const SurfacePoint local = mesh.surface(ray, {hit.t, hit.u, hit.v, hit.primId - p.firstPrim, 0});
    const ObjectSpace space = p.endTransform ? ObjectSpace::at(p.transform, *p.endTransform, ray.time) : ObjectSpace(p.transform);
    SurfacePoint sp = local;
    sp.position = space.point(glm::dvec3(local.position));
    sp.geometricNormal = space.normal(glm::dvec3(local.geometricNormal));
    sp.shadingNormal = space.normal(glm::dvec3(local.shadingNormal));
    if (p.material != MeshInstance::kMeshMaterials) sp.material = p.material;
    sp.instance = p.sceneInstance;
    return sp;
}

} // namespace wideray
