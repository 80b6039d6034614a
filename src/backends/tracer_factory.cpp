#include "backends/tracer_factory.h"

#include "core/error.h"
#include "geometry/sphere_geometry.h"
#include "kernels/isa_kernels.h"
#include "kernels/reference_kernel.h"
#include "backends/wideray_tracer.h"

namespace wideray {
namespace {

constexpr std::pair<KernelChoice, const char*> kKernelNames[] = {
    {KernelChoice::Scalar, "scalar"},   {KernelChoice::Single, "single"},   {KernelChoice::Packet4, "packet4"},
    {KernelChoice::Packet8, "packet8"},   {KernelChoice::Packet256, "packet256"},
    {KernelChoice::Packet16, "packet16"}, {KernelChoice::Stream, "stream"},
    {KernelChoice::Drst, "drst"},         {KernelChoice::Auto, "auto"}};

constexpr std::pair<Backend, const char*> kBackendNames[] = {{Backend::Wideray, "wideray"}, {Backend::Embree, "embree"}};

template <int N>
KernelSet<N> referenceKernel() {
    return {"scalar", &reference::intersect<N>, &reference::occluded<N>};
}

template <int N>
KernelSet<N> pickKernel(const IsaKernelTable<N>& table, KernelChoice choice, Isa isa) {
    KernelSet<N> k;
    switch (choice) {
    case KernelChoice::Scalar: return referenceKernel<N>();
    case KernelChoice::Single: k = table.single; break;
    case KernelChoice::Packet4: k = table.packet4; break;
    case KernelChoice::Packet8: k = table.packet8; break;
    case KernelChoice::Packet16: k = table.packet16; break;
    case KernelChoice::Packet256: k = table.packet256; break;
    case KernelChoice::Stream: k = table.stream; break;
    case KernelChoice::Drst: k = table.drst; break;
    case KernelChoice::Auto: break;
    }
    if (!k.intersect)
        throw InputError("--kernel", "", std::string("kernel '") + kernelName(choice) + "' is not available with ISA " +
                                             isaName(isa) + (choice == KernelChoice::Packet8 ? " (it needs avx2)" : "") +
                                             (choice == KernelChoice::Packet16 ? " (it needs avx512)" : ""));
    return k;
}

template <int N>
BuiltTracer build(const Scene& scene, const TriangleMesh& world, const TracerConfig& config, Isa isa) {
    IsaKernelTable<N> table = kernelTable<N>(isa);
    KernelSet<N> coherent, incoherent;
    if (config.kernel == KernelChoice::Auto) {
        // Camera rays share an origin, which is where interval culling shines; coherent shadow rays
        // start on surfaces, where 256-ray packets can visit far more leaves than they hit (8x
        // slower on the coffee maker, docs/performance-analysis.md), so they take 16-wide packets.
        const KernelSet<N>& widest = table.packet16.intersect ? table.packet16
                                   : table.packet8.intersect  ? table.packet8
                                                              : table.packet4;
        coherent = table.packet256;
        coherent.name = table.packet16.intersect ? "packet256+packet16"
                        : table.packet8.intersect ? "packet256+packet8"
                                                  : "packet256+packet4";
        coherent.occluded = widest.occluded;
        incoherent = table.single;
    } else {
        coherent = incoherent = pickKernel(table, config.kernel, isa);
    }
    auto accel = std::make_shared<const SceneAccel<N>>(world, userGeometries(scene));
    BuiltTracer out;
    out.timings = accel->timings();
    out.bytes = accel->bytes();
    out.isa = isa;
    out.coherentKernel = coherent.name;
    out.incoherentKernel = incoherent.name;
    out.tracer = std::make_unique<WiderayTracer<N>>(accel, coherent, incoherent, config.shadowCache);
    return out;
}

} // namespace

const char* backendName(Backend b) {
    for (const auto& [kind, name] : kBackendNames)
        if (kind == b) return name;
    return "?";
}

std::optional<Backend> parseBackend(std::string_view name) {
    for (const auto& [kind, n] : kBackendNames)
        if (name == n) return kind;
    return std::nullopt;
}

const char* kernelName(KernelChoice k) {
    for (const auto& [kind, name] : kKernelNames)
        if (kind == k) return name;
    return "?";
}

std::optional<KernelChoice> parseKernel(std::string_view name) {
    for (const auto& [kind, n] : kKernelNames)
        if (name == n) return kind;
    return std::nullopt;
}

std::vector<std::unique_ptr<Geometry>> userGeometries(const Scene& scene) {
    std::vector<std::unique_ptr<Geometry>> g;
    g.emplace_back();
    if (!scene.spheres.empty()) g.push_back(std::make_unique<SphereGeometry>(scene.spheres));
    return g;
}

BuiltTracer buildWiderayTracer(const Scene& scene, const TriangleMesh& world, const TracerConfig& config) {
    Isa isa = config.isa.value_or(bestIsa());
    if (!cpuSupports(isa))
        throw InputError("--isa", "", std::string("this CPU cannot run ") + isaName(isa) + " code (it has up to " +
                                          isaName(bestIsa()) + ")");
    if (config.bvhWidth == 4) return build<4>(scene, world, config, isa);
    if (config.bvhWidth == 8) return build<8>(scene, world, config, isa);
    throw InputError("--bvh-width", "", "the BVH width must be 4 or 8");
}

} // namespace wideray
