#pragma once
// The kernels of the course's structures (binary and skip-pointer BVHs, kd-tree, grids): one ray at a
// time, one table per ISA like the wide BVH's kernels (kernels/kernel_registry.h), so that each
// returns the hits of the scalar reference of the same ISA bit for bit.
#include <cstddef>
#include <cstdint>

#include "accel/course_views.h"
#include "core/ray.h"
#include "simd/cpu_features.h"

namespace wideray {

template <class View>
struct ViewKernel {
    void (*intersect)(const View&, const Ray*, Hit*, size_t, TraversalCost*) = nullptr;
    void (*occluded)(const View&, const Ray*, uint8_t*, size_t, TraversalCost*) = nullptr;
};

struct CourseKernels {
    ViewKernel<Bvh2View> bvh2;
    ViewKernel<SkipView> skip;
    ViewKernel<KdTreeView> kdtree;
    ViewKernel<GridView> grid;  ///< uniform, hierarchical and recursive grids alike

    template <class View>
    const ViewKernel<View>& of() const;
};

template <> inline const ViewKernel<Bvh2View>& CourseKernels::of() const { return bvh2; }
template <> inline const ViewKernel<SkipView>& CourseKernels::of() const { return skip; }
template <> inline const ViewKernel<KdTreeView>& CourseKernels::of() const { return kdtree; }
template <> inline const ViewKernel<GridView>& CourseKernels::of() const { return grid; }

CourseKernels sse42CourseKernels();
CourseKernels avx2CourseKernels();
CourseKernels avx512CourseKernels();

/// The kernels of an ISA; the caller checks cpuSupports(isa) first.
inline CourseKernels courseKernels(Isa isa) {
    switch (isa) {
    case Isa::Avx512: return avx512CourseKernels();
    case Isa::Avx2: return avx2CourseKernels();
    case Isa::Sse42: break;
    }
    return sse42CourseKernels();
}

} // namespace wideray
