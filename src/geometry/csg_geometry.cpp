#include "geometry/csg_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/object_space.h"

namespace wideray {

CsgGeometry::CsgGeometry(const std::vector<CsgObject>& objects, const std::vector<TriangleMesh>& meshes) {
    std::vector<AnalyticObject> analytics;
    for (const CsgObject& object : objects) {
        Tree tree;
        tree.nodes = object.nodes;
        tree.firstLeaf = uint32_t(leaves_.size());
        for (CsgNode& node : tree.nodes) {
            if (node.kind == CsgNode::Kind::Operation) continue;
            const bool mesh = node.kind == CsgNode::Kind::Mesh;
            if (mesh) {
                meshes_.emplace_back(meshes, object.meshes.at(node.solid));
                leaves_.push_back({true, uint32_t(meshes_.size() - 1), meshes_.back().bounds()});
            } else {
                analytics.push_back(object.analytics.at(node.solid));
                leaves_.push_back({false, uint32_t(analytics.size() - 1), {}});
            }
            node.solid = tree.leafCount++;
        }
        trees_.push_back(std::move(tree));
    }
    analytics_ = std::make_unique<AnalyticGeometry>(analytics);
    for (Leaf& leaf : leaves_)
        if (!leaf.mesh) leaf.bounds = analytics_->primitiveBounds(leaf.solid);
    for (Tree& tree : trees_) tree.bounds = nodeBounds(tree, 0);
}

// Conservative and tight where the operation allows: an intersection lies in every operand's box,
// a difference in its first operand's.
Bounds3f CsgGeometry::nodeBounds(const Tree& tree, uint32_t index) const {
    const CsgNode& node = tree.nodes[index];
    if (node.kind != CsgNode::Kind::Operation) return leaves_[tree.firstLeaf + node.solid].bounds;
    Bounds3f b = nodeBounds(tree, node.operands[0]);
    if (node.operation == CsgOperation::Difference) return b;
    for (size_t k = 1; k < node.operands.size(); ++k) {
        const Bounds3f o = nodeBounds(tree, node.operands[k]);
        if (node.operation != CsgOperation::Intersection) {
            b.grow(o);
        } else {
            const Bounds3f both(glm::max(b.lower, o.lower), glm::min(b.upper, o.upper));
            if (!both.empty()) b = both;  // an empty intersection keeps a valid box (it has no surface)
        }
    }
    return b;
}

bool CsgGeometry::contains(const Tree& tree, uint32_t index, const std::vector<uint8_t>& inside) {
    const CsgNode& node = tree.nodes[index];
    if (node.kind != CsgNode::Kind::Operation) return inside[node.solid] != 0;
    switch (node.operation) {
    case CsgOperation::Union:
        for (uint32_t k : node.operands)
            if (contains(tree, k, inside)) return true;
        return false;
    case CsgOperation::Intersection:
        for (uint32_t k : node.operands)
            if (!contains(tree, k, inside)) return false;
        return true;
    case CsgOperation::Difference:
        if (!contains(tree, node.operands[0], inside)) return false;
        for (size_t k = 1; k < node.operands.size(); ++k)
            if (contains(tree, node.operands[k], inside)) return false;
        return true;
    case CsgOperation::Xor: {
        bool odd = false;
        for (uint32_t k : node.operands) odd ^= contains(tree, k, inside);
        return odd;
    }
    }
    return false;
}

bool CsgGeometry::firstCrossing(const Tree& tree, const Ray& ray, double tnear, double tfar, ObjectCrossing& hit) const {
    // Per thread, reused: a ray's crossings need no allocation once the buffers have grown.
    thread_local SolidCrossings crossings;
    thread_local std::vector<uint8_t> inside;
    crossings.clear();
    const glm::dvec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
    for (uint32_t l = 0; l < tree.leafCount; ++l) {
        const Leaf& leaf = leaves_[tree.firstLeaf + l];
        double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
        if (!boxInterval(glm::dvec3(leaf.bounds.lower), glm::dvec3(leaf.bounds.upper), o, d, t0, t1)) continue;
        const size_t first = crossings.size();
        if (leaf.mesh) meshes_[leaf.solid].crossings(ray, crossings);
        else analytics_->crossings(leaf.solid, ray, crossings);
        for (size_t k = first; k < crossings.size(); ++k) crossings[k].leaf = l;
    }
    std::stable_sort(crossings.begin(), crossings.end(), [](const SolidCrossing& a, const SolidCrossing& b) { return a.t < b.t; });
    inside.assign(tree.leafCount, 0);
    bool wasInside = false;  // every solid is bounded: the line starts outside all of them
    for (size_t k = 0; k < crossings.size();) {
        if (crossings[k].t > tfar) return false;
        // Crossings at one t (solids that touch) change the object's inside together.
        size_t end = k;
        for (; end < crossings.size() && crossings[end].t == crossings[k].t; ++end)
            inside[crossings[end].leaf] = crossings[end].enters;
        const bool nowInside = contains(tree, 0, inside);
        if (nowInside != wasInside && crossings[k].t >= tnear) {
            hit.entersObject = nowInside;
            hit.crossing = crossings[k];
            // Where the group has several, the solid crossed is one whose change made the object's.
            for (size_t j = k; j < end; ++j) {
                inside[crossings[j].leaf] ^= 1;
                const bool without = contains(tree, 0, inside);
                inside[crossings[j].leaf] ^= 1;
                if (without != nowInside) {
                    hit.crossing = crossings[j];
                    break;
                }
            }
            return true;
        }
        wasInside = nowInside;
        k = end;
    }
    return false;
}

bool CsgGeometry::intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const {
    ObjectCrossing hit;
    if (!firstCrossing(trees_[primId], ray, ray.tnear, tfar, hit)) return false;
    t = float(hit.crossing.t);
    if (!(t >= ray.tnear && t <= tfar)) return false;
    u = v = 0.0f;
    return true;
}

SurfacePoint CsgGeometry::surface(const Ray& ray, const Hit& hit) const {
    // The crossing is found again (the same arithmetic finds the same one) rather than packed into u, v.
    const Tree& tree = trees_[hit.primId];
    ObjectCrossing found{{double(hit.t), true, 0}, true};  // only if the ray is not the one traced
    firstCrossing(tree, ray, ray.tnear, std::numeric_limits<double>::infinity(), found);
    const SolidCrossing& c = found.crossing;
    const Leaf& leaf = leaves_[tree.firstLeaf + c.leaf];
    const Hit leafHit{float(c.t), c.u, c.v, c.primId, 0};
    SurfacePoint sp = leaf.mesh ? meshes_[leaf.solid].surface(ray, leafHit) : analytics_->surface(ray, leafHit);
    if (c.enters != found.entersObject) {  // e.g. a difference's carved face: turned to face out of the object
        sp.geometricNormal = -sp.geometricNormal;
        sp.shadingNormal = -sp.shadingNormal;
    }
    sp.instance = kInvalidId;
    return sp;
}

} // namespace wideray
