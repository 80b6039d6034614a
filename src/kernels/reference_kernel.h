#pragma once
// The scalar single-ray reference: plain loops over children and triangles, compiled with the
// baseline ISA. Every other kernel must reproduce its answers exactly.
#include <cstddef>
#include <cstdint>

#include "accel/bvh_view.h"
#include "core/ray.h"

namespace wideray::reference {

template <int N>
void intersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs);
template <int N>
void occluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count);

} // namespace wideray::reference
