#pragma once
// Renders for the tests: through the scalar reference, on a given number of threads.
#include <tbb/global_control.h>

#include "core/fp_mode.h"
#include "render/renderer.h"
#include "backends/tracer_factory.h"

namespace wideray {

inline Image renderWithReference(const Scene& scene, int threads, const RenderOptions& options,
                                 RenderStats* statsOut = nullptr) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    FlushToZeroScope ftz;
    TriangleMesh world = flattenTriangles(scene);
    TracerConfig config;
    config.kernel = KernelChoice::Scalar;
    BuiltTracer built = buildWiderayTracer(scene, world, config);
    RenderStats stats;
    Image image = render(scene, world, *built.tracer, options, stats);
    if (statsOut) *statsOut = stats;
    return image;
}

} // namespace wideray
