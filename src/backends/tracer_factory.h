#pragma once
// Builds our tracer for a scene: the wide BVH (N = 4 or 8) and the kernels chosen for this CPU.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "accel/scene_accel.h"
#include "backends/tracer.h"
#include "simd/cpu_features.h"

namespace wideray {

/// Who traces the rays: our kernels over the wide BVH, or Intel Embree (the yardstick).
enum class Backend { Wideray, Embree };

const char* backendName(Backend b);
std::optional<Backend> parseBackend(std::string_view name);

/// scalar: the reference; single: one ray at a time with SIMD box and triangle tests; packetK: K rays
/// at a time; packet256: 256-ray packets with interval culling; stream: sorted ray streams; drst:
/// sorted ray streams in which each ray keeps its own order; auto: packets for coherent rays and the
/// fastest measured kernel for incoherent ones.
enum class KernelChoice { Scalar, Single, Packet4, Packet8, Packet16, Packet256, Stream, Drst, Auto };

const char* kernelName(KernelChoice k);
std::optional<KernelChoice> parseKernel(std::string_view name);

struct TracerConfig {
    int bvhWidth = 8;
    KernelChoice kernel = KernelChoice::Auto;
    std::optional<Isa> isa;  ///< nullopt: the best this CPU has
    bool shadowCache = false;  ///< last-occluder cache for incoherent shadow rays (single-ray kernel)
};

struct BuiltTracer {
    std::unique_ptr<Tracer> tracer;
    BuildTimings timings;
    size_t bytes = 0;
    Isa isa = Isa::Sse42;
    std::string coherentKernel, incoherentKernel;
};

/// The scene's user geometry, indexed by geomId (entry 0, the triangles, is null).
std::vector<std::unique_ptr<Geometry>> userGeometries(const Scene& scene);

/// Throws InputError when the configuration asks for an ISA this CPU lacks or a kernel that the
/// chosen ISA cannot run.
BuiltTracer buildWiderayTracer(const Scene& scene, const TriangleMesh& world, const TracerConfig& config);

} // namespace wideray
