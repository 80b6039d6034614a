#include "accel/scene_accel.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "accel/bvh_stats.h"
#include "accel/triangle_splitter.h"

namespace wideray {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Gives the leaves of a BVH over user primitives their type.
template <int N>
void markUserLeaves(WideBvh<N>& bvh) {
    auto mark = [](NodeRef& ref) {
        if (ref.isLeaf() && ref.count() > 0) ref = NodeRef::userLeaf(ref.first(), ref.count());
    };
    mark(bvh.root);
    for (WideNode<N>& node : bvh.nodes)
        for (NodeRef& child : node.child) mark(child);
}

/// One tree over both: a's nodes, then b's, under a new root whose two children are their roots.
template <int N>
WideBvh<N> joinBvhs(WideBvh<N> a, WideBvh<N> b) {
    if (b.root.bits == NodeRef::empty().bits) return a;
    if (a.root.bits == NodeRef::empty().bits) return b;
    const uint32_t offset = uint32_t(a.nodes.size());
    auto shift = [offset](NodeRef ref) { return ref.isLeaf() ? ref : NodeRef::inner(ref.index() + offset); };
    for (WideNode<N>& node : b.nodes)
        for (NodeRef& child : node.child) child = shift(child);
    WideBvh<N> out;
    out.nodes = std::move(a.nodes);
    out.nodes.insert(out.nodes.end(), b.nodes.begin(), b.nodes.end());
    WideNode<N> root;
    constexpr float inf = std::numeric_limits<float>::infinity();
    const NodeRef children[2] = {a.root, shift(b.root)};
    const Bounds3f bounds[2] = {a.bounds, b.bounds};
    for (int i = 0; i < N; ++i) {
        const bool used = i < 2;
        root.lowerX[i] = used ? bounds[i].lower.x : inf;
        root.lowerY[i] = used ? bounds[i].lower.y : inf;
        root.lowerZ[i] = used ? bounds[i].lower.z : inf;
        root.upperX[i] = used ? bounds[i].upper.x : -inf;
        root.upperY[i] = used ? bounds[i].upper.y : -inf;
        root.upperZ[i] = used ? bounds[i].upper.z : -inf;
        root.child[i] = used ? children[i] : NodeRef::empty();
    }
    out.root = NodeRef::inner(uint32_t(out.nodes.size()));
    out.nodes.push_back(root);
    out.bounds = a.bounds;
    out.bounds.grow(b.bounds);
    return out;
}

/// A leaf's primitives, each once: spatial splits put parts of one triangle in sibling leaves, which
/// the collapse may merge. Only a leaf of at least minSpatialSplitRefs primitives can repeat one
/// (smaller ones, all by default, skip the sort).
class DistinctPrims {
public:
    DistinctPrims(std::span<const uint32_t> prims, bool mayRepeat) : prims_(prims) {
        if (!mayRepeat) return;
        // The collapse merges at most 4 blocks' worth of primitives into one leaf.
        if (prims.size() > kCapacity) throw std::logic_error("SceneAccel: a leaf with more primitives than it can hold");
        std::copy(prims.begin(), prims.end(), local_);
        std::sort(local_, local_ + prims.size());
        prims_ = {local_, size_t(std::unique(local_, local_ + prims.size()) - local_)};
    }
    std::span<const uint32_t> get() const { return prims_; }

private:
    static constexpr size_t kCapacity = NodeRef::kMaxLeafItems * kBlockSize;
    std::span<const uint32_t> prims_;
    uint32_t local_[kCapacity];
};

/// Triangle leaves as blocks of kBlockSize triangles (unused lanes repeat the block's first
/// triangle, with an invalid primId).
class TriangleBlockWriter final : public LeafWriter {
public:
    /// Leaves of `repeatsFrom` primitives or more may name one twice.
    TriangleBlockWriter(const TriangleMesh& mesh, size_t repeatsFrom, TriangleBlocks& blocks)
        : mesh_(mesh), repeatsFrom_(repeatsFrom), blocks_(blocks) {}

    uint32_t itemCount(std::span<const uint32_t> prims) const override {
        return blocksFor(DistinctPrims(prims, prims.size() >= repeatsFrom_).get().size());
    }
    void allocate(size_t count) override { blocks_.resize(count); }
    void write(std::span<const uint32_t> leafPrims, uint32_t first) const override {
        const DistinctPrims distinct(leafPrims, leafPrims.size() >= repeatsFrom_);
        const std::span<const uint32_t> prims = distinct.get();
        for (size_t base = 0; base < prims.size(); base += kBlockSize) {
            TriangleBlock<kBlockSize>& block = blocks_[first++];
            for (int lane = 0; lane < kBlockSize; ++lane) {
                const bool used = base + lane < prims.size();
                const uint32_t prim = used ? prims[base + lane] : prims[base];
                const glm::uvec3& t = mesh_.triangles[prim];
                const glm::vec3 &a = mesh_.positions[t.x], &b = mesh_.positions[t.y], &c = mesh_.positions[t.z];
                block.v0x[lane] = a.x; block.v0y[lane] = a.y; block.v0z[lane] = a.z;
                block.v1x[lane] = b.x; block.v1y[lane] = b.y; block.v1z[lane] = b.z;
                block.v2x[lane] = c.x; block.v2y[lane] = c.y; block.v2z[lane] = c.z;
                block.primId[lane] = used ? prim : kInvalidId;
            }
        }
    }

private:
    static uint32_t blocksFor(size_t prims) { return uint32_t((prims + kBlockSize - 1) / kBlockSize); }

    const TriangleMesh& mesh_;
    size_t repeatsFrom_;
    TriangleBlocks& blocks_;
};

/// User primitive leaves: one reference (geomId, primId) per item.
class UserPrimWriter final : public LeafWriter {
public:
    UserPrimWriter(const std::vector<PrimRef>& refs, std::vector<PrimRef>& out) : refs_(refs), out_(out) {}

    uint32_t itemCount(std::span<const uint32_t> prims) const override { return uint32_t(prims.size()); }
    void allocate(size_t count) override { out_.resize(count); }
    void write(std::span<const uint32_t> prims, uint32_t first) const override {
        for (uint32_t p : prims) out_[first++] = refs_[p];
    }

private:
    const std::vector<PrimRef>& refs_;
    std::vector<PrimRef>& out_;
};

} // namespace

BuildRefs triangleRefs(const TriangleMesh& mesh, size_t capacity) {
    BuildRefs refs;
    refs.reserve(std::max(capacity, mesh.triangles.size()));
    refs.resize(mesh.triangles.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, refs.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const glm::uvec3& t = mesh.triangles[i];
            Bounds3f b;
            b.grow(mesh.positions[t.x]);
            b.grow(mesh.positions[t.y]);
            b.grow(mesh.positions[t.z]);
            refs[i] = makeBuildRef(b, uint32_t(i));
        }
    });
    return refs;
}

template <int N>
SceneAccel<N>::SceneAccel(std::shared_ptr<const SceneGeometry> geometry, const BvhBuildConfig& config)
    : geometry_(std::move(geometry)) {
    // The triangle blocks name their triangles by primId alone: one triangle geometry, geomId 0.
    for (uint32_t g = 0; g < geometry_->size(); ++g) {
        const Geometry& item = (*geometry_)[g];
        userGeometries_.push_back(item.user());
        if (item.triangles() && g != 0) throw std::logic_error("SceneAccel: triangle meshes must be geometry 0");
        if (const InstanceGeometry* instances = item.instances()) buildInstances(g, *instances, config);
    }
    WideBvh<N> triangles, user;
    if (geometry_->size() > 0 && (*geometry_)[0].triangles()) triangles = buildTrianglesAtBest(*(*geometry_)[0].triangles(), config);
    user = buildUser(config);
    auto start = std::chrono::steady_clock::now();
    bvh_ = joinBvhs(std::move(triangles), std::move(user));
    timings_.collapseSeconds += secondsSince(start);
}

template <int N>
WideBvh<N> SceneAccel<N>::buildTrianglesAtBest(const TriangleMesh& mesh, const BvhBuildConfig& config) {
    WideBvh<N> bvh = buildTriangles(mesh, config);
    if (config.quality != BuildQuality::High || mesh.triangles.size() > config.compareBuildsBelow) return bvh;
    // Top-down splitting is greedy: on some small meshes (Suzanne) the spatial splits that lower the
    // cost near the root raise it below; there the fast build is cheap to compare with.
    TriangleBlocks spatialBlocks = std::move(blocks_);
    blocks_.clear();
    BvhBuildConfig fast = config;
    fast.quality = BuildQuality::Fast;
    WideBvh<N> objectBvh = buildTriangles(mesh, fast);
    if (wideBvhStats(objectBvh, config).sahCost < wideBvhStats(bvh, config).sahCost) return objectBvh;
    blocks_ = std::move(spatialBlocks);
    return bvh;
}

template <int N>
WideBvh<N> SceneAccel<N>::buildTriangles(const TriangleMesh& mesh, const BvhBuildConfig& config) {
    if (mesh.triangles.empty()) return {};
    if (mesh.triangles.size() / kBlockSize >= NodeRef::kFirstMask)
        throw std::length_error("SceneAccel: more triangles than the BVH's leaves can address (" +
                                std::to_string(NodeRef::kFirstMask) + " blocks of " + std::to_string(kBlockSize) + ")");
    auto start = std::chrono::steady_clock::now();
    const TriangleSplitter splitter(mesh);
    BinaryBvh binary =
        buildBinaryBvh(triangleRefs(mesh, buildRefCapacity(mesh.triangles.size(), config)), config, &splitter);
    timings_.binarySeconds += secondsSince(start);

    start = std::chrono::steady_clock::now();
    TriangleBlockWriter writer(mesh, minSpatialSplitRefs(config), blocks_);
    WideBvh<N> bvh = collapseBvh<N>(binary, writer, config);
    timings_.collapseSeconds += secondsSince(start);
    return bvh;
}

template <int N>
void SceneAccel<N>::buildInstances(uint32_t geomId, const InstanceGeometry& instances, const BvhBuildConfig& config) {
    for (const auto& mesh : instances.meshes()) {
        meshAccels_.push_back(std::make_unique<SceneAccel<N>>(mesh, config));
        meshViews_.push_back(meshAccels_.back()->view());
        timings_.binarySeconds += meshAccels_.back()->timings().binarySeconds;
        timings_.collapseSeconds += meshAccels_.back()->timings().collapseSeconds;
    }
    auto rows = [](const glm::dmat4& m, double* out) {
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 4; ++column) out[4 * row + column] = m[column][row];
    };
    for (const InstanceGeometry::Placement& p : instances.placements()) {
        InstanceRef ref{{}, p.mesh, p.firstPrim};
        rows(glm::inverse(glm::dmat4(p.transform)), ref.objectFromWorld);
        if (p.endTransform) {
            ref.motion = uint32_t(instanceMotions_.size());
            InstanceMotion& motion = instanceMotions_.emplace_back();
            rows(glm::dmat4(p.transform), motion.worldFromObject[0]);
            rows(glm::dmat4(*p.endTransform), motion.worldFromObject[1]);
        }
        instanceRefs_.push_back(ref);
    }
    instanceTable_.geomId = geomId;
    instanceTable_.instances = instanceRefs_.data();
    instanceTable_.motions = instanceMotions_.data();
    instanceTable_.meshes<N>() = meshViews_.data();
}

template <int N>
WideBvh<N> SceneAccel<N>::buildUser(const BvhBuildConfig& config) {
    // User primitives and instances, each bounded by its geometry.
    BuildRefs buildRefs;
    std::vector<PrimRef> refs;
    for (uint32_t g = 0; g < geometry_->size(); ++g) {
        const Geometry& item = (*geometry_)[g];
        if (!item.user() && !item.instances()) continue;
        for (uint32_t p = 0; p < item.primitiveCount(); ++p) {
            buildRefs.push_back(makeBuildRef(item.primitiveBounds(p), uint32_t(refs.size())));
            refs.push_back({g, p});
        }
    }
    if (refs.empty()) return {};
    if (refs.size() >= NodeRef::kFirstMask) throw std::length_error("SceneAccel: too many user primitives");
    auto start = std::chrono::steady_clock::now();
    BvhBuildConfig userConfig = config;
    userConfig.blockSize = 1;
    BinaryBvh binary = buildBinaryBvh(std::move(buildRefs), userConfig);
    UserPrimWriter writer(refs, prims_);
    WideBvh<N> bvh = collapseBvh<N>(binary, writer, userConfig);
    markUserLeaves(bvh);
    timings_.binarySeconds += secondsSince(start);
    return bvh;
}

template <int N>
SceneView<N> SceneAccel<N>::view() const {
    return {bvh_.nodes.data(), bvh_.root,
            {blocks_.data(), prims_.data(), userGeometries_.data(), instanceRefs_.empty() ? nullptr : &instanceTable_},
            bvh_.bounds};
}

template <int N>
size_t SceneAccel<N>::triangleReferences() const {
    size_t references = 0;
    for (const TriangleBlock<kBlockSize>& block : blocks_) references += size_t(block.count());
    for (const auto& mesh : meshAccels_) references += mesh->triangleReferences();
    return references;
}

template <int N>
size_t SceneAccel<N>::bytes() const {
    size_t bytes = bvh_.nodes.size() * sizeof(WideNode<N>) + blocks_.size() * sizeof(TriangleBlock<kBlockSize>) +
                   prims_.size() * sizeof(PrimRef) + instanceRefs_.size() * sizeof(InstanceRef) +
                   instanceMotions_.size() * sizeof(InstanceMotion);
    for (const auto& mesh : meshAccels_) bytes += mesh->bytes();
    return bytes;
}

template <int N>
size_t SceneAccel<N>::flattenedBytes() const {
    size_t bytes = this->bytes() - instanceRefs_.size() * sizeof(InstanceRef);
    for (const auto& mesh : meshAccels_) bytes -= mesh->bytes();
    for (const InstanceRef& instance : instanceRefs_) bytes += meshAccels_[instance.mesh]->bytes();
    return bytes;
}

template class SceneAccel<4>;
template class SceneAccel<8>;
template class SceneAccel<16>;

} // namespace wideray
