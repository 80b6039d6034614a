#include "backends/course_structure.h"

#include <chrono>

#include <fmt/core.h>

#include "accel/bvh2_build.h"
#include "accel/grid_build.h"
#include "accel/kdtree_build.h"
#include "backends/wideray_structure.h"
#include "core/error.h"
#include "kernels/course_kernels.h"

namespace wideray {
namespace {

Bvh2View viewOf(const Bvh2& b, const PrimitiveView& p) { return {b.nodes.empty() ? nullptr : b.nodes.data(), b.items.data(), p}; }
SkipView viewOf(const SkipTree& s, const PrimitiveView& p) { return {s.nodes.data(), uint32_t(s.nodes.size()), s.items.data(), p}; }
KdTreeView viewOf(const KdTree& k, const PrimitiveView& p) {
    return {k.nodes.empty() ? nullptr : k.nodes.data(), k.items.data(), boxPlanes(k.bounds), p};
}
GridView viewOf(const Grid& g, const PrimitiveView& p) {
    return {g.grids.empty() ? nullptr : g.grids.data(), g.cells.data(), g.items.data(), p};
}

size_t bytesOf(const Bvh2& b) { return b.nodes.size() * sizeof(Bvh2Node) + b.items.size() * sizeof(uint32_t); }
size_t bytesOf(const SkipTree& s) { return s.nodes.size() * sizeof(SkipNode) + s.items.size() * sizeof(uint32_t); }
size_t bytesOf(const KdTree& k) { return k.nodes.size() * sizeof(KdNode) + k.items.size() * sizeof(uint32_t); }
size_t bytesOf(const Grid& g) {
    return g.grids.size() * sizeof(GridLevel) + g.cells.size() * sizeof(GridCell) + g.items.size() * sizeof(uint32_t);
}

double referencesPerItem(size_t references, const PrimitiveTable& table) {
    return table.size() ? double(references) / double(table.size()) : 0.0;
}

std::string shapeOf(const Bvh2& b, const PrimitiveTable& t) {
    return fmt::format("{} nodes, {} leaves, depth {}, {:.2f} references per primitive", b.nodes.size(), b.leaves,
                       b.depth, referencesPerItem(b.items.size(), t));
}
std::string shapeOf(const SkipTree& s, const PrimitiveTable& t) {
    return fmt::format("{} nodes in depth-first order with miss links, {:.2f} references per primitive", s.nodes.size(),
                       referencesPerItem(s.items.size(), t));
}
std::string shapeOf(const KdTree& k, const PrimitiveTable& t) {
    return fmt::format("{} nodes, {} leaves ({} empty), depth {}, {:.2f} references per primitive", k.nodes.size(),
                       k.leaves, k.emptyLeaves, k.depth, referencesPerItem(k.items.size(), t));
}
std::string shapeOf(const Grid& g, const PrimitiveTable& t) {
    const GridLevel& top = g.grids.front();
    return fmt::format("{} levels, top {}x{}x{}, {} grids, {} cells ({:.0f}% empty), {:.2f} references per primitive",
                       g.levels, top.res[0], top.res[1], top.res[2], g.grids.size(), g.cells.size(),
                       g.cells.empty() ? 0.0 : 100.0 * double(g.emptyCells) / double(g.cells.size()),
                       referencesPerItem(g.items.size(), t));
}

template <class Data>
class CourseStructureOf final : public CourseStructure {
public:
    template <class Build>
    CourseStructureOf(std::shared_ptr<const SceneGeometry> geometry, std::string name, Build&& build)
        : CourseStructure(geometry), name_(std::move(name)), started_(std::chrono::steady_clock::now()), table_(*geometry) {
        data_ = build(table_);
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
        view_ = viewOf(data_, table_.view());
    }

    std::string name() const override { return name_; }
    double buildSeconds() const override { return seconds_; }
    size_t bytes() const override { return bytesOf(data_) + table_.bytes(); }
    std::string summary() const override {
        if (table_.size() == 0) return name_ + ": empty";
        return fmt::format("{}: {}, {:.1f} bytes/primitive, build {:.1f} ms", name_, shapeOf(data_, table_),
                           double(bytes()) / double(table_.size()), seconds_ * 1e3);
    }
    void trace(Isa isa, const Ray* rays, size_t count, Hit* hits, uint8_t* occluded, TraversalCost* costs) const override {
        const auto kernel = courseKernels(isa).of<decltype(view_)>();
        if (hits) kernel.intersect(view_, rays, hits, count, costs);
        else kernel.occluded(view_, rays, occluded, count, costs);
    }

private:
    std::string name_;
    std::chrono::steady_clock::time_point started_;  ///< the build's time includes the table's
    PrimitiveTable table_;
    Data data_;
    double seconds_ = 0;
    decltype(viewOf(std::declval<Data>(), PrimitiveView{})) view_;
};

class CourseTracer final : public Tracer {
public:
    CourseTracer(std::shared_ptr<const CourseStructure> structure, Isa isa)
        : structure_(std::move(structure)), isa_(isa) {}

    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence, TraversalCost* costs) const override {
        structure_->trace(isa_, rays.data(), rays.size(), hits.data(), nullptr, costs);
    }
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence, int) const override {
        structure_->trace(isa_, rays.data(), rays.size(), nullptr, occluded.data(), nullptr);
    }
    const SceneGeometry& geometry() const override { return structure_->geometry(); }
    std::string description() const override { return structure_->name() + " single " + isaName(isa_); }

private:
    std::shared_ptr<const CourseStructure> structure_;
    Isa isa_;
};

template <class Data, class Build>
std::shared_ptr<const Structure> make(std::shared_ptr<const SceneGeometry> geometry, const StructureOptions& options,
                                      const char* name, Build build) {
    if (!options.quality.empty() && options.quality != "fast")
        throw InputError("--quality", "", std::string(name) + " has one build quality (fast); high is for bvh4, bvh8 and bvh16");
    return std::make_shared<const CourseStructureOf<Data>>(std::move(geometry), name, build);
}

} // namespace

std::unique_ptr<Tracer> CourseStructure::tracer(const KernelChoice& choice) const {
    if (choice.kernel != "auto" && choice.kernel != "single")
        throw InputError("--kernel", "", name() + " is traced one ray at a time: kernel auto or single, not '" +
                                             choice.kernel + "'");
    return std::make_unique<CourseTracer>(std::static_pointer_cast<const CourseStructure>(shared_from_this()),
                                          chosenIsa(choice));
}

std::shared_ptr<const Structure> buildBvh2(std::shared_ptr<const SceneGeometry> geometry, const StructureOptions& options) {
    return make<Bvh2>(std::move(geometry), options, "BVH2", [](const PrimitiveTable& t) { return buildBvh2(t); });
}

std::shared_ptr<const Structure> buildSkipBvh(std::shared_ptr<const SceneGeometry> geometry, const StructureOptions& options) {
    return make<SkipTree>(std::move(geometry), options, "skip BVH",
                          [](const PrimitiveTable& t) { return threadBvh2(buildBvh2(t)); });
}

std::shared_ptr<const Structure> buildKdTreeStructure(std::shared_ptr<const SceneGeometry> geometry,
                                                      const StructureOptions& options) {
    return make<KdTree>(std::move(geometry), options, "kd-tree", [](const PrimitiveTable& t) { return buildKdTree(t); });
}

std::shared_ptr<const Structure> buildUniformGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                  const StructureOptions& options) {
    return make<Grid>(std::move(geometry), options, "uniform grid",
                      [](const PrimitiveTable& t) { return buildGrid(t, uniformGridConfig()); });
}

std::shared_ptr<const Structure> buildHierarchicalGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                       const StructureOptions& options) {
    return make<Grid>(std::move(geometry), options, "hierarchical grid",
                      [](const PrimitiveTable& t) { return buildGrid(t, hierarchicalGridConfig()); });
}

std::shared_ptr<const Structure> buildRecursiveGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                    const StructureOptions& options) {
    return make<Grid>(std::move(geometry), options, "recursive grid",
                      [](const PrimitiveTable& t) { return buildGrid(t, recursiveGridConfig()); });
}

} // namespace wideray
