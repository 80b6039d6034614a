#pragma once
// Intel Embree 3 behind our Tracer interface, so that the renderer, the tests and the benchmarks
// trace the same rays through Embree and through our kernels and compare answers and speed.
//
// The scene maps onto Embree so that hits come back with our ids:
//   geomID 0: one RTC_GEOMETRY_TYPE_TRIANGLE geometry holding the flattened world triangles in
//             their order, so Embree's primID is our primId and its (u, v) weight the second and
//             third vertex as ours do;
//   geomID 1: when the scene has spheres, one RTC_GEOMETRY_TYPE_USER geometry whose bounds,
//             intersect and occluded callbacks call our Geometry (userGeometries(scene)[1]), with
//             our tie rule (equal t: smaller (geomId, primId) wins) applied against Embree's hit.
// Embree's triangle test is not watertight and does not order equal-t hits, so answers differ
// from ours at shared edges and vertices (tests/test_embree_crosscheck.cpp counts these).
#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "core/scene.h"
#include "backends/tracer.h"

namespace wideray {

/// Which Embree entry point traces a batch: one ray at a time, SoA packets of K, or a ray stream.
enum class EmbreeKernel { Intersect1, Packet4, Packet8, Packet16, Stream1M };

/// The entry point's name, e.g. "rtcIntersect16" ("rtcOccluded16" for the same kernel's shadow rays).
const char* embreeKernelName(EmbreeKernel kernel);

struct EmbreeConfig {
    RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;  ///< Embree's default and its advice for most uses
    std::optional<EmbreeKernel> coherent;    ///< nullopt: the widest packet this CPU runs natively
    EmbreeKernel incoherent = EmbreeKernel::Intersect1;
};

class EmbreeTracer final : public Tracer {
public:
    /// Throws std::runtime_error with Embree's message when Embree reports an error, and InputError
    /// when the configuration asks for a kernel this Embree build cannot run.
    EmbreeTracer(const Scene& scene, const TriangleMesh& world, const EmbreeConfig& config = {});

    /// Embree reports no traversal work: `costs`, when given, is filled with zeros.
    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                   TraversalCost* costs = nullptr) const override;
    /// Embree keeps no shadow cache: `depth` is ignored.
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                  int depth = -1) const override;
    const Geometry& geometry(uint32_t geomId) const override { return *geometries_[geomId]; }
    std::string description() const override;

    /// Geometry set-up and rtcCommitScene.
    double buildSeconds() const { return buildSeconds_; }
    /// Bytes Embree holds for the scene (vertex and index copies, BVH), from its memory monitor.
    size_t bytes() const { return size_t(std::max<int64_t>(0, bytes_.load())); }

    /// Whether this CPU and Embree build run the kernel (packets natively, streams at all).
    static bool supports(EmbreeKernel kernel);

private:
    struct ReleaseDevice {
        void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
    };
    struct ReleaseScene {
        void operator()(RTCScene s) const { rtcReleaseScene(s); }
    };

    void check(const char* step) const;
    EmbreeKernel kernel(Coherence c) const { return c == Coherence::Coherent ? coherent_ : incoherent_; }

    // Declared before the device and the scene: Embree's callbacks use them until both are released.
    std::vector<std::unique_ptr<Geometry>> geometries_;
    std::atomic<int64_t> bytes_{0};
    std::string lastError_;
    std::unique_ptr<RTCDeviceTy, ReleaseDevice> device_;
    std::unique_ptr<RTCSceneTy, ReleaseScene> scene_;
    EmbreeKernel coherent_ = EmbreeKernel::Intersect1, incoherent_ = EmbreeKernel::Intersect1;
    RTCBuildQuality quality_ = RTC_BUILD_QUALITY_MEDIUM;
    double buildSeconds_ = 0;
};

} // namespace wideray
