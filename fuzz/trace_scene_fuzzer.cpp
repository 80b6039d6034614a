// libFuzzer harness, end to end: a scene that parses is turned into geometry, its BVH is built (and
// Embree's), and a handful of camera rays are traced and shaded through both. Scenes over a small
// budget of primitives are skipped, so that one input stays fast.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "backends/backend_registry.h"
#include "core/error.h"
#include "geometry/scene_geometry.h"
#include "io/scene_parser.h"
#include "render/bench_rays.h"

namespace {

constexpr uint64_t kTriangleBudget = 200000;
constexpr size_t kPrimitiveBudget = 2000;

bool small(const wideray::SceneDescription& scene) {
    uint64_t triangles = 0;
    for (const wideray::MeshInstance& i : scene.instances) triangles += scene.meshes[i.mesh].triangles.size();
    size_t blobBalls = 0;
    for (const wideray::AnalyticObject& a : scene.analytics) blobBalls += a.balls.size();
    size_t heights = 0;
    for (const wideray::HeightField& h : scene.heightFields) heights += h.heights.size();
    return triangles <= kTriangleBudget && scene.instances.size() <= kPrimitiveBudget &&
           scene.spheres.size() + scene.analytics.size() + scene.csgs.size() <= kPrimitiveBudget &&
           blobBalls <= kPrimitiveBudget && heights <= kTriangleBudget;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace wideray;
    SceneDescription scene;
    try {
        scene = parseScene(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.json");
    } catch (const InputError&) {
        return 0;
    }
    if (!small(scene)) return 0;
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const std::vector<Ray> rays = primaryRays(scene, 8, 6);
    for (const char* backend : {"wideray", "embree"}) {
        std::unique_ptr<Tracer> tracer = findBackend(backend).build(geometry, {})->tracer({});
        std::vector<Hit> hits(rays.size());
        std::vector<uint8_t> occluded(rays.size());
        tracer->intersect(rays, hits, Coherence::Coherent);
        tracer->occluded(rays, occluded, Coherence::Incoherent);
        for (size_t i = 0; i < rays.size(); ++i)
            if (hits[i].valid()) (void)geometry->surface(rays[i], hits[i]);
    }
    return 0;
}
