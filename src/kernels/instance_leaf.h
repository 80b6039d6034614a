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

/// The inverse of the affine transform (row-major 3x4) `a`.
inline void invertAffine(const double* a, double* inverse) {
    const double c00 = a[5] * a[10] - a[6] * a[9], c01 = a[6] * a[8] - a[4] * a[10], c02 = a[4] * a[9] - a[5] * a[8];
    const double invDet = 1.0 / (a[0] * c00 + a[1] * c01 + a[2] * c02);
    const double r[9] = {c00 * invDet, (a[2] * a[9] - a[1] * a[10]) * invDet, (a[1] * a[6] - a[2] * a[5]) * invDet,
                         c01 * invDet, (a[0] * a[10] - a[2] * a[8]) * invDet, (a[2] * a[4] - a[0] * a[6]) * invDet,
                         c02 * invDet, (a[1] * a[8] - a[0] * a[9]) * invDet, (a[0] * a[5] - a[1] * a[4]) * invDet};
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) inverse[4 * row + column] = r[3 * row + column];
        inverse[4 * row + 3] = -(r[3 * row] * a[3] + r[3 * row + 1] * a[7] + r[3 * row + 2] * a[11]);
    }
}

/// The ray in the instance's object space (at the ray's time, if the instance moves).
inline Ray objectRay(const InstanceTable& table, const InstanceRef& instance, const Ray& ray) {
    double moving[12];
    const double* m = instance.objectFromWorld;
    if (instance.motion != kInvalidId) {
        const InstanceMotion& motion = table.motions[instance.motion];
        double at[12];
        const double time = ray.time;
        for (int i = 0; i < 12; ++i) at[i] = (1.0 - time) * motion.worldFromObject[0][i] + time * motion.worldFromObject[1][i];
        invertAffine(at, moving);
        m = moving;
    }
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
    const Ray local = objectRay(table, instance, ray);
    const SceneView<N>& mesh = table.meshes<N>()[instance.mesh];
    Hit inner;
    inner.t = hit.t;
    const bool occluded =
        traceSingle<N, kNodeSimdWidth<N>, kBlockSize, AnyHit, SceneLeafIntersector<N>>(mesh, local, inner, cost);
    if constexpr (AnyHit) return occluded;
    if (inner.valid()) {
        const uint32_t prim = instance.firstPrim + inner.primId;
        if (isCloser(inner.t, table.geomId, prim, hit)) hit = {inner.t, inner.u, inner.v, prim, table.geomId};
    }
    return false;
}

} // namespace WIDERAY_ISA
} // namespace wideray
