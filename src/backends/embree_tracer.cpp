#include "backends/embree_tracer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "kernels/hit_order.h"

namespace wideray {
namespace {

constexpr std::pair<EmbreeKernel, const char*> kKernelNames[] = {
    {EmbreeKernel::Intersect1, "rtcIntersect1"},   {EmbreeKernel::Packet4, "rtcIntersect4"},
    {EmbreeKernel::Packet8, "rtcIntersect8"},      {EmbreeKernel::Packet16, "rtcIntersect16"},
    {EmbreeKernel::Stream1M, "rtcIntersect1M"}};

/// A device only for asking what this Embree build and CPU support; it lives as long as the process.
RTCDevice queryDevice() {
    static RTCDevice device = rtcNewDevice(nullptr);
    return device;
}

RTCIntersectContext contextFor(Coherence coherence) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherence == Coherence::Coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                     : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return context;
}

void toEmbree(const Ray& r, RTCRay& e) {
    e.org_x = r.ox, e.org_y = r.oy, e.org_z = r.oz, e.tnear = r.tnear;
    e.dir_x = r.dx, e.dir_y = r.dy, e.dir_z = r.dz, e.time = r.time;
    e.tfar = r.tfar, e.mask = UINT32_MAX, e.id = 0, e.flags = 0;
}

void clearHit(RTCHit& h) { h.geomID = h.primID = h.instID[0] = RTC_INVALID_GEOMETRY_ID; }

/// An instance's hit carries the instance's geomID in the top-level scene, which
/// EmbreeStructure::fromInstanceHits turns into ours.
Hit embreeHit(float t, float u, float v, unsigned primID, unsigned geomID, unsigned instID) {
    if (geomID == RTC_INVALID_GEOMETRY_ID) return {};
    return {t, u, v, primID, instID != RTC_INVALID_GEOMETRY_ID ? instID : geomID};
}

Hit fromEmbree(const RTCRayHit& e) { return embreeHit(e.ray.tfar, e.hit.u, e.hit.v, e.hit.primID, e.hit.geomID, e.hit.instID[0]); }

bool isOccluded(float tfar) { return tfar == -std::numeric_limits<float>::infinity(); }

template <int K> struct Packet;
template <> struct Packet<4> {
    using RayHit = RTCRayHit4;
    using Rays = RTCRay4;
    static constexpr auto intersect = rtcIntersect4;
    static constexpr auto occluded = rtcOccluded4;
};
template <> struct Packet<8> {
    using RayHit = RTCRayHit8;
    using Rays = RTCRay8;
    static constexpr auto intersect = rtcIntersect8;
    static constexpr auto occluded = rtcOccluded8;
};
template <> struct Packet<16> {
    using RayHit = RTCRayHit16;
    using Rays = RTCRay16;
    static constexpr auto intersect = rtcIntersect16;
    static constexpr auto occluded = rtcOccluded16;
};

/// Loads rays[first, first + K) into a packet; lanes past the end and invalid rays are masked off
/// (and given a harmless ray, as Embree may still read them).
template <int K, class Rays>
void loadPacket(std::span<const Ray> rays, size_t first, Rays& e, int* valid) {
    for (int i = 0; i < K; ++i) {
        bool active = first + i < rays.size() && isValidRay(rays[first + i]);
        Ray r = active ? rays[first + i] : Ray{};
        valid[i] = active ? -1 : 0;
        e.org_x[i] = r.ox, e.org_y[i] = r.oy, e.org_z[i] = r.oz, e.tnear[i] = r.tnear;
        e.dir_x[i] = r.dx, e.dir_y[i] = r.dy, e.dir_z[i] = r.dz, e.time[i] = r.time;
        e.tfar[i] = r.tfar, e.mask[i] = UINT32_MAX, e.id[i] = 0, e.flags[i] = 0;
    }
}

template <int K>
void intersectPackets(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays, std::span<Hit> hits) {
    for (size_t first = 0; first < rays.size(); first += K) {
        alignas(64) int valid[K];
        typename Packet<K>::RayHit e;
        loadPacket<K>(rays, first, e.ray, valid);
        for (int i = 0; i < K; ++i) e.hit.geomID[i] = e.hit.primID[i] = e.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        Packet<K>::intersect(valid, scene, &context, &e);
        for (size_t i = 0; i < K && first + i < rays.size(); ++i)
            hits[first + i] = embreeHit(e.ray.tfar[i], e.hit.u[i], e.hit.v[i], e.hit.primID[i], e.hit.geomID[i], e.hit.instID[0][i]);
    }
}

template <int K>
void occludedPackets(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays,
                     std::span<uint8_t> occluded) {
    for (size_t first = 0; first < rays.size(); first += K) {
        alignas(64) int valid[K];
        typename Packet<K>::Rays e;
        loadPacket<K>(rays, first, e, valid);
        Packet<K>::occluded(valid, scene, &context, &e);
        for (size_t i = 0; i < K && first + i < rays.size(); ++i) occluded[first + i] = valid[i] && isOccluded(e.tfar[i]);
    }
}

void intersectSingle(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays, std::span<Hit> hits) {
    for (size_t i = 0; i < rays.size(); ++i) {
        hits[i] = {};
        if (!isValidRay(rays[i])) continue;
        RTCRayHit e;
        toEmbree(rays[i], e.ray);
        clearHit(e.hit);
        rtcIntersect1(scene, &context, &e);
        hits[i] = fromEmbree(e);
    }
}

void occludedSingle(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays,
                    std::span<uint8_t> occluded) {
    for (size_t i = 0; i < rays.size(); ++i) {
        occluded[i] = 0;
        if (!isValidRay(rays[i])) continue;
        RTCRay e;
        toEmbree(rays[i], e);
        rtcOccluded1(scene, &context, &e);
        occluded[i] = isOccluded(e.tfar);
    }
}

/// Streams hold the valid rays of a chunk, compacted; `source` maps them back.
constexpr size_t kStreamSize = 256;

void intersectStream(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays, std::span<Hit> hits) {
    std::array<RTCRayHit, kStreamSize> stream;
    std::array<uint32_t, kStreamSize> source;
    for (size_t first = 0; first < rays.size(); first += kStreamSize) {
        size_t end = std::min(rays.size(), first + kStreamSize), m = 0;
        for (size_t i = first; i < end; ++i) {
            hits[i] = {};
            if (!isValidRay(rays[i])) continue;
            toEmbree(rays[i], stream[m].ray);
            clearHit(stream[m].hit);
            source[m++] = uint32_t(i);
        }
        rtcIntersect1M(scene, &context, stream.data(), unsigned(m), sizeof(RTCRayHit));
        for (size_t j = 0; j < m; ++j) hits[source[j]] = fromEmbree(stream[j]);
    }
}

void occludedStream(RTCScene scene, RTCIntersectContext& context, std::span<const Ray> rays,
                    std::span<uint8_t> occluded) {
    std::array<RTCRay, kStreamSize> stream;
    std::array<uint32_t, kStreamSize> source;
    for (size_t first = 0; first < rays.size(); first += kStreamSize) {
        size_t end = std::min(rays.size(), first + kStreamSize), m = 0;
        for (size_t i = first; i < end; ++i) {
            occluded[i] = 0;
            if (!isValidRay(rays[i])) continue;
            toEmbree(rays[i], stream[m]);
            source[m++] = uint32_t(i);
        }
        rtcOccluded1M(scene, &context, stream.data(), unsigned(m), sizeof(RTCRay));
        for (size_t j = 0; j < m; ++j) occluded[source[j]] = isOccluded(stream[j].tfar);
    }
}

} // namespace

const char* embreeKernelName(EmbreeKernel kernel) {
    for (const auto& [k, name] : kKernelNames)
        if (k == kernel) return name;
    return "?";
}

std::optional<EmbreeKernel> parseEmbreeKernel(std::string_view name) {
    for (const auto& [k, n] : kKernelNames)
        if (name == n) return k;
    return std::nullopt;
}

bool embreeSupports(EmbreeKernel kernel) {
    auto property = [](RTCDeviceProperty p) { return rtcGetDeviceProperty(queryDevice(), p) != 0; };
    switch (kernel) {
    case EmbreeKernel::Intersect1: return true;
    case EmbreeKernel::Packet4: return property(RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED);
    case EmbreeKernel::Packet8: return property(RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED);
    case EmbreeKernel::Packet16: return property(RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
    case EmbreeKernel::Stream1M: return property(RTC_DEVICE_PROPERTY_RAY_STREAM_SUPPORTED);
    }
    return false;
}

EmbreeKernel widestNativeEmbreePacket() {
    for (EmbreeKernel k : {EmbreeKernel::Packet16, EmbreeKernel::Packet8, EmbreeKernel::Packet4})
        if (embreeSupports(k)) return k;
    return EmbreeKernel::Intersect1;
}

EmbreeTracer::EmbreeTracer(std::shared_ptr<const EmbreeStructure> structure, EmbreeKernel coherent,
                           EmbreeKernel incoherent)
    : structure_(std::move(structure)), coherent_(coherent), incoherent_(incoherent) {
    for (EmbreeKernel k : {coherent_, incoherent_})
        if (!embreeSupports(k))
            throw InputError("embree", "", std::string("this CPU or Embree build cannot run ") + embreeKernelName(k) +
                                                 " natively");
}

void EmbreeTracer::intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                             TraversalCost* costs) const {
    RTCIntersectContext context = contextFor(coherence);
    RTCScene scene = structure_->scene();
    switch (kernel(coherence)) {
    case EmbreeKernel::Intersect1: intersectSingle(scene, context, rays, hits); break;
    case EmbreeKernel::Packet4: intersectPackets<4>(scene, context, rays, hits); break;
    case EmbreeKernel::Packet8: intersectPackets<8>(scene, context, rays, hits); break;
    case EmbreeKernel::Packet16: intersectPackets<16>(scene, context, rays, hits); break;
    case EmbreeKernel::Stream1M: intersectStream(scene, context, rays, hits); break;
    }
    structure_->fromInstanceHits(hits);
    if (costs) std::fill(costs, costs + rays.size(), TraversalCost{});
}

void EmbreeTracer::occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence, int) const {
    RTCIntersectContext context = contextFor(coherence);
    RTCScene scene = structure_->scene();
    EmbreeKernel k = kernel(coherence);
    if (k == EmbreeKernel::Packet16 && structure_->instanced()) k = EmbreeKernel::Packet8;  // see EmbreeStructure::instanced
    switch (k) {
    case EmbreeKernel::Intersect1: occludedSingle(scene, context, rays, occluded); break;
    case EmbreeKernel::Packet4: occludedPackets<4>(scene, context, rays, occluded); break;
    case EmbreeKernel::Packet8: occludedPackets<8>(scene, context, rays, occluded); break;
    case EmbreeKernel::Packet16: occludedPackets<16>(scene, context, rays, occluded); break;
    case EmbreeKernel::Stream1M: occludedStream(scene, context, rays, occluded); break;
    }
}

std::string EmbreeTracer::description() const {
    return std::string("embree ") + embreeKernelName(coherent_) + "/" + embreeKernelName(incoherent_) + ", " +
           structure_->qualityName() + " quality BVH";
}

} // namespace wideray
