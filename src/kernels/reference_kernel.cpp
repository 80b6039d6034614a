#include "kernels/reference_kernel.h"

#include "kernels/traverse_single.h"

namespace wideray::reference {

template <int N>
void intersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        traceSingle<N, 1, 1, false>(scene, rays[i], hit, cost);
        hits[i] = hit.valid() ? hit : Hit{};
        if (costs) costs[i] = cost;
    }
}

template <int N>
void occluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        occluded[i] = traceSingle<N, 1, 1, true>(scene, rays[i], hit, cost) ? 1 : 0;
    }
}

template void intersect<4>(const SceneView<4>&, const Ray*, Hit*, size_t, TraversalCost*);
template void intersect<8>(const SceneView<8>&, const Ray*, Hit*, size_t, TraversalCost*);
template void occluded<4>(const SceneView<4>&, const Ray*, uint8_t*, size_t);
template void occluded<8>(const SceneView<8>&, const Ray*, uint8_t*, size_t);

} // namespace wideray::reference
