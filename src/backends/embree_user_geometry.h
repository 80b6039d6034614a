#pragma once
// Our Geometry interface (spheres, and whatever joins them) as an Embree user geometry.
#include <cstdint>

#include <embree3/rtcore.h>

#include "core/geometry.h"

namespace wideray {

/// Attaches `geometry` to `scene` as RTC_GEOMETRY_TYPE_USER with id `geomId`. Its callbacks apply
/// our tie rule against the hit Embree holds, so equal-t hits resolve as in our kernels.
/// `geometry` must outlive the scene.
void attachUserGeometry(RTCDevice device, RTCScene scene, const UserGeometry& geometry, uint32_t geomId);

} // namespace wideray
