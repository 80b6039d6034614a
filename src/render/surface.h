#pragma once
// The surface at a hit: position, normals, uv and material, for triangles and user geometry alike.
#include "core/geometry.h"
#include "core/mesh.h"
#include "backends/tracer.h"

namespace wideray {

SurfacePoint surfaceAt(const TriangleMesh& world, const Tracer& tracer, const Ray& ray, const Hit& hit);

} // namespace wideray
