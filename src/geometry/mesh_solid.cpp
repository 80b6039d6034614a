#include "geometry/mesh_solid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/object_space.h"

namespace wideray {
namespace {

constexpr uint32_t kLeafTriangles = 4;

TriangleMesh placedMesh(const std::vector<TriangleMesh>& meshes, const MeshInstance& instance) {
    SceneDescription placed;
    placed.meshes = {meshes.at(instance.mesh)};
    placed.instances = {{0, instance.transform, instance.material}};
    return flattenTriangles(placed);
}

/// An edge function that is exactly zero (the line passes through the edge or a vertex) takes the
/// sign it would have for a point moved by an infinitesimal (1, eps) in the sheared plane: its
/// gradient's. The neighbour across the edge computes the exact negation, so of the triangles
/// around an edge or a vertex exactly one is hit: simulation of simplicity.
double perturbed(double edge, double wx, double wy) {
    if (edge != 0.0) return edge;
    return wy != 0.0 ? -wy : wx;
}

/// Woop, Benthin and Wald's watertight test in double precision, over the whole line, with ties on
/// edges and vertices broken as above: t, and the weights u, v of b and c.
bool lineTriangle(const glm::dvec3& o, int kx, int ky, int kz, const glm::dvec3& shear, const glm::dvec3& a,
                  const glm::dvec3& b, const glm::dvec3& c, double& t, double& u, double& v) {
    const glm::dvec3 A = a - o, B = b - o, C = c - o;
    const double ax = A[kx] - shear.x * A[kz], ay = A[ky] - shear.y * A[kz];
    const double bx = B[kx] - shear.x * B[kz], by = B[ky] - shear.y * B[kz];
    const double cx = C[kx] - shear.x * C[kz], cy = C[ky] - shear.y * C[kz];
    const double U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
    const double su = perturbed(U, bx - cx, by - cy), sv = perturbed(V, cx - ax, cy - ay), sw = perturbed(W, ax - bx, ay - by);
    if (!((su > 0 && sv > 0 && sw > 0) || (su < 0 && sv < 0 && sw < 0))) return false;
    const double det = U + V + W;
    if (det == 0.0) return false;
    const double T = shear.z * (U * A[kz] + V * B[kz] + W * C[kz]);
    t = T / det;
    u = V / det;
    v = W / det;
    return true;
}

/// A triangle the line meets.
struct LineHit {
    double t;
    int side;  ///< +1 against the outward normal, -1 along it
    SolidCrossing hit;
};

} // namespace

MeshSolid::MeshSolid(const std::vector<TriangleMesh>& meshes, const MeshInstance& instance)
    : geometry_(placedMesh(meshes, instance)) {
    const uint32_t count = geometry_.primitiveCount();
    std::vector<glm::vec3> centers(count);
    for (uint32_t i = 0; i < count; ++i) centers[i] = geometry_.primitiveBounds(i).center();
    order_.resize(count);
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.reserve(2 * (count / kLeafTriangles + 1));
    build(0, count, centers);
}

// Median split of the centers along the box's longest axis: the tree only has to keep the crossings
// query logarithmic for the meshes CSG takes.
uint32_t MeshSolid::build(uint32_t first, uint32_t count, std::vector<glm::vec3>& centers) {
    const uint32_t index = uint32_t(nodes_.size());
    Bounds3f box, centerBox;
    for (uint32_t i = first; i < first + count; ++i) {
        box.grow(geometry_.primitiveBounds(order_[i]));
        centerBox.grow(centers[order_[i]]);
    }
    const glm::vec3 pad = 1e-5f * (glm::abs(box.lower) + glm::abs(box.upper)) + 1e-30f;
    nodes_.push_back({{box.lower - pad, box.upper + pad}, first, count});
    if (count <= kLeafTriangles) return index;
    const int axis = centerBox.largestAxis();
    const uint32_t half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](uint32_t a, uint32_t b) { return centers[a][axis] < centers[b][axis]; });
    build(first, half, centers);
    const uint32_t right = build(first + half, count - half, centers);
    nodes_[index].first = right;
    nodes_[index].count = 0;
    return index;
}

void MeshSolid::crossings(const Ray& ray, SolidCrossings& out) const {
    const glm::dvec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
    int kz = std::fabs(d.x) > std::fabs(d.y) ? (std::fabs(d.x) > std::fabs(d.z) ? 0 : 2) : (std::fabs(d.y) > std::fabs(d.z) ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0.0) std::swap(kx, ky);
    const glm::dvec3 shear(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);

    // Per thread, reused: no allocation per ray once it has grown (crossings never recurse).
    thread_local std::vector<LineHit> hits;
    hits.clear();
    const TriangleMesh& mesh = *geometry_.triangles();
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
        if (!boxInterval(glm::dvec3(node.box.lower), glm::dvec3(node.box.upper), o, d, t0, t1)) continue;
        if (node.count == 0) {
            stack[top++] = node.first;
            stack[top++] = uint32_t(&node - nodes_.data()) + 1;
            continue;
        }
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const glm::uvec3& tri = mesh.triangles[order_[i]];
            const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]), c(mesh.positions[tri.z]);
            double t, u, v;
            if (!lineTriangle(o, kx, ky, kz, shear, a, b, c, t, u, v)) continue;
            const int side = glm::dot(glm::cross(b - a, c - a), d) < 0.0 ? 1 : -1;
            hits.push_back({t, side, {t, side > 0, order_[i], float(u), float(v)}});
        }
    }
    std::sort(hits.begin(), hits.end(), [](const LineHit& a, const LineHit& b) {
        return a.t != b.t ? a.t < b.t : a.hit.primId < b.hit.primId;
    });
    int count = 0;
    for (size_t k = 0; k < hits.size();) {
        // Crossings at one t (an edge or a vertex of several triangles) count together.
        const bool before = count > 0;
        size_t end = k;
        for (; end < hits.size() && hits[end].t == hits[k].t; ++end) count += hits[end].side;
        if ((count > 0) != before) {
            SolidCrossing crossing = hits[k].hit;
            for (size_t j = k; j < end; ++j)
                if (hits[j].hit.enters == !before) crossing = hits[j].hit;  // a triangle facing the way the line goes
            crossing.enters = !before;
            out.push_back(crossing);
        }
        k = end;
    }
}

} // namespace wideray
