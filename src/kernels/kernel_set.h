#pragma once
// A traversal kernel as a pair of function pointers, chosen once per tracer (never per ray).
#include <cstddef>
#include <cstdint>

#include "core/bvh_view.h"
#include "core/ray.h"

namespace wideray {

template <int N>
struct KernelSet {
    using IntersectFn = void (*)(const SceneView<N>&, const Ray*, Hit*, size_t, TraversalCost*);
    using OccludedFn = void (*)(const SceneView<N>&, const Ray*, uint8_t*, size_t);
    const char* name = "";
    IntersectFn intersect = nullptr;
    OccludedFn occluded = nullptr;
};

} // namespace wideray
