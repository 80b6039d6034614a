#include "backends/embree_structure.h"

#include <chrono>
#include <cstring>
#include <stdexcept>

#include <fmt/core.h>

#include "backends/embree_tracer.h"
#include "backends/embree_user_geometry.h"
#include "core/error.h"

namespace wideray {
namespace {

/// Copies of the mesh in Embree's buffers: shared buffers would tie the structure's lifetime to the
/// caller's mesh and need padding past the last vertex for Embree's 16-byte loads.
void attachTriangles(RTCDevice device, RTCScene scene, const TriangleMesh& mesh, uint32_t geomId) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    void* vertices = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3),
                                             mesh.positions.size());
    void* indices = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3),
                                            mesh.triangles.size());
    if (vertices && indices) {
        std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
        std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, geomId);
    rtcReleaseGeometry(g);
}

} // namespace

EmbreeStructure::EmbreeStructure(std::shared_ptr<const SceneGeometry> geometry, RTCBuildQuality quality)
    : Structure(std::move(geometry)), quality_(quality) {
    device_.reset(rtcNewDevice(nullptr));
    if (!device_) throw std::runtime_error("Embree: cannot create a device");
    // Errors are recorded here and turned into exceptions by check(): throwing from inside Embree's
    // C API would unwind through frames that do not expect it.
    rtcSetDeviceErrorFunction(
        device_.get(),
        [](void* self, RTCError, const char* message) { static_cast<EmbreeStructure*>(self)->lastError_ = message; },
        this);
    rtcSetDeviceMemoryMonitorFunction(
        device_.get(),
        [](void* self, ssize_t bytes, bool) {
            static_cast<EmbreeStructure*>(self)->bytes_ += bytes;
            return true;
        },
        this);

    auto start = std::chrono::steady_clock::now();
    scene_.reset(rtcNewScene(device_.get()));
    check("rtcNewScene");
    rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(scene_.get(), quality_);
    const SceneGeometry& g = this->geometry();
    for (uint32_t geomId = 0; geomId < g.size(); ++geomId) {
        if (const TriangleMesh* mesh = g[geomId].triangles()) {
            if (!mesh->triangles.empty()) attachTriangles(device_.get(), scene_.get(), *mesh, geomId);
            check("triangle geometry");
        } else if (const InstanceGeometry* instances = g[geomId].instances()) {
            attachInstances(*instances, geomId);
        } else {
            attachUserGeometry(device_.get(), scene_.get(), *g[geomId].user(), geomId);
            check("user geometry");
        }
    }
    rtcCommitScene(scene_.get());
    check("rtcCommitScene");
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void EmbreeStructure::attachInstances(const InstanceGeometry& instances, uint32_t geomId) {
    for (const auto& mesh : instances.meshes()) {
        meshScenes_.emplace_back(rtcNewScene(device_.get()));
        rtcSetSceneBuildQuality(meshScenes_.back().get(), quality_);
        attachTriangles(device_.get(), meshScenes_.back().get(), *(*mesh)[0].triangles(), 0);
        rtcCommitScene(meshScenes_.back().get());
        check("instanced mesh");
    }
    instanceGeomId_ = geomId;
    firstInstanceId_ = geometry().size();
    for (const InstanceGeometry::Placement& p : instances.placements()) {
        RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, meshScenes_[p.mesh].get());
        rtcSetGeometryTimeStepCount(g, p.endTransform ? 2 : 1);  // Embree interpolates the matrices entry by entry, as we do
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &p.transform[0][0]);
        if (p.endTransform) rtcSetGeometryTransform(g, 1, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &(*p.endTransform)[0][0]);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene_.get(), g, firstInstanceId_ + uint32_t(instanceFirstPrim_.size()));
        rtcReleaseGeometry(g);
        instanceFirstPrim_.push_back(p.firstPrim);
    }
    check("instances");
}

void EmbreeStructure::fromInstanceHits(std::span<Hit> hits) const {
    if (instanceFirstPrim_.empty()) return;
    for (Hit& hit : hits)
        if (hit.valid() && hit.geomId >= firstInstanceId_) {
            hit.primId += instanceFirstPrim_[hit.geomId - firstInstanceId_];
            hit.geomId = instanceGeomId_;
        }
}

void EmbreeStructure::check(const char* step) const {
    if (rtcGetDeviceError(device_.get()) != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + step + ": " + lastError_);
}

const char* EmbreeStructure::qualityName() const {
    return quality_ == RTC_BUILD_QUALITY_LOW ? "low" : quality_ == RTC_BUILD_QUALITY_HIGH ? "high" : "medium";
}

std::string EmbreeStructure::summary() const {
    return fmt::format("Embree BVH ({} quality): build {:.1f} ms, {:.1f} MB", qualityName(), buildSeconds_ * 1e3,
                       double(bytes()) / 1e6);
}

std::unique_ptr<Tracer> EmbreeStructure::tracer(const KernelChoice& choice) const {
    auto self = std::static_pointer_cast<const EmbreeStructure>(shared_from_this());
    if (choice.kernel == "auto")
        return std::make_unique<EmbreeTracer>(self, widestNativeEmbreePacket(), EmbreeKernel::Intersect1);
    std::optional<EmbreeKernel> kernel = parseEmbreeKernel(choice.kernel);
    if (!kernel) throw InputError("--kernel", "", "Embree has no kernel named '" + choice.kernel + "'");
    return std::make_unique<EmbreeTracer>(self, *kernel, *kernel);
}

std::shared_ptr<const Structure> buildEmbree(std::shared_ptr<const SceneGeometry> geometry,
                                             const StructureOptions& options) {
    const std::pair<const char*, RTCBuildQuality> qualities[] = {
        {"low", RTC_BUILD_QUALITY_LOW},       {"medium", RTC_BUILD_QUALITY_MEDIUM}, {"", RTC_BUILD_QUALITY_MEDIUM},
        {"fast", RTC_BUILD_QUALITY_MEDIUM}, {"high", RTC_BUILD_QUALITY_HIGH}};
    for (const auto& [name, quality] : qualities)
        if (options.quality == name) return std::make_shared<EmbreeStructure>(std::move(geometry), quality);
    throw InputError("--quality", "", "Embree's build quality is low, medium (or fast) or high, not '" + options.quality + "'");
}

} // namespace wideray
