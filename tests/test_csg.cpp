// Constructive solid geometry: the truth table of every operation on two overlapping spheres along
// known rays, nested trees, closed meshes as solids (rays through their edges and vertices), a die
// against an independent point-membership oracle, materials and normals of the surfaces, shadow rays
// through a hole, refraction through a CSG solid, every backend and structure, keys and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "backends/backend_registry.h"
#include "geometry/csg_geometry.h"
#include "geometry/scene_geometry.h"
#include "io/scene_parser.h"
#include "render/image_difference.h"
#include "render_helpers.h"
#include "backend_trace.h"
#include "scene_errors.h"

namespace wideray {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Ray ray(glm::vec3 o, glm::vec3 d, float tnear = 0.0f) { return {o.x, o.y, o.z, d.x, d.y, d.z, tnear, kInf}; }

/// A scene of the given objects (JSON) with materials "a", "b" and "c".
SceneDescription csgScene(const std::string& objects) {
    return parseScene(R"({"lights": [{"type": "point", "position": [0, 5, 0]}],
        "materials": {"a": {"type": "diffuse"}, "b": {"type": "diffuse"}, "c": {"type": "diffuse"}},
        "objects": [)" + objects + "]}", "csg.json");
}

/// Two unit spheres overlapping on the x axis: A over [-1.5, 0.5], B over [-0.5, 1.5].
std::string twoSpheres(const std::string& operation) {
    return R"({"type": "csg", "operation": ")" + operation + R"(", "operands": [
        {"type": "sphere", "center": [-0.5, 0, 0], "radius": 1, "material": "a"},
        {"type": "sphere", "center": [0.5, 0, 0], "radius": 1, "material": "b"}]})";
}

struct Surface {
    float t;
    uint32_t material;
    bool facesRay;  ///< the geometric normal points against the ray: the ray enters the object
};

/// Every surface of the scene's first CSG object along the ray, in order.
std::vector<Surface> surfaces(const SceneDescription& scene, Ray r) {
    const CsgGeometry geometry(scene.csgs, scene.meshes);
    std::vector<Surface> out;
    float t, u, v;
    while (out.size() < 64 && geometry.intersect(r, 0, r.tfar, t, u, v)) {
        const SurfacePoint sp = geometry.surface(r, {t, u, v, 0, 1});
        out.push_back({t, sp.material, glm::dot(sp.geometricNormal, glm::vec3(r.dx, r.dy, r.dz)) < 0.0f});
        r.tnear = std::nextafter(t, kInf);
    }
    return out;
}

void expectSurfaces(const SceneDescription& scene, const Ray& r, const std::vector<Surface>& expected, const std::string& what) {
    const std::vector<Surface> found = surfaces(scene, r);
    ASSERT_EQ(found.size(), expected.size()) << what;
    for (size_t k = 0; k < found.size(); ++k) {
        EXPECT_NEAR(found[k].t, expected[k].t, 1e-5f) << what << " surface " << k;
        EXPECT_EQ(found[k].material, expected[k].material) << what << " surface " << k;
        EXPECT_EQ(found[k].facesRay, expected[k].facesRay) << what << " surface " << k;
    }
}

TEST(Csg, TruthTablesOfTwoSpheres) {
    // Materials: a = 0, b = 1. Along +x from x = -5: A from t 3.5 to 5.5, B from 4.5 to 6.5.
    const Ray along = ray({-5, 0, 0}, {1, 0, 0});
    expectSurfaces(csgScene(twoSpheres("union")), along, {{3.5f, 0, true}, {6.5f, 1, false}}, "union");
    expectSurfaces(csgScene(twoSpheres("intersection")), along, {{4.5f, 1, true}, {5.5f, 0, false}}, "intersection");
    expectSurfaces(csgScene(twoSpheres("difference")), along, {{3.5f, 0, true}, {4.5f, 1, false}}, "difference");
    expectSurfaces(csgScene(twoSpheres("xor")), along,
                   {{3.5f, 0, true}, {4.5f, 1, false}, {5.5f, 0, true}, {6.5f, 1, false}}, "xor");
    // Backwards along -x: the difference A - B is met at B's surface first, its normal turned to the ray.
    const Ray back = ray({5, 0, 0}, {-1, 0, 0});
    expectSurfaces(csgScene(twoSpheres("difference")), back, {{5.5f, 1, true}, {6.5f, 0, false}}, "difference back");
    // Beside the overlap (x = -1.2, through A only): union and difference see A, intersection nothing.
    const Ray beside = ray({-1.2f, 5, 0}, {0, -1, 0});
    const float half = std::sqrt(1.0f - 0.7f * 0.7f);
    expectSurfaces(csgScene(twoSpheres("intersection")), beside, {}, "intersection beside");
    expectSurfaces(csgScene(twoSpheres("difference")), beside, {{5 - half, 0, true}, {5 + half, 0, false}}, "difference beside");
    // From inside the overlap (the origin): union is left through B, intersection through A.
    const Ray inside = ray({0, 0, 0}, {1, 0, 0});
    expectSurfaces(csgScene(twoSpheres("union")), inside, {{1.5f, 1, false}}, "union from inside");
    expectSurfaces(csgScene(twoSpheres("intersection")), inside, {{0.5f, 0, false}}, "intersection from inside");
    expectSurfaces(csgScene(twoSpheres("xor")), inside, {{0.5f, 0, true}, {1.5f, 1, false}}, "xor from inside");
}

TEST(Csg, NestedTreesAndInheritedMaterials) {
    // (A u B) - C, C a sphere of material c around the origin; the tree's "material" is a default that
    // the operands' own materials override.
    const SceneDescription scene = csgScene(R"({"type": "csg", "operation": "difference", "material": "c", "operands": [
        )" + twoSpheres("union") + R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 0.25}]})");
    ASSERT_EQ(scene.csgs.size(), 1u);
    ASSERT_EQ(scene.csgs[0].nodes.size(), 5u);
    expectSurfaces(scene, ray({-5, 0, 0}, {1, 0, 0}), {{3.5f, 0, true}, {4.75f, 2, false}, {5.25f, 2, true}, {6.5f, 1, false}},
                   "(A u B) - C");
    // Four levels: ((A n B) u C) xor D, with D a big ellipsoid: inside D but outside the rest.
    const SceneDescription deep = csgScene(R"({"type": "csg", "operation": "xor", "operands": [
        {"type": "csg", "operation": "union", "operands": [)" + twoSpheres("intersection") + R"(,
            {"type": "sphere", "center": [0, 0, 0], "radius": 0.1, "material": "c"}]},
        {"type": "ellipsoid", "radii": [3, 3, 3], "material": "c"}]})");
    expectSurfaces(deep, ray({-5, 0, 0}, {1, 0, 0}), {{2, 2, true}, {4.5f, 1, false}, {5.5f, 0, true}, {8, 2, false}}, "deep");
}

constexpr const char* kCube = R"({"type": "generated", "shape": "cube", "material": "a"})";

TEST(Csg, ClosedMeshesCountEdgesAndVerticesOnce) {
    // The cube intersected with a sphere that contains it is the cube. Rays through the middles of its
    // faces pass along the diagonals that split them into two triangles, rays along its edges and
    // through its corners touch three or six triangles at one point.
    const SceneDescription scene = csgScene(std::string(R"({"type": "csg", "operation": "intersection", "operands": [)") + kCube +
                                 R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "b"}]})");
    ASSERT_EQ(scene.csgs[0].meshes.size(), 1u);
    for (int axis = 0; axis < 3; ++axis) {
        glm::vec3 o(0.0f), d(0.0f);
        o[axis] = -5.0f;
        d[axis] = 1.0f;
        expectSurfaces(scene, ray(o, d), {{4, 0, true}, {6, 0, false}}, "through face middles, axis " + std::to_string(axis));
        expectSurfaces(scene, ray(-o, -d), {{4, 0, true}, {6, 0, false}}, "backwards, axis " + std::to_string(axis));
    }
    const glm::vec3 diagonal = glm::normalize(glm::vec3(1, 1, 1));
    expectSurfaces(scene, ray(glm::vec3(-5.0f), diagonal), {{4 * std::sqrt(3.0f), 0, true}, {6 * std::sqrt(3.0f), 0, false}},
                   "corner to corner");
    // Along the edge x = y = 1 the line only touches the solid: it never enters it.
    expectSurfaces(scene, ray({1, 1, -5}, {0, 0, 1}), {}, "along an edge");
    expectSurfaces(scene, ray({-5, 0.3f, 0.3f}, {1, 0, 0}), {{4, 0, true}, {6, 0, false}}, "across the diagonal");
}

/// Whether the die of kDie holds a point: a cube intersected with a sphere, minus two spheres.
bool inDie(const glm::vec3& p) {
    const bool cube = std::fabs(p.x) <= 1 && std::fabs(p.y) <= 1 && std::fabs(p.z) <= 1;
    const bool rounded = glm::length(p) <= 1.38f;
    const bool pip1 = glm::length(p - glm::vec3(0, 0, 1.08f)) <= 0.3f, pip2 = glm::length(p - glm::vec3(1.08f, 0.5f, 0.5f)) <= 0.3f;
    return cube && rounded && !pip1 && !pip2;
}

constexpr const char* kDie = R"({"type": "csg", "operation": "difference", "material": "b", "operands": [
    {"type": "csg", "operation": "intersection", "operands": [
        {"type": "generated", "shape": "cube", "material": "a"},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1.38, "material": "a"}]},
    {"type": "sphere", "center": [0, 0, 1.08], "radius": 0.3},
    {"type": "ellipsoid", "center": [1.08, 0.5, 0.5], "radii": [0.3, 0.3, 0.3]}]})";

TEST(Csg, DieAgainstPointMembership) {
    // The first surface along random rays from outside against a search of inDie: fine steps, then
    // bisection of the first step where membership changes.
    const SceneDescription scene = csgScene(kDie);
    const CsgGeometry geometry(scene.csgs, scene.meshes);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    int hits = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const glm::vec3 origin = 4.0f * glm::normalize(glm::vec3(uniform(rng), uniform(rng), uniform(rng)));
        const glm::vec3 target(0.6f * uniform(rng), 0.6f * uniform(rng), 0.6f * uniform(rng) + 0.4f);
        const glm::vec3 d = glm::normalize(target - origin);
        float expected = kInf;
        const float step = 1e-3f;
        for (float t = 0.0f; t < 8.0f; t += step)
            if (inDie(origin + (t + step) * d)) {
                float lo = t, hi = t + step;
                for (int k = 0; k < 30; ++k) (inDie(origin + 0.5f * (lo + hi) * d) ? hi : lo) = 0.5f * (lo + hi);
                expected = hi;
                break;
            }
        float t, u, v;
        const bool hit = geometry.intersect(ray(origin, d), 0, kInf, t, u, v);
        ASSERT_EQ(hit, expected != kInf) << "ray " << i << " expected t " << expected;
        if (!hit) continue;
        ++hits;
        if (t < expected - 2e-5f) {
            // A sliver thinner than the search's step (the ray entering a face at a pip's rim) is
            // checked finely: the die holds points just after t.
            bool sliver = false;
            for (int k = 1; k <= 2000 && !sliver; ++k) sliver = inDie(origin + (t + 5e-7f * float(k)) * d);
            EXPECT_TRUE(sliver) << "ray " << i << ": t " << t << " expected " << expected;
            expected = t;
        }
        EXPECT_NEAR(t, expected, 2e-5f) << "ray " << i;
        // The pips are carved: their surfaces have the pips' material (b) and face out of the die.
        const SurfacePoint sp = geometry.surface(ray(origin, d), {t, u, v, 0, 1});
        EXPECT_LT(glm::dot(sp.geometricNormal, d), 0.0f) << "ray " << i;
        const glm::vec3 p = origin + t * d;
        const bool onPip = std::fabs(glm::length(p - glm::vec3(0, 0, 1.08f)) - 0.3f) < 1e-4f ||
                           std::fabs(glm::length(p - glm::vec3(1.08f, 0.5f, 0.5f)) - 0.3f) < 1e-4f;
        EXPECT_EQ(sp.material, onPip ? 1u : 0u) << "ray " << i;
        checked += onPip;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(checked, 20);
}

TEST(Csg, ShadowRaysPassThroughAHole) {
    // A cube with a cylinder drilled along z: rays through the hole are not occluded, the others are,
    // through every backend.
    const SceneDescription scene = csgScene(std::string(R"({"type": "csg", "operation": "difference", "operands": [)") + kCube +
                                 R"(, {"type": "cylinder", "radius": 0.5, "height": 3, "transform": {"rotate": {"axis": [1, 0, 0], "degrees": 90}}}]})");
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    std::vector<Ray> rays;
    for (int i = 0; i < 41; ++i) {
        Ray r = ray({-1.0f + 0.05f * float(i), 0.0f, -5.0f}, {0, 0, 1});
        r.tfar = 10.0f;
        rays.push_back(r);
    }
    for (const std::string backend : {"wideray", "embree"}) {
        std::vector<uint8_t> occluded(rays.size());
        findBackend(backend).build(geometry, {})->tracer({})->occluded(rays, occluded, Coherence::Incoherent);
        for (size_t i = 0; i < rays.size(); ++i) {
            const float x = rays[i].ox;
            if (std::fabs(std::fabs(x) - 0.5f) < 1e-3f || std::fabs(std::fabs(x) - 1.0f) < 1e-3f) continue;  // on a wall
            EXPECT_EQ(occluded[i] != 0, std::fabs(x) > 0.5f && std::fabs(x) < 1.0f) << backend << " x " << x;
        }
    }
}

/// A scene of a glass object (JSON) over a checkered floor, lit by a point light.
SceneDescription glassScene(const std::string& object) {
    return parseScene(R"({"camera": {"position": [0.5, 1, 5], "look_at": [0, 0, 0]},
        "image": {"width": 64, "height": 48}, "background": [0.2, 0.3, 0.5],
        "lights": [{"type": "point", "position": [2, 4, 3], "intensity": 20}],
        "materials": {"glass": {"type": "dielectric", "ior": 1.5, "absorption": [0.3, 0.1, 0.05]},
                      "floor": {"type": "diffuse", "color": {"type": "checker", "scale": 4}}},
        "objects": [{"type": "generated", "shape": "quad", "material": "floor", "transform": {"scale": 5, "translate": [0, -1, 0]}},
                    )" + object + "]}", "glass.json");
}

void expectSameImage(const SceneDescription& a, const SceneDescription& b, const std::string& what) {
    const ImageDifference diff = compareImages(renderWithReference(a, 2, {}), renderWithReference(b, 2, {}), 0.01f);
    EXPECT_LT(diff.meanAbsolute, 2e-4) << what;
    EXPECT_LT(diff.pixelsOver, 8u) << what;
}

TEST(Csg, RefractionThroughACsgSolidEqualsThePlainSolid) {
    // A glass ball, and the same ball as the intersection with a larger sphere and as the union with
    // a smaller one inside it: rays enter, refract, bounce inside and leave the same way.
    const std::string ball = R"({"type": "ellipsoid", "radii": [1, 1, 1], "material": "glass"})";
    expectSameImage(glassScene(ball),
                    glassScene(R"({"type": "csg", "operation": "intersection", "operands": [)" + ball +
                               R"(, {"type": "sphere", "center": [0, 0.5, 0], "radius": 3, "material": "floor"}]})"),
                    "ball as an intersection");
    expectSameImage(glassScene(ball),
                    glassScene(R"({"type": "csg", "operation": "union", "operands": [)" + ball +
                               R"(, {"type": "sphere", "center": [0.2, 0, 0], "radius": 0.5, "material": "floor"}]})"),
                    "ball as a union");
    // A glass slab whose front face is carved by a difference: the face is the cutter's, turned to
    // face out of the glass, so light refracts into the slab there as through the plain slab's face.
    const std::string slab = R"({"type": "generated", "shape": "cube", "material": "glass",
        "transform": {"scale": [1, 0.8, 0.15], "rotate": {"axis": [0, 1, 0], "degrees": 20}}})";
    expectSameImage(glassScene(slab),
                    glassScene(R"({"type": "csg", "operation": "difference", "material": "glass",
                        "transform": {"rotate": {"axis": [0, 1, 0], "degrees": 20}}, "operands": [
                        {"type": "generated", "shape": "cube", "transform": {"scale": [1, 0.8, 1], "translate": [0, 0, 0.85]}},
                        {"type": "generated", "shape": "cube", "transform": {"scale": 2, "translate": [0, 0, 2.15]}}]})"),
                    "slab carved by a difference");
}

TEST(Csg, EveryBackendAndStructureFindsTheSameHits) {
    const SceneDescription scene = csgScene(std::string(kDie) + "," + twoSpheres("xor").replace(0, 1, R"({"transform": {"translate": [3, 0, 0]}, )"));
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const std::vector<Ray> rays = testing::rayFan({1, 1.5f, 7}, {-2, -2}, {5, 2}, 60, 40);
    const std::vector<Hit> expected = testing::traceThrough(geometry, "wideray", "bvh8", rays);
    size_t csgHits = 0;
    for (const Hit& h : expected) csgHits += h.valid();
    EXPECT_GT(csgHits, rays.size() / 4);
    for (const auto& [backend, accel] : std::vector<std::pair<std::string, std::string>>{
             {"embree", ""}, {"wideray", "bvh4"}, {"wideray", "kdtree"}, {"wideray", "rgrid"}}) {
        const std::vector<Hit> hits = testing::traceThrough(geometry, backend, accel, rays);
        size_t mismatches = 0;
        for (size_t i = 0; i < rays.size(); ++i)
            mismatches += hits[i].valid() != expected[i].valid() ||
                          (hits[i].valid() && (hits[i].primId != expected[i].primId || hits[i].t != expected[i].t));
        EXPECT_EQ(mismatches, 0u) << backend << " " << accel;
    }
}

TEST(Csg, SceneKeysRoundTripAndBadValuesNameTheirKey) {
    const SceneDescription first = csgScene(kDie);
    const SceneDescription second = parseScene(writeScene(first), "written.json");
    ASSERT_EQ(second.csgs.size(), 1u);
    EXPECT_EQ(second.csgs[0].nodes.size(), first.csgs[0].nodes.size());
    EXPECT_EQ(second.csgs[0].analytics.size(), first.csgs[0].analytics.size());
    ASSERT_EQ(second.csgs[0].meshes.size(), 1u);
    EXPECT_EQ(second.csgs[0].meshes[0].transform, first.csgs[0].meshes[0].transform);
    for (const Ray& r : {ray({-5, 0.2f, 0.1f}, {1, 0, 0}), ray({0.1f, 0.05f, 5}, {0, 0, -1}), ray({5, 0.5f, 0.5f}, {-1, 0, 0})}) {
        const std::vector<Surface> a = surfaces(first, r), b = surfaces(second, r);
        ASSERT_EQ(a.size(), b.size());
        for (size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].t, b[k].t);
    }
    const auto error = testing::objectError;
    const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1})";
    EXPECT_NE(error(R"({"type": "csg", "operation": "unoin", "operands": [)" + sphere + "," + sphere + "]}").find("objects[0].operation"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "unoin", "operands": [)" + sphere + "," + sphere + "]}").find("union"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [)" + sphere + "]}").find("objects[0].operands"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union"})").find("operands"), std::string::npos);
    const std::string open = R"({"type": "generated", "shape": "quad"})";
    const std::string openError = error(R"({"type": "csg", "operation": "union", "operands": [)" + sphere + "," + open + "]}");
    EXPECT_NE(openError.find("objects[0].operands[1]"), std::string::npos) << openError;
    EXPECT_NE(openError.find("not closed"), std::string::npos) << openError;
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [{"type": "cylinder", "capped": false}, )" + sphere + "]}")
                  .find("objects[0].operands[0].capped"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [{"type": "quadric", "coefficients": [1,1,1,0,0,0,0,0,0,-1]}, )" +
                    sphere + "]}")
                  .find("objects[0].operands[0].type"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [{"type": "heightfield"}, )" + sphere + "]}")
                  .find("cannot be a CSG operand"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}, )" +
                    sphere + "]}")
                  .find("objects[0].operands[0].radius"),
              std::string::npos);
}

} // namespace
} // namespace wideray
