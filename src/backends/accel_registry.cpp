#include "backends/accel_registry.h"

#include "backends/course_structure.h"
#include "backends/wideray_structure.h"
#include "backends/find_by_name.h"

namespace wideray {
namespace {

template <int N>
std::shared_ptr<const Structure> buildBvhOfWidth(std::shared_ptr<const SceneGeometry> geometry,
                                                 const StructureOptions& options) {
    StructureOptions o = options;
    o.bvhWidth = N;
    return buildWideBvh(std::move(geometry), o);
}

constexpr Accel kAccels[] = {
    {"bvh8", "our wide BVH, 8 children per node, every kernel (the default)", &buildBvhOfWidth<8>, true},
    {"bvh4", "our wide BVH, 4 children per node, every kernel", &buildBvhOfWidth<4>, true},
    {"bvh16", "our wide BVH, 16 children per node (one AVX-512 box test), every kernel but drst",
     &buildBvhOfWidth<16>, true},
    {"bvh2", "binary SAH BVH, stack traversal nearest child first", &buildBvh2},
    {"skip", "the binary BVH in depth-first order with miss links, stackless traversal", &buildSkipBvh},
    {"kdtree", "SAH kd-tree (Wald and Havran 2006) with split clipping, front-to-back traversal", &buildKdTreeStructure},
    {"grid", "uniform grid, about 8 cells per primitive, 3D-DDA with mailboxing", &buildUniformGrid},
    {"hgrid", "hierarchical grid: about 2 cells per primitive, a finer grid in each cell of more than 16",
     &buildHierarchicalGrid},
    {"rgrid", "recursive grid: a coarse grid, crowded cells refined again, up to 5 levels", &buildRecursiveGrid},
};

} // namespace

std::span<const Accel> accels() { return kAccels; }

const Accel& findAccel(std::string_view name) {
    return findByName(accels(), name, "--accel", "acceleration structure");
}

bool isWideBvh(std::string_view name) { return findAccel(name).wideBvh; }

std::shared_ptr<const Structure> buildWideray(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options) {
    if (options.accel.empty()) return buildWideBvh(std::move(geometry), options);
    return findAccel(options.accel).build(std::move(geometry), options);
}

} // namespace wideray
