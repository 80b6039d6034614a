// The public Scene (include/wideray/scene.h) over the engine: what is added becomes a
// SceneDescription (each mesh placed by an instance), build() makes its SceneGeometry and wide BVH
// (backends/wideray_structure.h) and a tracer per kind of call, and every hit is translated from the
// engine's ids (geomId of a geometry kind, primId in the flattened form) to the caller's.
#include "wideray/scene.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include "api/mxcsr_scope.h"
#include "backends/wideray_structure.h"
#include "core/error.h"
#include "core/scene.h"
#include "geometry/instance_geometry.h"
#include "geometry/sphere_geometry.h"
#include "geometry/triangle_geometry.h"
#include "kernels/kernel_registry.h"

namespace wideray {
namespace {

/// Rays per task when a stream is traced in parallel, as the renderer and bench hand them out.
constexpr size_t kRaysPerTask = 4096;

/// The option an engine error names (its "file" is the CLI flag) in the API's words.
[[noreturn]] void rethrow(const InputError& e) {
    std::string where = e.file();
    for (const auto& [flag, field] : {std::pair{"--kernel", "SceneOptions::kernel"}, {"--isa", "SceneOptions::isa"},
                                      {"--bvh-width", "SceneOptions::bvhWidth"}})
        if (where == flag) where = field;
    throw Error(where + ": " + e.message());
}

bool mirrors(const glm::mat4& m) { return glm::determinant(glm::mat3(m)) < 0.0f; }

} // namespace

struct Scene::Impl {
    SceneOptions options;
    SceneDescription description;
    /// Meshes added with Sharing::Shared: the caller's arrays, read by build().
    struct SharedMesh {
        uint32_t mesh;
        std::span<const float> positions;
        std::span<const uint32_t> indices;
    };
    std::vector<SharedMesh> shared;
    std::vector<uint32_t> meshGeomIds;       ///< per mesh of the description: the geomId addTriangleMesh gave it
    std::vector<uint32_t> instanceGeomIds;   ///< per instance of the description
    struct SphereSet {
        uint32_t first, geomId;
    };
    std::vector<SphereSet> sphereSets;       ///< in the order of description.spheres
    uint32_t nextGeomId = 0;

    // What build() made; null until then, and again after an addition.
    std::shared_ptr<const Structure> structure;
    std::unique_ptr<Tracer> single, packet4, packet8, packet16, streams;
    /// Per engine geomId: what kind of geometry it is.
    enum class Kind { Triangles, Instances, Spheres };
    std::vector<Kind> kinds;
    std::vector<uint8_t> flattenedMirrored;  ///< per description instance: flattened with its vertex order reversed

    void invalidate() { structure.reset(); }
    const Tracer& ready(const std::unique_ptr<Tracer>& tracer) const {
        if (!structure) throw Error("wideray::Scene: build() the scene before tracing it (and again after adding to it)");
        return *tracer;
    }
    std::unique_ptr<Tracer> makeTracer(std::initializer_list<const char*> kernels) const;
    void toCallerIds(Hit& hit) const;
};

std::unique_ptr<Tracer> Scene::Impl::makeTracer(std::initializer_list<const char*> kernels) const {
    std::optional<Isa> isa;
    if (!options.isa.empty()) {
        isa = parseIsa(options.isa);
        if (!isa) throw Error("SceneOptions::isa: '" + options.isa + "' is not one of sse42, avx2, avx512");
    }
    try {
        if (!options.kernel.empty()) return structure->tracer(KernelChoice(options.kernel, isa));
        // The first kernel of the list that the ISA runs (16-wide packets need AVX-512; on AVX2 two
        // 8-wide packets trace them).
        const Isa chosen = chosenIsa(KernelChoice("auto", isa));
        for (const char* name : kernels)
            if (std::string_view(name) == "auto" || kernelTable<8>(chosen).find(name)->available())
                return structure->tracer(KernelChoice(name, isa));
    } catch (const InputError& e) {
        rethrow(e);
    }
    return structure->tracer(KernelChoice("single", isa));
}

void Scene::Impl::toCallerIds(Hit& hit) const {
    if (!hit.valid()) return;
    const Geometry& g = structure->geometry()[hit.geomId];
    switch (kinds[hit.geomId]) {
    case Kind::Triangles: {
        const auto& triangles = static_cast<const TriangleGeometry&>(g);
        const uint32_t instance = triangles.instanceOf(hit.primId);
        hit.primId -= triangles.instanceFirstPrim(hit.primId);
        // A mirrored instance was flattened with two vertices swapped; u and v follow the caller's order.
        if (flattenedMirrored[instance]) std::swap(hit.u, hit.v);
        hit.geomId = instanceGeomIds[instance];
        break;
    }
    case Kind::Instances: {
        const InstanceGeometry::Placement& p = g.instances()->placements()[g.instances()->instanceOf(hit.primId)];
        hit.primId -= p.firstPrim;
        hit.geomId = instanceGeomIds[p.sceneInstance];
        break;
    }
    case Kind::Spheres: {
        auto set = std::upper_bound(sphereSets.begin(), sphereSets.end(), hit.primId,
                                    [](uint32_t prim, const SphereSet& s) { return prim < s.first; }) - 1;
        hit.primId -= set->first;
        hit.geomId = set->geomId;
        break;
    }
    }
}

Scene::Scene(const SceneOptions& options) : impl_(std::make_unique<Impl>()) {
    if (options.bvhWidth != 4 && options.bvhWidth != 8 && options.bvhWidth != 16)
        throw Error(fmt::format("SceneOptions::bvhWidth: must be 4, 8 or 16, not {}", options.bvhWidth));
    impl_->options = options;
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

namespace {

/// Throws naming `where` (the call, or the build and the shared mesh it reads) unless the arrays are a mesh.
void checkMesh(std::span<const float> positions, std::span<const uint32_t> indices, std::string_view where) {
    if (positions.size() % 3 != 0)
        throw Error(fmt::format("{}: positions holds {} floats, not 3 per vertex", where, positions.size()));
    if (indices.size() % 3 != 0)
        throw Error(fmt::format("{}: indices holds {} values, not 3 per triangle", where, indices.size()));
    const size_t vertices = positions.size() / 3;
    if (vertices > kInvalidId || indices.size() / 3 > kInvalidId)
        throw Error(fmt::format("{}: more than 2^32 - 1 vertices or triangles", where));
    for (size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i]))
            throw Error(fmt::format("{}: positions[{}] (vertex {}) is {}", where, i, i / 3, positions[i]));
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= vertices)
            throw Error(fmt::format("{}: indices[{}] (triangle {}) is {}, but the mesh has {} vertices", where, i,
                                    i / 3, indices[i], vertices));
}

TriangleMesh copyMesh(std::span<const float> positions, std::span<const uint32_t> indices) {
    TriangleMesh mesh;
    mesh.positions.resize(positions.size() / 3);
    std::copy(positions.begin(), positions.end(), &mesh.positions.data()->x);
    mesh.triangles.resize(indices.size() / 3);
    std::copy(indices.begin(), indices.end(), &mesh.triangles.data()->x);
    return mesh;
}

} // namespace

uint32_t Scene::addTriangleMesh(std::span<const float> positions, std::span<const uint32_t> indices, Sharing sharing) {
    checkMesh(positions, indices, "addTriangleMesh");
    Impl& s = *impl_;
    const uint32_t mesh = uint32_t(s.description.meshes.size());
    if (sharing == Sharing::Copy) {
        s.description.meshes.push_back(copyMesh(positions, indices));
    } else {
        s.description.meshes.emplace_back();
        s.shared.push_back({mesh, positions, indices});
    }
    const uint32_t geomId = s.nextGeomId++;
    s.meshGeomIds.push_back(geomId);
    s.description.instances.push_back({mesh, glm::mat4(1.0f)});
    s.instanceGeomIds.push_back(geomId);
    s.invalidate();
    return geomId;
}

uint32_t Scene::addInstance(uint32_t meshId, const Transform& transform) {
    Impl& s = *impl_;
    const auto mesh = std::find(s.meshGeomIds.begin(), s.meshGeomIds.end(), meshId);
    if (mesh == s.meshGeomIds.end())
        throw Error(fmt::format("addInstance: geomId {} is not a mesh of this scene (addTriangleMesh's ids are)", meshId));
    glm::mat4 m(1.0f);
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) {
            if (!std::isfinite(transform.m[row][col]))
                throw Error(fmt::format("addInstance: transform.m[{}][{}] is {}", row, col, transform.m[row][col]));
            m[col][row] = transform.m[row][col];  // glm is column-major
        }
    if (glm::determinant(glm::mat3(m)) == 0.0f) throw Error("addInstance: the transform is singular");
    const uint32_t geomId = s.nextGeomId++;
    s.description.instances.push_back({uint32_t(mesh - s.meshGeomIds.begin()), m});
    s.instanceGeomIds.push_back(geomId);
    s.invalidate();
    return geomId;
}

uint32_t Scene::addSpheres(std::span<const float> centers, std::span<const float> radii) {
    if (centers.size() != 3 * radii.size())
        throw Error(fmt::format("addSpheres: {} center coordinates for {} radii (3 per sphere)", centers.size(),
                                radii.size()));
    if (radii.empty()) throw Error("addSpheres: no spheres");
    for (size_t i = 0; i < centers.size(); ++i)
        if (!std::isfinite(centers[i])) throw Error(fmt::format("addSpheres: centers[{}] is {}", i, centers[i]));
    for (size_t i = 0; i < radii.size(); ++i)
        if (!(radii[i] > 0.0f) || !std::isfinite(radii[i]))
            throw Error(fmt::format("addSpheres: radii[{}] is {}; radii are positive and finite", i, radii[i]));
    Impl& s = *impl_;
    const uint32_t geomId = s.nextGeomId++;
    s.sphereSets.push_back({uint32_t(s.description.spheres.size()), geomId});
    for (size_t i = 0; i < radii.size(); ++i)
        s.description.spheres.push_back({{centers[3 * i], centers[3 * i + 1], centers[3 * i + 2]}, radii[i], 0});
    s.invalidate();
    return geomId;
}

void Scene::build() {
    Impl& s = *impl_;
    s.invalidate();
    std::shared_ptr<const Structure> structure;
    try {
        MxcsrScope mode;
        // Shared arrays are read at every build; the caller may have changed them since they were added.
        for (const Impl::SharedMesh& m : s.shared) {
            checkMesh(m.positions, m.indices, fmt::format("build: shared mesh (geomId {})", s.meshGeomIds[m.mesh]));
            s.description.meshes[m.mesh] = copyMesh(m.positions, m.indices);
        }
        auto geometry = std::make_shared<const SceneGeometry>(s.description, Instancing::Auto);
        // The engine's copy is all it needs until the next build.
        for (const Impl::SharedMesh& m : s.shared) s.description.meshes[m.mesh] = TriangleMesh{};

        const std::vector<bool> twoLevel = twoLevelMeshes(s.description, Instancing::Auto);
        s.flattenedMirrored.assign(s.description.instances.size(), 0);
        for (size_t i = 0; i < s.description.instances.size(); ++i)
            s.flattenedMirrored[i] = !twoLevel[s.description.instances[i].mesh] && mirrors(s.description.instances[i].transform);
        s.kinds.clear();
        for (uint32_t g = 0; g < geometry->size(); ++g) {
            const Geometry& geom = (*geometry)[g];
            s.kinds.push_back(geom.instances() ? Impl::Kind::Instances
                              : dynamic_cast<const SphereGeometry*>(&geom) ? Impl::Kind::Spheres
                                                                            : Impl::Kind::Triangles);
        }

        StructureOptions structureOptions;
        structureOptions.bvhWidth = s.options.bvhWidth;
        structureOptions.quality = s.options.quality == BuildQuality::High ? "high" : "fast";
        structure = buildWideBvh(std::move(geometry), structureOptions);
    } catch (const InputError& e) {
        rethrow(e);
    } catch (const std::length_error& e) {  // more primitives than the structure can address
        throw Error(std::string("build: ") + e.what());
    } catch (const std::bad_alloc&) {
        throw Error("build: out of memory");
    }
    s.structure = structure;
    try {
        s.single = s.makeTracer({"single"});
        s.packet4 = s.makeTracer({"packet4", "single"});
        s.packet8 = s.makeTracer({"packet8", "packet4", "single"});
        s.packet16 = s.makeTracer({"packet16", "packet8", "packet4", "single"});
        s.streams = s.makeTracer({"auto"});
    } catch (...) {
        s.invalidate();
        throw;
    }
}

bool Scene::built() const { return impl_->structure != nullptr; }

Hit Scene::intersect(const Ray& ray) const {
    const Tracer& tracer = impl_->ready(impl_->single);
    Hit hit;
    {
        MxcsrScope mode;
        tracer.intersect({&ray, 1}, {&hit, 1}, Coherence::Incoherent);
    }
    impl_->toCallerIds(hit);
    return hit;
}

bool Scene::occluded(const Ray& ray) const {
    const Tracer& tracer = impl_->ready(impl_->single);
    uint8_t occluded = 0;
    MxcsrScope mode;
    tracer.occluded({&ray, 1}, {&occluded, 1}, Coherence::Incoherent);
    return occluded != 0;
}

namespace {

/// The packet's lanes as rays; lanes not valid get an interval no ray meets (tnear > tfar).
template <int K>
std::array<Ray, K> packetRays(const RayPacket<K>& packet) {
    std::array<Ray, K> rays;
    for (int i = 0; i < K; ++i) {
        rays[i] = packet.ray(i);
        if (!packet.valid[i]) rays[i].tnear = 1.0f, rays[i].tfar = 0.0f;
    }
    return rays;
}

} // namespace

template <int K>
HitPacket<K> Scene::intersect(const RayPacket<K>& packet) const {
    const Tracer& tracer = impl_->ready(K == 4 ? impl_->packet4 : K == 8 ? impl_->packet8 : impl_->packet16);
    const std::array<Ray, K> rays = packetRays(packet);
    std::array<Hit, K> hits{};
    {
        MxcsrScope mode;
        tracer.intersect(rays, hits, Coherence::Coherent);
    }
    HitPacket<K> result;
    for (int i = 0; i < K; ++i) {
        impl_->toCallerIds(hits[i]);
        result.t[i] = hits[i].t, result.u[i] = hits[i].u, result.v[i] = hits[i].v;
        result.primId[i] = hits[i].primId, result.geomId[i] = hits[i].geomId;
    }
    return result;
}

template <int K>
std::array<bool, K> Scene::occluded(const RayPacket<K>& packet) const {
    const Tracer& tracer = impl_->ready(K == 4 ? impl_->packet4 : K == 8 ? impl_->packet8 : impl_->packet16);
    const std::array<Ray, K> rays = packetRays(packet);
    std::array<uint8_t, K> occluded{};
    {
        MxcsrScope mode;
        tracer.occluded(rays, occluded, Coherence::Coherent);
    }
    std::array<bool, K> result;
    for (int i = 0; i < K; ++i) result[i] = occluded[i] != 0;
    return result;
}

template HitPacket<4> Scene::intersect<4>(const RayPacket<4>&) const;
template HitPacket<8> Scene::intersect<8>(const RayPacket<8>&) const;
template HitPacket<16> Scene::intersect<16>(const RayPacket<16>&) const;
template std::array<bool, 4> Scene::occluded<4>(const RayPacket<4>&) const;
template std::array<bool, 8> Scene::occluded<8>(const RayPacket<8>&) const;
template std::array<bool, 16> Scene::occluded<16>(const RayPacket<16>&) const;

namespace {

/// Calls trace(begin, end) over [0, n) on the calling thread or in tasks of kRaysPerTask rays.
template <typename Trace>
void forEachChunk(size_t n, Threading threading, const Trace& trace) {
    if (threading == Threading::Caller || n <= kRaysPerTask) {
        MxcsrScope mode;
        for (size_t begin = 0; begin < n; begin += kRaysPerTask) trace(begin, std::min(n, begin + kRaysPerTask));
        return;
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kRaysPerTask), [&](const tbb::blocked_range<size_t>& r) {
        MxcsrScope mode;
        trace(r.begin(), r.end());
    });
}

} // namespace

void Scene::intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence, Threading threading) const {
    if (hits.size() != rays.size())
        throw Error(fmt::format("intersect: {} rays but room for {} hits", rays.size(), hits.size()));
    const Tracer& tracer = impl_->ready(impl_->streams);
    forEachChunk(rays.size(), threading, [&](size_t begin, size_t end) {
        std::fill(hits.begin() + begin, hits.begin() + end, Hit{});
        tracer.intersect(rays.subspan(begin, end - begin), hits.subspan(begin, end - begin), coherence);
        for (size_t i = begin; i < end; ++i) impl_->toCallerIds(hits[i]);
    });
}

void Scene::occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                     Threading threading) const {
    if (occluded.size() != rays.size())
        throw Error(fmt::format("occluded: {} rays but room for {} answers", rays.size(), occluded.size()));
    const Tracer& tracer = impl_->ready(impl_->streams);
    forEachChunk(rays.size(), threading, [&](size_t begin, size_t end) {
        std::fill(occluded.begin() + begin, occluded.begin() + end, uint8_t(0));
        tracer.occluded(rays.subspan(begin, end - begin), occluded.subspan(begin, end - begin), coherence);
    });
}

std::array<float, 6> Scene::bounds() const {
    impl_->ready(impl_->single);
    const Bounds3f b = impl_->structure->geometry().bounds();
    return {b.lower.x, b.lower.y, b.lower.z, b.upper.x, b.upper.y, b.upper.z};
}

uint64_t Scene::primitiveCount() const {
    impl_->ready(impl_->single);
    return impl_->structure->geometry().triangleCount() + impl_->description.spheres.size();
}

size_t Scene::bytes() const {
    impl_->ready(impl_->single);
    return impl_->structure->bytes();
}

std::string Scene::description() const {
    impl_->ready(impl_->single);
    return fmt::format("{} {}; single rays: {}; packets: {}; streams: {}", impl_->structure->name(),
                       impl_->options.quality == BuildQuality::High ? "high" : "fast", impl_->single->description(),
                       impl_->packet16->description(), impl_->streams->description());
}

} // namespace wideray
