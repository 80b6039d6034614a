#include "backends/embree_user_geometry.h"

#include <limits>

#include "kernels/hit_order.h"

namespace wideray {
namespace {

const UserGeometry& geometryOf(void* userPtr) { return *static_cast<const UserGeometry*>(userPtr); }

Ray rayOf(RTCRayN* rays, unsigned n, unsigned i) {
    return {RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i),
            RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i),
            RTCRayN_tnear(rays, n, i), RTCRayN_tfar(rays, n, i), RTCRayN_time(rays, n, i)};
}

void bounds(const RTCBoundsFunctionArguments* args) {
    Bounds3f b = geometryOf(args->geometryUserPtr).primitiveBounds(args->primID);
    RTCBounds& out = *args->bounds_o;
    out.lower_x = b.lower.x, out.lower_y = b.lower.y, out.lower_z = b.lower.z;
    out.upper_x = b.upper.x, out.upper_y = b.upper.y, out.upper_z = b.upper.z;
}

void intersect(const RTCIntersectFunctionNArguments* args) {
    const UserGeometry& geometry = geometryOf(args->geometryUserPtr);
    const unsigned n = args->N;
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
    for (unsigned i = 0; i < n; ++i) {
        if (!args->valid[i]) continue;
        Ray ray = rayOf(rays, n, i);
        // A hit inside an instance compares by the instance's id, which follows all of ours as our
        // instance geometry follows the others.
        const unsigned instance = RTCHitN_instID(hits, n, i, 0);
        Hit current{ray.tfar, 0, 0, RTCHitN_primID(hits, n, i),
                    instance != RTC_INVALID_GEOMETRY_ID ? instance : RTCHitN_geomID(hits, n, i)};
        float t = 0, u = 0, v = 0;
        if (!geometry.intersect(ray, args->primID, ray.tfar, t, u, v) ||
            !isCloser(t, args->geomID, args->primID, current))
            continue;
        RTCRayN_tfar(rays, n, i) = t;
        RTCHitN_u(hits, n, i) = u;
        RTCHitN_v(hits, n, i) = v;
        RTCHitN_Ng_x(hits, n, i) = RTCHitN_Ng_y(hits, n, i) = RTCHitN_Ng_z(hits, n, i) = 0.0f;
        RTCHitN_primID(hits, n, i) = args->primID;
        RTCHitN_geomID(hits, n, i) = args->geomID;
        RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
    }
}

void occluded(const RTCOccludedFunctionNArguments* args) {
    const UserGeometry& geometry = geometryOf(args->geometryUserPtr);
    const unsigned n = args->N;
    for (unsigned i = 0; i < n; ++i) {
        if (!args->valid[i]) continue;
        Ray ray = rayOf(args->ray, n, i);
        float t = 0, u = 0, v = 0;
        if (geometry.intersect(ray, args->primID, ray.tfar, t, u, v))
            RTCRayN_tfar(args->ray, n, i) = -std::numeric_limits<float>::infinity();
    }
}

} // namespace

void attachUserGeometry(RTCDevice device, RTCScene scene, const UserGeometry& geometry, uint32_t geomId) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, geometry.primitiveCount());
    rtcSetGeometryUserData(g, const_cast<UserGeometry*>(&geometry));
    rtcSetGeometryBoundsFunction(g, bounds, nullptr);
    rtcSetGeometryIntersectFunction(g, intersect);
    rtcSetGeometryOccludedFunction(g, occluded);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, geomId);
    rtcReleaseGeometry(g);
}

} // namespace wideray
