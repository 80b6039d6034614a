#include "geometry/geometry_registry.h"

#include <algorithm>

#include "geometry/analytic_geometry.h"
#include "geometry/csg_geometry.h"
#include "geometry/heightfield_geometry.h"
#include "geometry/instance_geometry.h"
#include "geometry/sphere_geometry.h"
#include "geometry/triangle_geometry.h"

namespace wideray {
namespace {

std::unique_ptr<Geometry> makeTriangles(const SceneDescription& scene, const std::vector<bool>& twoLevel) {
    return std::make_unique<TriangleGeometry>(scene, twoLevel);
}

std::unique_ptr<Geometry> makeSpheres(const SceneDescription& scene, const std::vector<bool>&) {
    if (scene.spheres.empty()) return nullptr;
    return std::make_unique<SphereGeometry>(scene.spheres);
}

std::unique_ptr<Geometry> makeAnalytics(const SceneDescription& scene, const std::vector<bool>&) {
    if (scene.analytics.empty()) return nullptr;
    return std::make_unique<AnalyticGeometry>(scene.analytics);
}

std::unique_ptr<Geometry> makeHeightFields(const SceneDescription& scene, const std::vector<bool>&) {
    if (scene.heightFields.empty()) return nullptr;
    return std::make_unique<HeightFieldGeometry>(scene.heightFields);
}

std::unique_ptr<Geometry> makeCsgs(const SceneDescription& scene, const std::vector<bool>&) {
    if (scene.csgs.empty()) return nullptr;
    return std::make_unique<CsgGeometry>(scene.csgs, scene.meshes);
}

std::unique_ptr<Geometry> makeInstances(const SceneDescription& scene, const std::vector<bool>& twoLevel) {
    if (std::find(twoLevel.begin(), twoLevel.end(), true) == twoLevel.end()) return nullptr;
    return std::make_unique<InstanceGeometry>(scene, twoLevel);
}

constexpr GeometryKind kKinds[] = {
    {"triangles", &makeTriangles},
    {"spheres", &makeSpheres},
    {"analytic", &makeAnalytics},
    {"heightfields", &makeHeightFields},
    {"csg", &makeCsgs},
    {"instances", &makeInstances},
};

} // namespace

std::span<const GeometryKind> geometryKinds() { return kKinds; }

} // namespace wideray
