#include "geometry/geometry_registry.h"

#include "geometry/analytic_geometry.h"
#include "geometry/csg_geometry.h"
#include "geometry/heightfield_geometry.h"
#include "geometry/sphere_geometry.h"
#include "geometry/triangle_geometry.h"

namespace wideray {
namespace {

std::unique_ptr<Geometry> makeTriangles(const Scene& scene) { return std::make_unique<TriangleGeometry>(scene); }

std::unique_ptr<Geometry> makeSpheres(const Scene& scene) {
    if (scene.spheres.empty()) return nullptr;
    return std::make_unique<SphereGeometry>(scene.spheres);
}

std::unique_ptr<Geometry> makeAnalytics(const Scene& scene) {
    if (scene.analytics.empty()) return nullptr;
    return std::make_unique<AnalyticGeometry>(scene.analytics);
}

std::unique_ptr<Geometry> makeHeightFields(const Scene& scene) {
    if (scene.heightFields.empty()) return nullptr;
    return std::make_unique<HeightFieldGeometry>(scene.heightFields);
}

std::unique_ptr<Geometry> makeCsgs(const Scene& scene) {
    if (scene.csgs.empty()) return nullptr;
    return std::make_unique<CsgGeometry>(scene.csgs, scene.meshes);
}

constexpr GeometryKind kKinds[] = {
    {"triangles", &makeTriangles},
    {"spheres", &makeSpheres},
    {"analytic", &makeAnalytics},
    {"heightfields", &makeHeightFields},
    {"csg", &makeCsgs},
};

} // namespace

std::span<const GeometryKind> geometryKinds() { return kKinds; }

} // namespace wideray
