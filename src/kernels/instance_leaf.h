#pragma once
// Two-level instances at a leaf of the top-level BVH: the ray is taken into the instance's object
// space and traced through its mesh's BVH with the ISA's single-ray kernel, whatever kernel reached
// the leaf (so every kernel of an ISA finds the same hits). Packets and streams reach it one lane at
// a time through the user leaves (kernels/user_leaf.h). The direction is transformed, not normalized,
// so t is the same in both spaces.
#include "accel/bvh_view.h"
#include "kernels/hit_order.h"
#include "kernels/ray_state.h"
#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The ray in the instance's object space.
inline Ray objectRay(const InstanceRef& instance, const Ray& ray) {
    const double* m = instance.objectFromWorld;
    const double ox = ray.ox, oy = ray.oy, oz = ray.oz, dx = ray.dx, dy = ray.dy, dz = ray.dz;
    Ray local = ray;
    local.ox = float(m[0] * ox + m[1] * oy + m[2] * oz + m[3]);
    local.oy = float(m[4] * ox + m[5] * oy + m[6] * oz + m[7]);
    local.oz = float(m[8] * ox + m[9] * oy + m[10] * oz + m[11]);
    local.dx = float(m[0] * dx + m[1] * dy + m[2] * dz);
    local.dy = float(m[4] * dx + m[5] * dy + m[6] * dz);
    local.dz = float(m[8] * dx + m[9] * dy + m[10] * dz);
    return local;
}

// Declared in kernels/user_leaf.h. Not inlined: the mesh's traversal would otherwise inline into the
// leaf intersector that calls it.
template <int N, bool AnyHit>
[[gnu::noinline]] bool intersectInstance(const InstanceTable& table, uint32_t index, const Ray& ray, Hit& hit,
                                         TraversalCost& cost) {
    const InstanceRef& instance = table.instances[index];
    const Ray local = objectRay(instance, ray);
    if (!isValidRay(local)) return false;
    const SceneView<N>& mesh = table.meshes<N>()[instance.mesh];
    Hit inner;
    inner.t = hit.t;
    const bool occluded = traceSubtree<N, kNodeSimdWidth<N>, kBlockSize, AnyHit, SceneLeafIntersector<N>>(
        mesh, mesh.root, local, makeSingleRayState(local), inner, cost);
    if constexpr (AnyHit) return occluded;
    if (inner.valid()) {
        const uint32_t prim = instance.firstPrim + inner.primId;
        if (isCloser(inner.t, table.geomId, prim, hit)) hit = {inner.t, inner.u, inner.v, prim, table.geomId};
    }
    return false;
}

} // namespace WIDERAY_ISA
} // namespace wideray
