#pragma once
// Intel Embree 3 as a backend: the scene's geometry in an Embree scene at one build quality, so that
// the renderer, the tests and the benchmarks trace the same rays through Embree and through our
// kernels and compare answers and speed.
//
// The scene maps onto Embree so that hits come back with our ids: each triangle geometry becomes an
// RTC_GEOMETRY_TYPE_TRIANGLE geometry with the same geomId holding its triangles in their order, so
// Embree's primID is our primId and its (u, v) weight the second and third vertex as ours do; each
// user geometry becomes an RTC_GEOMETRY_TYPE_USER geometry whose bounds, intersect and occluded
// callbacks call ours, with our tie rule (equal t: smaller (geomId, primId) wins) applied against
// Embree's hit. Embree's triangle test is not watertight and does not order equal-t hits, so answers
// differ from ours at shared edges and vertices (tests/test_embree_crosscheck.cpp counts these).
// Two-level instances become one Embree scene per instanced mesh, placed by an
// RTC_GEOMETRY_TYPE_INSTANCE geometry per instance (geomIDs after ours), whose hits are given our
// ids (the instance geometry's geomId, the flattened primId) by fromInstanceHits.
#include <algorithm>
#include <atomic>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "backends/backend_registry.h"
#include "backends/structure.h"

namespace wideray {

class EmbreeStructure final : public Structure {
public:
    /// Throws std::runtime_error with Embree's message when Embree reports an error.
    EmbreeStructure(std::shared_ptr<const SceneGeometry> geometry, RTCBuildQuality quality);

    RTCScene scene() const { return scene_.get(); }
    RTCBuildQuality quality() const { return quality_; }
    /// "low", "medium" or "high".
    const char* qualityName() const;

    std::string name() const override { return "Embree BVH"; }
    /// Geometry set-up and rtcCommitScene.
    double buildSeconds() const override { return buildSeconds_; }
    /// Bytes Embree holds for the scene (vertex and index copies, BVH), from its memory monitor.
    size_t bytes() const override { return size_t(std::max<int64_t>(0, bytes_.load())); }
    std::string summary() const override;
    /// kernel "auto": the widest packet this CPU runs natively for coherent rays, rtcIntersect1 for
    /// incoherent ones; or one entry point by name (rtcIntersect1, 4, 8, 16, rtcIntersect1M).
    std::unique_ptr<Tracer> tracer(const KernelChoice& choice) const override;

    /// Whether the scene has two-level instances. Embree 3.13.5's rtcOccluded16 does not return on
    /// some shadow rays through instances on this AVX-512 machine (measured: scenes/bunny_field.json),
    /// so its tracers occlude 16-wide packets as two of 8 there.
    bool instanced() const { return !instanceFirstPrim_.empty(); }
    /// Hits of instances (geomId: the instance's geomID in Embree's scene) with our geomId and primId.
    void fromInstanceHits(std::span<Hit> hits) const;

private:
    struct ReleaseDevice {
        void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
    };
    struct ReleaseScene {
        void operator()(RTCScene s) const { rtcReleaseScene(s); }
    };

    void check(const char* step) const;
    void attachInstances(const InstanceGeometry& instances, uint32_t geomId);

    std::atomic<int64_t> bytes_{0};
    std::string lastError_;
    std::unique_ptr<RTCDeviceTy, ReleaseDevice> device_;
    std::unique_ptr<RTCSceneTy, ReleaseScene> scene_;
    std::vector<std::unique_ptr<RTCSceneTy, ReleaseScene>> meshScenes_;  ///< one per instanced mesh
    uint32_t instanceGeomId_ = kInvalidId, firstInstanceId_ = 0;
    std::vector<uint32_t> instanceFirstPrim_;
    RTCBuildQuality quality_;
    double buildSeconds_ = 0;
};

/// The backend row's build function (options.quality: low, medium or high).
std::shared_ptr<const Structure> buildEmbree(std::shared_ptr<const SceneGeometry> geometry,
                                             const StructureOptions& options);

} // namespace wideray
