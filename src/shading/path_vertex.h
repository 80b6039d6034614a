#pragma once
// What happens where a path of the path tracer (render.integrator "path") meets a surface:
// unidirectional path tracing with next-event estimation (Kajiya 1986; Veach 1997, ch. 9; Pharr,
// Jakob and Humphreys, "Physically Based Rendering", 3rd ed., 14.5). At diffuse, plastic and rough
// conductor surfaces every light is sampled (a shadow ray per sample), area-light samples weighted
// against the material's own sampling by the balance heuristic, and the path goes on in one direction
// sampled from the material: cosine-weighted for diffuse, a mixture of cosine and Blinn-Phong
// half-vector sampling for plastic, the glossy lobe for conductors. Mirrors, smooth conductors and
// dielectrics (reflection or refraction chosen by their Fresnel reflectance) take no light samples:
// what their paths reach of an area light counts in full. Russian roulette from the third bounce for paths that carry less than they started with;
// paths end after render.max_depth scattering events. Polarization is tracked through Fresnel events
// as in the Whitted integrator; diffuse and plastic surfaces depolarize.
#include "core/geometry.h"
#include "core/random.h"
#include "shading/path_state.h"
#include "shading/surface_scattering.h"

namespace wideray {

/// The balance heuristic's weight of a strategy with density `pdf` against one with `other`.
inline float balanceHeuristic(float pdf, float other) { return pdf / (pdf + other); }

/// Shades the surface `sp` that `path` (its ray of unit direction) has reached, its throughput
/// already including the segment's attenuation: shadow samples for the lights, and the path's
/// continuation unless it ends here.
void scatterPathVertex(const ShadingContext& context, const PathState& path, const SurfacePoint& sp, SampleRng& rng,
                       ScatterOutput& out);

} // namespace wideray
