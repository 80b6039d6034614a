// The analytic primitives (ellipsoid, cylinder, cone, paraboloid, hyperboloids, general quadric,
// torus): hits, t and normals against closed forms and against a root search of their own implicit
// functions in long double, rays from inside, along axes and grazing; transforms; every backend
// and structure finds the same hits; scene keys, their errors and the round trip.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "backends/accel_registry.h"
#include "backends/backend_registry.h"
#include "core/error.h"
#include "geometry/analytic_geometry.h"
#include "geometry/polynomial_roots.h"
#include "io/scene_parser.h"
#include "backend_trace.h"
#include "scene_errors.h"
#include "geometry/scene_geometry.h"

namespace wideray {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Ray ray(glm::vec3 o, glm::vec3 d, float tnear = 0.0f) { return {o.x, o.y, o.z, d.x, d.y, d.z, tnear, kInf}; }

AnalyticObject object(AnalyticShape shape, glm::mat4 transform = glm::mat4(1.0f)) {
    AnalyticObject o;
    o.shape = shape;
    o.transform = transform;
    return o;
}

/// The closest hit of one object, and its surface normal (a miss has t = inf).
struct Result {
    float t = kInf;
    glm::vec3 normal{0.0f};
};

Result trace(const AnalyticObject& o, const Ray& r) {
    AnalyticGeometry g({o});
    Result result;
    float t, u, v;
    if (!g.intersect(r, 0, r.tfar, t, u, v)) return result;
    Hit hit{t, u, v, 0, 0};
    result.t = t;
    result.normal = g.surface(r, hit).geometricNormal;
    return result;
}

void expectHit(const AnalyticObject& o, const Ray& r, float t, glm::vec3 normal, const char* what) {
    const Result h = trace(o, r);
    EXPECT_NEAR(h.t, t, 1e-5f * std::max(1.0f, t)) << what;
    EXPECT_LT(glm::length(h.normal - normal), 1e-4f) << what << ": normal " << h.normal.x << " " << h.normal.y << " "
                                                      << h.normal.z;
}

TEST(Analytic, QuadricsAgainstClosedForms) {
    using S = AnalyticShape;
    const glm::vec3 x(1, 0, 0), y(0, 1, 0);
    // Along +x at y = 0 from x = -5: the radius there is 1, 1, 1/2, sqrt(1/2), sqrt(1/2).
    expectHit(object(S::Ellipsoid), ray({-5, 0, 0}, x), 4.0f, -x, "sphere");
    expectHit(object(S::Cylinder), ray({-5, 0, 0}, x), 4.0f, -x, "cylinder side");
    expectHit(object(S::Cone), ray({-5, 0, 0}, x), 4.5f, glm::normalize(glm::vec3(-1, 0.5f, 0)), "cone side");
    expectHit(object(S::Paraboloid), ray({-5, 0, 0}, x), 5.0f - std::sqrt(0.5f), glm::normalize(glm::vec3(-2 * std::sqrt(0.5f), -0.5f, 0)),
              "paraboloid side");
    expectHit(object(S::Hyperboloid), ray({-5, 0, 0}, x), 5.0f - std::sqrt(0.5f), -x, "hyperboloid waist");
    // Caps at y = -1 and 1, along the axis and off it.
    expectHit(object(S::Cylinder), ray({0.5f, -5, 0}, y), 4.0f, -y, "cylinder cap");
    expectHit(object(S::Cone), ray({0.5f, -5, 0}, y), 4.0f, -y, "cone base");
    expectHit(object(S::Paraboloid), ray({0.2f, 5, 0.3f}, -y), 4.0f, y, "paraboloid cap");
    expectHit(object(S::Paraboloid), ray({0, -5, 0}, y), 4.0f, -y, "paraboloid vertex");
    // The two sheets: vertices at y = +-1/2, nothing between them.
    expectHit(object(S::TwoSheetHyperboloid), ray({0, 5, 0}, -y), 4.0f, y, "two sheets, cap");
    expectHit(object(S::TwoSheetHyperboloid), ray({0, 0, 0}, y), 0.5f, -y, "two sheets, vertex from between");
    EXPECT_EQ(trace(object(S::TwoSheetHyperboloid), ray({-5, 0, 0}, x)).t, kInf) << "between the sheets";
    // From inside: the exit.
    expectHit(object(S::Ellipsoid), ray({0, 0, 0}, x), 1.0f, x, "sphere from inside");
    expectHit(object(S::Cylinder), ray({0, 0, 0}, y), 1.0f, y, "cylinder cap from inside");
    // Open ends: a ray along the axis of an uncapped cylinder passes through.
    AnalyticObject open = object(S::Cylinder);
    open.capped = false;
    EXPECT_EQ(trace(open, ray({0.5f, -5, 0}, y)).t, kInf);
    expectHit(open, ray({0, 0, 0}, x), 1.0f, x, "open cylinder from inside");
    // A general quadric: the sphere of radius 1/2 by its coefficients; clipped to the unit cube.
    AnalyticObject q = object(S::Quadric);
    q.coefficients = {1, 1, 1, 0, 0, 0, 0, 0, 0, -0.25f};
    expectHit(q, ray({-5, 0, 0}, x), 4.5f, -x, "general quadric");
    q.coefficients = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0};  // the plane y = 0, within the cube
    expectHit(q, ray({0.3f, 5, 0.2f}, -y), 5.0f, y, "quadric plane");
    EXPECT_EQ(trace(q, ray({3, 5, 0}, -y)).t, kInf) << "outside the cube";
}

TEST(Analytic, TransformsMoveRaysIntoObjectSpace) {
    using S = AnalyticShape;
    // An ellipsoid is a scaled sphere: radii 2, 1, 1/2.
    const AnalyticObject e = object(S::Ellipsoid, glm::scale(glm::mat4(1.0f), {2, 1, 0.5f}));
    expectHit(e, ray({-10, 0, 0}, {1, 0, 0}), 8.0f, {-1, 0, 0}, "ellipsoid x");
    expectHit(e, ray({0, 0, 10}, {0, 0, -1}), 9.5f, {0, 0, 1}, "ellipsoid z");
    // Normals by the inverse transpose: at (sqrt 2, sqrt(1/2), 0) on x^2/4 + y^2 = 1 the normal is
    // along (x / 4, y) = (sqrt 2 / 4, sqrt(1/2)).
    const float px = std::sqrt(2.0f), py = std::sqrt(0.5f);
    expectHit(e, ray({px, 5, 0}, {0, -1, 0}), 5.0f - py, glm::normalize(glm::vec3(px / 4, py, 0)), "ellipsoid normal");
    // A cylinder turned onto the x axis and moved: its cap faces +x at x = 3 + 1.
    const glm::mat4 m = glm::translate(glm::mat4(1.0f), {3, 0, 0}) *
                        glm::rotate(glm::mat4(1.0f), -float(M_PI) / 2, glm::vec3(0, 0, 1));
    expectHit(object(S::Cylinder, m), ray({10, 0.3f, 0}, {-1, 0, 0}), 6.0f, {1, 0, 0}, "turned cylinder cap");
    expectHit(object(S::Cylinder, m), ray({3, 5, 0}, {0, -1, 0}), 4.0f, {0, 1, 0}, "turned cylinder side");
    // A direction of any length: t is in its units.
    expectHit(object(S::Ellipsoid), ray({-5, 0, 0}, {4, 0, 0}), 1.0f, {-1, 0, 0}, "long direction");
}

/// The torus' implicit function along a ray, in long double.
long double torusAt(const Ray& r, long double t, long double R, long double rr) {
    const long double x = r.ox + t * r.dx, y = r.oy + t * r.dy, z = r.oz + t * r.dz;
    const long double q = x * x + y * y + z * z + R * R - rr * rr;
    return q * q - 4 * R * R * (x * x + z * z);
}

/// The first sign change of f over [0, tmax] by fine sampling (`steps` samples) and bisection in long
/// double: the reference, independent of the solvers; inf where there is none.
template <class F>
long double firstCrossing(F&& f, long double tmax, int steps) {
    long double a = 0, fa = f(0.0L);
    for (int i = 1; i <= steps; ++i) {
        const long double b = tmax * i / steps, fb = f(b);
        if ((fa < 0) != (fb < 0)) {
            long double lo = a, hi = b;
            for (int k = 0; k < 200; ++k) {
                const long double m = 0.5L * (lo + hi);
                if ((f(m) < 0) == (fa < 0)) lo = m;
                else hi = m;
            }
            return 0.5L * (lo + hi);
        }
        a = b;
        fa = fb;
    }
    return INFINITY;
}

TEST(Analytic, TorusAgainstRootSearch) {
    AnalyticObject torus = object(AnalyticShape::Torus);
    torus.majorRadius = 1.0f;
    torus.minorRadius = 0.25f;
    const glm::vec3 x(1, 0, 0), y(0, 1, 0);
    expectHit(torus, ray({-5, 0, 0}, x), 3.75f, -x, "outer equator");
    expectHit(torus, ray({0, 0, 0}, x), 0.75f, -x, "from the hole, the inner equator");
    expectHit(torus, ray({1, -5, 0}, y), 4.75f, -y, "down the tube");
    expectHit(torus, ray({1, 0, 0}, y), 0.25f, y, "from inside the tube");
    EXPECT_EQ(trace(torus, ray({0, -5, 0}, y)).t, kInf) << "through the hole";
    // Grazing the top of the tube from outside, just below and just above it.
    for (float dy : {1e-3f, 1e-5f}) {
        const float h = 0.25f - dy;
        EXPECT_NEAR(trace(torus, ray({-5, h, 0}, x)).t, 5.0f - 1.0f - std::sqrt(0.0625f - h * h), 1e-4f) << "grazing " << dy;
        EXPECT_EQ(trace(torus, ray({-5, 0.25f + dy, 0}, x)).t, kInf) << "above the tube " << dy;
    }
    // Random rays from around and inside the torus against the root search, nearly all of them
    // aimed at the tube (and some of those grazing it).
    uint32_t state = 12345;
    auto unit = [&] { state = state * 1664525u + 1013904223u; return float(state >> 8) / float(1 << 24); };
    size_t hits = 0;
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 o(4 * unit() - 2, 2 * unit() - 1, 4 * unit() - 2);
        const float angle = 6.2831853f * unit();
        const glm::vec3 target(std::cos(angle), 0.3f * (unit() - 0.5f), std::sin(angle));
        const Ray r = ray(o, glm::normalize(target - o));
        const long double expected = firstCrossing([&](long double t) { return torusAt(r, t, 1.0L, 0.25L); }, 10.0L, 200000);
        const float t = trace(torus, r).t;
        if (std::isinf(double(expected))) {
            EXPECT_EQ(t, kInf) << "ray " << i;
            continue;
        }
        ++hits;
        EXPECT_NEAR(double(t), double(expected), 1e-5 * std::max(1.0, double(expected))) << "ray " << i;
    }
    EXPECT_GT(hits, 300u);
}

/// A blob's field minus its threshold along a ray, in long double.
long double blobAt(const AnalyticObject& blob, const Ray& r, long double t) {
    long double f = -blob.threshold;
    for (const BlobBall& b : blob.balls) {
        const long double x = r.ox + t * r.dx - b.center.x, y = r.oy + t * r.dy - b.center.y, z = r.oz + t * r.dz - b.center.z;
        const long double u = 1.0L - (x * x + y * y + z * z) / ((long double)b.radius * b.radius);
        if (u > 0) f += b.strength * u * u * u;
    }
    return f;
}

TEST(Analytic, BlobsAgainstTheirField) {
    // One ball: the surface is the sphere where (1 - r^2)^3 = threshold.
    AnalyticObject one = object(AnalyticShape::Blob);
    one.balls = {{{0, 0, 0}, 1.0f, 1.0f}};
    one.threshold = 0.5f;
    const float radius = std::sqrt(1.0f - std::cbrt(0.5f));
    expectHit(one, ray({-5, 0, 0}, {1, 0, 0}), 5.0f - radius, {-1, 0, 0}, "one ball");
    expectHit(one, ray({0, 0, 0}, {0, 1, 0}), radius, {0, 1, 0}, "one ball from inside");
    // Three balls, one of them carving (negative strength): random rays against the field itself.
    AnalyticObject blob = object(AnalyticShape::Blob);
    blob.balls = {{{-0.5f, 0, 0}, 1.0f, 1.0f}, {{0.5f, 0.1f, 0}, 0.9f, 1.0f}, {{0, 0.6f, 0.3f}, 0.5f, -0.8f}};
    blob.threshold = 0.3f;
    uint32_t state = 777;
    auto unit = [&] { state = state * 1664525u + 1013904223u; return float(state >> 8) / float(1 << 24); };
    size_t hits = 0;
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 o(6 * unit() - 3, 6 * unit() - 3, 6 * unit() - 3);
        const glm::vec3 target(unit() - 0.5f, 0.6f * (unit() - 0.5f), 0.6f * (unit() - 0.5f));
        const Ray r = ray(o, glm::normalize(target - o));
        const long double expected = firstCrossing([&](long double t) { return blobAt(blob, r, t); }, 8.0L, 100000);
        const Result h = trace(blob, r);
        if (std::isinf(double(expected))) {
            EXPECT_EQ(h.t, kInf) << "ray " << i;
            continue;
        }
        ++hits;
        EXPECT_NEAR(double(h.t), double(expected), 1e-5 * std::max(1.0, double(expected))) << "ray " << i;
        // The normal faces the ray's origin side where the ray enters from outside.
        if (blobAt(blob, r, 0) < 0) {
            EXPECT_LT(glm::dot(h.normal, glm::vec3(r.dx, r.dy, r.dz)), 0.0f) << "ray " << i;
        }
    }
    EXPECT_GT(hits, 200u);
}

TEST(Analytic, PolynomialRootsOfKnownPolynomials) {
    double roots[8];
    const double quartic[5] = {24, -50, 35, -10, 1};  // (x-1)(x-2)(x-3)(x-4)
    ASSERT_EQ(polynomialRoots(quartic, 4, 0.0, 10.0, roots), 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(roots[i], i + 1.0, 1e-12);
    EXPECT_EQ(polynomialRoots(quartic, 4, 1.5, 2.5, roots), 1);
    const double close[3] = {1.0 - 1e-12, -2.0, 1.0};  // (x - 1)^2 - 1e-12: roots 1 +- 1e-6
    ASSERT_EQ(polynomialRoots(close, 2, 0.0, 2.0, roots), 2);
    EXPECT_NEAR(roots[0], 1.0 - 1e-6, 1e-10);  // the coefficient 1 - 1e-12 is rounded: 5e-11 in the roots
    EXPECT_NEAR(roots[1], 1.0 + 1e-6, 1e-10);
    const double none[3] = {1.0, 0.0, 1.0};  // x^2 + 1
    EXPECT_EQ(polynomialRoots(none, 2, -10.0, 10.0, roots), 0);
}

/// A scene of every analytic shape; rays at them through every backend and structure.
constexpr const char* kShapesScene = R"({
  "camera": {"position": [0, 2, 9], "look_at": [0, 0, 0]},
  "lights": [{"type": "point", "position": [3, 6, 4]}],
  "materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
  "objects": [
    {"type": "ellipsoid", "radii": [1, 0.6, 0.8], "center": [-3, 0, 0], "material": "white"},
    {"type": "cylinder", "radius": 0.5, "height": 1.5, "transform": {"translate": [-1.5, 0, 0]}},
    {"type": "cone", "radius": 0.6, "height": 1.4, "capped": false},
    {"type": "paraboloid", "transform": {"translate": [1.5, 0, 0], "scale": 0.6}},
    {"type": "hyperboloid", "sheets": 2, "transform": {"translate": [3, 0, 0], "scale": 0.7}},
    {"type": "hyperboloid", "transform": {"translate": [0, 2, 0], "scale": 0.6}},
    {"type": "quadric", "coefficients": [1, 0, 1, 0, 0, 0, 0, -1, 0, 0], "transform": {"translate": [0, -2, 0]}},
    {"type": "torus", "major_radius": 1, "minor_radius": 0.3,
     "transform": {"rotate": {"axis": [1, 0, 0], "degrees": 70}, "translate": [2, 2, 0]}},
    {"type": "blob", "threshold": 0.4, "balls": [{"center": [-0.4, 0, 0], "radius": 0.8},
      {"center": [0.4, 0.2, 0], "radius": 0.7}, {"center": [0, -0.3, 0.2], "radius": 0.4, "strength": -0.5}],
     "transform": {"translate": [-2, 2, 0]}},
    {"type": "generated", "shape": "quad", "transform": {"scale": 6, "translate": [0, -3, 0]}}
  ]
})";

TEST(Analytic, EveryBackendAndStructureFindsTheSameHits) {
    const SceneDescription scene = parseScene(kShapesScene, "shapes.json");
    ASSERT_EQ(scene.analytics.size(), 9u);
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const std::vector<Ray> rays = testing::rayFan({0, 2, 9}, {-5, -3}, {5, 3.5f}, 64, 48);
    const std::vector<Hit> expected = testing::traceThrough(geometry, "wideray", "bvh8", rays);
    size_t analyticHits = 0;
    for (const Hit& h : expected) analyticHits += h.valid() && h.geomId != 0;
    EXPECT_GT(analyticHits, rays.size() / 8);
    for (const auto& [backend, accel] : std::vector<std::pair<std::string, std::string>>{
             {"embree", ""}, {"wideray", "bvh4"}, {"wideray", "kdtree"}, {"wideray", "grid"}}) {
        const std::vector<Hit> hits = testing::traceThrough(geometry, backend, accel, rays);
        size_t mismatches = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            // Embree's own triangle test rounds t differently; the analytic primitives are ours in both.
            const bool ownTriangles = backend == "embree" && expected[i].geomId == 0;
            const float tolerance = ownTriangles ? 1e-5f * expected[i].t : 0.0f;
            const bool differs = hits[i].valid() != expected[i].valid() ||
                                 (hits[i].valid() && (hits[i].geomId != expected[i].geomId ||
                                                      hits[i].primId != expected[i].primId ||
                                                      std::fabs(hits[i].t - expected[i].t) > tolerance));
            if (differs && ++mismatches <= 3)
                ADD_FAILURE() << backend << " " << accel << " ray " << i << ": geom " << hits[i].geomId << " prim "
                              << hits[i].primId << " t " << hits[i].t << " vs " << expected[i].geomId << " "
                              << expected[i].primId << " " << expected[i].t;
        }
        EXPECT_EQ(mismatches, 0u) << backend << " " << accel;
    }
}

TEST(Analytic, SceneKeysRoundTripAndBadValuesNameTheirKey) {
    const SceneDescription first = parseScene(kShapesScene, "shapes.json");
    const SceneDescription second = parseScene(writeScene(first), "written.json");
    ASSERT_EQ(second.analytics.size(), first.analytics.size());
    for (size_t i = 0; i < first.analytics.size(); ++i) {
        EXPECT_EQ(second.analytics[i].shape, first.analytics[i].shape) << i;
        EXPECT_EQ(second.analytics[i].transform, first.analytics[i].transform) << i;
        EXPECT_EQ(second.analytics[i].capped, first.analytics[i].capped) << i;
        EXPECT_EQ(second.analytics[i].coefficients, first.analytics[i].coefficients) << i;
        EXPECT_EQ(second.analytics[i].minorRadius, first.analytics[i].minorRadius) << i;
        EXPECT_EQ(second.analytics[i].balls.size(), first.analytics[i].balls.size()) << i;
    }
    const auto error = testing::objectError;
    EXPECT_NE(error(R"({"type": "quadric", "coefficients": [1, 2]})").find("objects[0].coefficients"), std::string::npos);
    EXPECT_NE(error(R"({"type": "quadric", "coefficients": [0,0,0,0,0,0,0,0,0,0]})").find("not all be zero"), std::string::npos);
    EXPECT_NE(error(R"({"type": "torus", "major_radius": 1, "minor_radius": 2})").find("minor_radius"), std::string::npos);
    EXPECT_NE(error(R"({"type": "hyperboloid", "sheets": 3})").find("objects[0].sheets"), std::string::npos);
    EXPECT_NE(error(R"({"type": "cylinder", "radius": -1})").find("objects[0].radius"), std::string::npos);
    EXPECT_NE(error(R"({"type": "cone", "sheets": 2})").find("sheets"), std::string::npos);
    EXPECT_NE(error(R"({"type": "ellipsoid", "radii": [1, 0, 1]})").find("objects[0].radii"), std::string::npos);
    EXPECT_NE(error(R"({"type": "cylindre"})").find("cylinder"), std::string::npos);
    EXPECT_NE(error(R"({"type": "blob", "balls": []})").find("objects[0].balls"), std::string::npos);
    EXPECT_NE(error(R"({"type": "blob", "balls": [{"center": [0, 0, 0], "radius": 1, "strength": 0}]})").find("balls[0].strength"),
              std::string::npos);
}

} // namespace
} // namespace wideray
