#include "geometry/analytic_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/polynomial_roots.h"

namespace wideray {

double AnalyticGeometry::Quadric::at(const glm::dvec3& p) const {
    return a * p.x * p.x + b * p.y * p.y + c * p.z * p.z + d * p.x * p.y + e * p.x * p.z + f * p.y * p.z + g * p.x +
           h * p.y + i * p.z + j;
}

glm::dvec3 AnalyticGeometry::Quadric::gradient(const glm::dvec3& p) const {
    return {2 * a * p.x + d * p.y + e * p.z + g, 2 * b * p.y + d * p.x + f * p.z + h, 2 * c * p.z + e * p.x + f * p.y + i};
}

namespace {

using Quadric = AnalyticGeometry::Quadric;

/// The canonical quadrics, negative inside: within -1 <= y <= 1, of radius 1 at their capped ends.
Quadric canonicalQuadric(const AnalyticObject& o) {
    switch (o.shape) {
    case AnalyticShape::Ellipsoid: return {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
    case AnalyticShape::Cylinder: return {1, 0, 1, 0, 0, 0, 0, 0, 0, -1};
    case AnalyticShape::Cone: return {1, -0.25, 1, 0, 0, 0, 0, 0.5, 0, -0.25};            // apex at y = 1
    case AnalyticShape::Paraboloid: return {1, 0, 1, 0, 0, 0, 0, -0.5, 0, -0.5};          // vertex at y = -1
    case AnalyticShape::Hyperboloid: return {1, -0.5, 1, 0, 0, 0, 0, 0, 0, -0.5};         // waist 1/sqrt(2)
    case AnalyticShape::TwoSheetHyperboloid: return {0.75, -1, 0.75, 0, 0, 0, 0, 0, 0, 0.25};  // vertices at y = +-1/2
    case AnalyticShape::Quadric: {
        const auto& k = o.coefficients;
        return {k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8], k[9]};
    }
    case AnalyticShape::Torus:
    case AnalyticShape::Blob: break;
    }
    return {};
}

/// The blob's field minus its threshold along the ray o + t d, as a polynomial of degree 6 in t over
/// an interval where the balls in `active` are the ones whose support the ray is in.
void blobPolynomial(const AnalyticObject& blob, const std::vector<uint32_t>& active, const glm::dvec3& o,
                    const glm::dvec3& d, double* c) {
    for (int k = 0; k <= 6; ++k) c[k] = 0.0;
    c[0] = -double(blob.threshold);
    const double dd = glm::dot(d, d);
    for (uint32_t i : active) {
        const BlobBall& ball = blob.balls[i];
        const glm::dvec3 oc = o - glm::dvec3(ball.center);
        const double r2 = double(ball.radius) * ball.radius;
        // u(t) = 1 - |oc + t d|^2 / r^2 = u0 + u1 t + u2 t^2; the field adds strength * u^3.
        const double u0 = 1.0 - glm::dot(oc, oc) / r2, u1 = -2.0 * glm::dot(oc, d) / r2, u2 = -dd / r2;
        const double square[5] = {u0 * u0, 2 * u0 * u1, u1 * u1 + 2 * u0 * u2, 2 * u1 * u2, u2 * u2};
        const double s = ball.strength;
        for (int k = 0; k < 5; ++k) {
            c[k] += s * square[k] * u0;
            c[k + 1] += s * square[k] * u1;
            c[k + 2] += s * square[k] * u2;
        }
    }
}

/// The field's gradient at p (the surface normal points against it: the field falls outwards).
glm::dvec3 blobGradient(const AnalyticObject& blob, const glm::dvec3& p) {
    glm::dvec3 g(0.0);
    for (const BlobBall& ball : blob.balls) {
        const glm::dvec3 pc = p - glm::dvec3(ball.center);
        const double r2 = double(ball.radius) * ball.radius, u = 1.0 - glm::dot(pc, pc) / r2;
        if (u > 0.0) g += double(ball.strength) * 3.0 * u * u * (-2.0 / r2) * pc;
    }
    return g;
}

} // namespace

AnalyticGeometry::AnalyticGeometry(const std::vector<AnalyticObject>& objects) {
    for (const AnalyticObject& model : objects) {
        Object o{model, ObjectSpace(model.transform)};
        if (model.shape == AnalyticShape::Torus) {
            const double extent = double(model.majorRadius) + double(model.minorRadius);
            o.lower = {-extent, -model.minorRadius, -extent};
            o.upper = {extent, model.minorRadius, extent};
        } else if (model.shape == AnalyticShape::Blob) {
            o.lower = glm::dvec3(std::numeric_limits<double>::infinity());
            o.upper = -o.lower;
            for (const BlobBall& ball : model.balls) {
                o.lower = glm::min(o.lower, glm::dvec3(ball.center) - double(ball.radius));
                o.upper = glm::max(o.upper, glm::dvec3(ball.center) + double(ball.radius));
            }
        } else {
            o.quadric = canonicalQuadric(model);
            o.lower = glm::dvec3(-1.0);
            o.upper = glm::dvec3(1.0);
        }
        // A margin keeps the roots where the box touches the surface (an ellipsoid's on the box faces)
        // inside the searched interval, and gives crossings() room outside the solid beyond its last root.
        const glm::dvec3 margin = 1e-4 * (o.upper - o.lower);
        o.lower -= margin;
        o.upper += margin;
        o.worldBounds = motionBounds(model.transform, model.endTransform, o.lower, o.upper);
        objects_.push_back(o);
    }
}

template <class Visit>
void AnalyticGeometry::visitRoots(const Object& object, const glm::dvec3& o, const glm::dvec3& d, double tnear,
                                  double tfar, Visit&& visit) const {
    double t0 = tnear, t1 = tfar;
    if (!boxInterval(object.lower, object.upper, o, d, t0, t1)) return;
    if (object.model.shape == AnalyticShape::Blob) return visitBlobRoots(object.model, o, d, t0, t1, visit);
    // Solved from the entry point, where the polynomial's terms are of the size of the object.
    const double ts = t0;
    const glm::dvec3 os = o + ts * d;
    auto take = [&](double t, int part) {
        if (t >= tnear && t <= tfar) visit(t, part);
    };
    double roots[8];
    if (object.model.shape == AnalyticShape::Torus) {
        const double R = object.model.majorRadius, r = object.model.minorRadius, R2 = R * R;
        const double length = glm::length(d);
        const glm::dvec3 n = d / length;  // unit direction: s is a distance
        const double e = glm::dot(os, n), f = glm::dot(os, os) + R2 - r * r;
        const double c[5] = {f * f - 4 * R2 * (os.x * os.x + os.z * os.z),
                             4 * e * f - 8 * R2 * (os.x * n.x + os.z * n.z),
                             4 * e * e + 2 * f - 4 * R2 * (n.x * n.x + n.z * n.z), 4 * e, 1.0};
        const int count = polynomialRoots(c, 4, 0.0, (t1 - ts) * length, roots);
        for (int k = 0; k < count; ++k) {
            // Refined on the torus' own equation, which has no expanded terms to cancel.
            double s = roots[k];
            for (int step = 0; step < 2; ++step) {
                const glm::dvec3 p = os + s * n;
                const double q = glm::dot(p, p) + R2 - r * r;
                const double g = q * q - 4 * R2 * (p.x * p.x + p.z * p.z);
                const double dg = 4 * q * glm::dot(p, n) - 8 * R2 * (p.x * n.x + p.z * n.z);
                if (dg == 0.0) break;
                const double next = s - g / dg;
                if (std::fabs(next - roots[k]) > 1e-6 * (r + std::fabs(roots[k]))) break;  // stay with this root
                s = next;
            }
            take(ts + s / length, 0);
        }
        return;
    }
    const Quadric& q = object.quadric;
    const double A = q.a * d.x * d.x + q.b * d.y * d.y + q.c * d.z * d.z + q.d * d.x * d.y + q.e * d.x * d.z + q.f * d.y * d.z;
    const double B = 2 * (q.a * os.x * d.x + q.b * os.y * d.y + q.c * os.z * d.z) + q.d * (os.x * d.y + os.y * d.x) +
                     q.e * (os.x * d.z + os.z * d.x) + q.f * (os.y * d.z + os.z * d.y) + q.g * d.x + q.h * d.y + q.i * d.z;
    const double C = q.at(os);
    const double c[3] = {C, B, A};
    const int count = polynomialRoots(c, 2, 0.0, t1 - ts, roots);
    const bool general = object.model.shape == AnalyticShape::Quadric;
    for (int k = 0; k < count; ++k) {
        const double t = ts + roots[k];
        const glm::dvec3 p = o + t * d;
        const bool inside = general ? glm::all(glm::lessThanEqual(glm::abs(p), glm::dvec3(1.0))) : std::fabs(p.y) <= 1.0;
        if (inside) take(t, 0);
    }
    if (object.model.capped && !general && d.y != 0.0) {
        for (int end = 0; end < 2; ++end) {
            const double y = end == 0 ? -1.0 : 1.0;
            const double t = (y - o.y) / d.y;
            glm::dvec3 p = o + t * d;
            p.y = y;
            if (q.at(p) <= 0.0) take(t, 1 + end);
        }
    }
}

template <class Visit>
void AnalyticGeometry::visitBlobRoots(const AnalyticObject& blob, const glm::dvec3& o, const glm::dvec3& d, double t0,
                                      double t1, Visit&& visit) {
    // Where the ray enters and leaves each ball's support: between two such events the field is one
    // polynomial of degree 6, whose roots in the piece are exact (bracketed by its derivatives).
    struct Event {
        double t;
        uint32_t ball;
        bool enters;
    };
    std::vector<Event> events;
    const double dd = glm::dot(d, d);
    for (uint32_t i = 0; i < blob.balls.size(); ++i) {
        const BlobBall& ball = blob.balls[i];
        const glm::dvec3 oc = o - glm::dvec3(ball.center);
        const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - double(ball.radius) * ball.radius;
        const double disc = b * b - dd * c;
        if (disc <= 0.0) continue;
        const double root = std::sqrt(disc);
        const double enter = (-b - root) / dd, leave = (-b + root) / dd;
        if (leave < t0 || enter > t1) continue;
        events.push_back({std::max(enter, t0), i, true});
        events.push_back({std::min(leave, t1), i, false});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        return a.t != b.t ? a.t < b.t : a.enters > b.enters;
    });
    std::vector<uint32_t> active;
    double roots[8];
    for (size_t k = 0; k + 1 < events.size(); ++k) {
        const Event& e = events[k];
        if (e.enters) active.push_back(e.ball);
        else active.erase(std::find(active.begin(), active.end(), e.ball));
        const double start = e.t, end = events[k + 1].t;
        if (active.empty() || !(end > start)) continue;
        double c[7];
        blobPolynomial(blob, active, o + start * d, d, c);  // in t - start: terms of the blob's size
        const int count = polynomialRoots(c, 6, 0.0, end - start, roots);
        for (int r = 0; r < count; ++r)
            if (!visit(start + roots[r], 0)) return;
    }
}

const ObjectSpace& AnalyticGeometry::spaceAt(const Object& object, float time, std::optional<ObjectSpace>& moving) {
    if (!object.model.endTransform) return object.space;
    return moving.emplace(ObjectSpace::at(object.model.transform, *object.model.endTransform, time));
}

bool AnalyticGeometry::contains(const Object& object, const glm::dvec3& p) {
    switch (object.model.shape) {
    case AnalyticShape::Torus: {
        const double R = object.model.majorRadius, r = object.model.minorRadius;
        const double q = glm::dot(p, p) + R * R - r * r;
        return q * q - 4 * R * R * (p.x * p.x + p.z * p.z) < 0.0;
    }
    case AnalyticShape::Blob: {
        double field = 0.0;
        for (const BlobBall& ball : object.model.balls) {
            const glm::dvec3 pc = p - glm::dvec3(ball.center);
            const double u = 1.0 - glm::dot(pc, pc) / (double(ball.radius) * ball.radius);
            if (u > 0.0) field += double(ball.strength) * u * u * u;
        }
        return field > double(object.model.threshold);
    }
    case AnalyticShape::Quadric:
        return object.quadric.at(p) <= 0.0 && glm::all(glm::lessThanEqual(glm::abs(p), glm::dvec3(1.0)));
    default: return object.quadric.at(p) <= 0.0 && (!object.model.capped || std::fabs(p.y) <= 1.0);
    }
}

void AnalyticGeometry::crossings(uint32_t primId, const Ray& ray, SolidCrossings& out) const {
    const Object& object = objects_[primId];
    glm::dvec3 o, d;
    std::optional<ObjectSpace> moving;
    const ObjectSpace& space = spaceAt(object, ray.time, moving);
    space.ray(ray, o, d);
    double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
    if (!boxInterval(object.lower, object.upper, o, d, t0, t1)) return;
    const size_t first = out.size();
    visitRoots(object, o, d, t0, t1, [&](double t, int part) {
        out.push_back({t, false, primId, float(part)});
        return true;
    });
    std::sort(out.begin() + first, out.end(), [](const SolidCrossing& a, const SolidCrossing& b) { return a.t < b.t; });
    // Which roots change the inside, decided by the solid's own inequality between them: a tangent
    // root, or one root found twice, changes nothing and is dropped.
    bool inside = false;  // before the box
    size_t kept = first;
    for (size_t k = first; k < out.size(); ++k) {
        const double next = k + 1 < out.size() ? out[k + 1].t : t1;
        if (next == out[k].t && k + 1 < out.size()) continue;
        const bool after = contains(object, o + 0.5 * (out[k].t + next) * d);
        if (after == inside) continue;
        inside = after;
        out[k].enters = after;
        out[kept++] = out[k];
    }
    out.resize(kept);
}

bool AnalyticGeometry::intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const {
    const Object& object = objects_[primId];
    glm::dvec3 o, d;
    std::optional<ObjectSpace> moving;
    const ObjectSpace& space = spaceAt(object, ray.time, moving);
    space.ray(ray, o, d);
    double tHit = std::numeric_limits<double>::infinity();
    int part = 0;
    visitRoots(object, o, d, ray.tnear, tfar, [&](double root, int rootPart) {
        if (root < tHit) tHit = root, part = rootPart;
        return false;  // a blob's first root is its nearest
    });
    if (tHit == std::numeric_limits<double>::infinity()) return false;
    t = float(tHit);
    if (!(t >= ray.tnear && t <= tfar)) return false;
    u = float(part);
    v = 0.0f;
    return true;
}

SurfacePoint AnalyticGeometry::surface(const Ray& ray, const Hit& hit) const {
    const Object& object = objects_[hit.primId];
    glm::dvec3 o, d;
    std::optional<ObjectSpace> moving;
    const ObjectSpace& space = spaceAt(object, ray.time, moving);
    space.ray(ray, o, d);
    glm::dvec3 p = o + double(hit.t) * d;
    const int part = int(hit.u);
    glm::dvec3 normal;
    glm::vec2 uv;
    constexpr double kTwoPi = 6.283185307179586;
    if (object.model.shape == AnalyticShape::Blob) {
        normal = -blobGradient(object.model, p);
        uv = {float(std::atan2(p.z, p.x) / kTwoPi + 0.5), 0.0f};
    } else if (object.model.shape == AnalyticShape::Torus) {
        const double R = object.model.majorRadius, r = object.model.minorRadius;
        const double q = glm::dot(p, p) + R * R - r * r;
        normal = 4.0 * q * p - 8.0 * R * R * glm::dvec3(p.x, 0.0, p.z);
        const double ring = std::sqrt(p.x * p.x + p.z * p.z) - R;
        uv = {float(std::atan2(p.z, p.x) / kTwoPi + 0.5), float(std::atan2(p.y, ring) / kTwoPi + 0.5)};
    } else if (part == 0) {
        normal = object.quadric.gradient(p);
        uv = {float(std::atan2(p.z, p.x) / kTwoPi + 0.5), float(0.5 * (p.y + 1.0))};
    } else {
        p.y = part == 1 ? -1.0 : 1.0;
        normal = {0.0, p.y, 0.0};
        uv = {float(0.5 * (p.x + 1.0)), float(0.5 * (p.z + 1.0))};
    }
    SurfacePoint sp;
    sp.position = space.point(p);
    sp.geometricNormal = sp.shadingNormal = space.normal(normal);
    sp.uv = uv;
    sp.material = object.model.material;
    return sp;
}

} // namespace wideray
