#pragma once
// Two-level instancing: the instances of meshes placed many times (Instancing::Auto) keep one copy
// of their mesh, in object space, with its own BVH; a top-level BVH over the instances' boxes
// leads the ray to an instance, where it is taken into object space (accel/scene_accel.h,
// kernels/instance_leaf.h). A hit names its triangle by the primId it has in the flattened form:
// the instance's first primId (instances in scene order, each counting its mesh's triangles) plus
// the triangle's index in its mesh.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/scene.h"

namespace wideray {

class SceneGeometry;

/// Which instances are two-level (moving instances always are): Auto, those of meshes whose copies beyond the first would add
/// kAutoTwoLevelTriangles or more triangles to the flattened form (below that, flattening costs
/// little memory and saves the ray's transform); TwoLevel, all; Flatten, none (every instance's
/// triangles copied into the world-space triangle geometry).
enum class Instancing { Auto, Flatten, TwoLevel };
constexpr uint64_t kAutoTwoLevelTriangles = 1 << 16;

/// Per mesh of the scene: whether its instances are two-level.
std::vector<bool> twoLevelMeshes(const SceneDescription& scene, Instancing instancing);

class InstanceGeometry final : public Geometry {
public:
    struct Placement {
        uint32_t mesh;           ///< index into meshes()
        glm::mat4 transform;     ///< object to world (at time 0 if it moves)
        std::optional<glm::mat4> endTransform;  ///< moving: at time 1
        uint32_t material;       ///< MeshInstance::kMeshMaterials: the mesh's own
        uint32_t sceneInstance;  ///< index into SceneDescription::instances
        uint32_t firstPrim;
        Bounds3f bounds;         ///< world box
    };

    /// The scene's instances of the meshes marked in `twoLevel`.
    InstanceGeometry(const SceneDescription& scene, const std::vector<bool>& twoLevel);
    ~InstanceGeometry() override;

    /// One primitive per instance, bounded by its world box.
    uint32_t primitiveCount() const override { return uint32_t(placements_.size()); }
    Bounds3f primitiveBounds(uint32_t instance) const override { return placements_[instance].bounds; }
    Bounds3f bounds() const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;
    const InstanceGeometry* instances() const override { return this; }

    std::span<const Placement> placements() const { return placements_; }
    /// The instanced meshes in object space, each as a scene geometry of its triangles alone.
    const std::vector<std::shared_ptr<const SceneGeometry>>& meshes() const { return meshes_; }
    /// The triangles of all instances (the flattened form's count).
    uint64_t instancedTriangles() const { return instancedTriangles_; }
    /// The instance whose triangles include primId.
    uint32_t instanceOf(uint32_t primId) const;

private:
    std::vector<Placement> placements_;
    std::vector<std::shared_ptr<const SceneGeometry>> meshes_;
    uint64_t instancedTriangles_ = 0;
};

} // namespace wideray
