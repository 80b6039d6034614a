#pragma once
/// Rays and hits: one ray, packets of 4, 8 or 16 rays in SoA form, and what a trace reports.
#include <cstdint>
#include <limits>

namespace wideray {

/// The id of no primitive and no geometry: a miss.
constexpr uint32_t kInvalidId = UINT32_MAX;

/// A ray o + t d, t in [tnear, tfar]. Rays with a NaN or infinite component, a zero direction or
/// tnear > tfar are invalid: every kernel reports them as a miss and not occluded.
struct Ray {
    float ox = 0, oy = 0, oz = 0;
    float dx = 0, dy = 0, dz = 1;
    float tnear = 0;
    float tfar = std::numeric_limits<float>::infinity();
    float time = 0;  ///< in [0, 1], for moving geometry
};

/// The closest hit along a ray. For a triangle, u and v weight its second and third vertex; geomId is
/// the id the scene gave the mesh, instance or sphere set, primId the triangle or sphere in it. Equal
/// t is resolved by the smaller (geomId, primId), so every kernel finds the same hit.
struct Hit {
    float t = std::numeric_limits<float>::infinity();
    float u = 0, v = 0;
    uint32_t primId = kInvalidId;
    uint32_t geomId = kInvalidId;

    bool valid() const { return primId != kInvalidId; }
};

/// How a batch of rays was made: coherent batches (camera rays in screen-space blocks, their shadow
/// rays) go to packet kernels; incoherent ones (bounces) to sorted streams.
enum class Coherence { Coherent, Incoherent };

/// K rays in SoA form (K = 4, 8, 16). Lanes whose `valid` is 0 are not traced and report a miss.
template <int K>
struct alignas(64) RayPacket {
    static_assert(K == 4 || K == 8 || K == 16, "packets are 4, 8 or 16 rays wide");
    float ox[K] = {}, oy[K] = {}, oz[K] = {};
    float dx[K] = {}, dy[K] = {}, dz[K] = {};
    float tnear[K] = {};
    float tfar[K] = {};
    float time[K] = {};
    int32_t valid[K] = {};  ///< nonzero: trace this lane

    /// Lane i set to `ray` and marked valid.
    void set(int i, const Ray& ray) {
        ox[i] = ray.ox, oy[i] = ray.oy, oz[i] = ray.oz;
        dx[i] = ray.dx, dy[i] = ray.dy, dz[i] = ray.dz;
        tnear[i] = ray.tnear, tfar[i] = ray.tfar, time[i] = ray.time;
        valid[i] = -1;
    }
    Ray ray(int i) const { return {ox[i], oy[i], oz[i], dx[i], dy[i], dz[i], tnear[i], tfar[i], time[i]}; }
};

/// The closest hits of a packet's rays, lane by lane as in Hit.
template <int K>
struct alignas(64) HitPacket {
    float t[K], u[K], v[K];
    uint32_t primId[K], geomId[K];

    Hit hit(int i) const { return {t[i], u[i], v[i], primId[i], geomId[i]}; }
};

} // namespace wideray
