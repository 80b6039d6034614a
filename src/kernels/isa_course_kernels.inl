// The course structures' kernels of one ISA, compiled from the same source for each: a translation
// unit in kernels/isa/ defines WIDERAY_ISA and WIDERAY_ISA_COURSE_KERNELS (the table's name) and
// includes this file with its ISA's compiler flags.
#include "kernels/course_kernels.h"
#include "kernels/traverse_grid.h"
#include "kernels/traverse_kdtree.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace {

template <bool AnyHit> bool traceView(const Bvh2View& v, const Ray& r, Hit& h, TraversalCost& c) { return traceBvh2<AnyHit>(v, r, h, c); }
template <bool AnyHit> bool traceView(const SkipView& v, const Ray& r, Hit& h, TraversalCost& c) { return traceSkip<AnyHit>(v, r, h, c); }
template <bool AnyHit> bool traceView(const KdTreeView& v, const Ray& r, Hit& h, TraversalCost& c) { return traceKdTree<AnyHit>(v, r, h, c); }
template <bool AnyHit> bool traceView(const GridView& v, const Ray& r, Hit& h, TraversalCost& c) { return traceGrid<AnyHit>(v, r, h, c); }

template <class View>
void viewIntersect(const View& view, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        traceView<false>(view, rays[i], hit, cost);
        hits[i] = hit.valid() ? hit : Hit{};
        if (costs) costs[i] = cost;
    }
}

template <class View>
void viewOccluded(const View& view, const Ray* rays, uint8_t* occluded, size_t count, TraversalCost* costs) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        occluded[i] = traceView<true>(view, rays[i], hit, cost) ? 1 : 0;
        if (costs) costs[i] = cost;
    }
}

template <class View>
ViewKernel<View> viewKernel() {
    return {&viewIntersect<View>, &viewOccluded<View>};
}

} // namespace
} // namespace WIDERAY_ISA

CourseKernels WIDERAY_ISA_COURSE_KERNELS() {
    return {viewKernel<Bvh2View>(), viewKernel<SkipView>(), viewKernel<KdTreeView>(), viewKernel<GridView>()};
}

} // namespace wideray
