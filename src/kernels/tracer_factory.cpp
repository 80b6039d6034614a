#include "kernels/tracer_factory.h"

#include "core/error.h"
#include "core/sphere_geometry.h"
#include "kernels/reference_kernel.h"
#include "kernels/wideray_tracer.h"

namespace wideray {
namespace {

constexpr std::pair<KernelChoice, const char*> kKernelNames[] = {
    {KernelChoice::Scalar, "scalar"},   {KernelChoice::Packet4, "packet4"}, {KernelChoice::Packet8, "packet8"},
    {KernelChoice::Packet16, "packet16"}, {KernelChoice::Stream, "stream"}, {KernelChoice::Auto, "auto"}};

template <int N>
KernelSet<N> referenceKernel() {
    return {"scalar", &reference::intersect<N>, &reference::occluded<N>};
}

template <int N>
BuiltTracer build(const Scene& scene, const TriangleMesh& world, const TracerConfig& config, Isa isa) {
    auto accel = std::make_shared<const SceneAccel<N>>(world, userGeometries(scene));
    BuiltTracer out;
    out.timings = accel->timings();
    out.bytes = accel->bytes();
    out.isa = isa;
    KernelSet<N> kernel = referenceKernel<N>();
    if (config.kernel != KernelChoice::Scalar && config.kernel != KernelChoice::Auto)
        throw InputError("--kernel", "", std::string("kernel '") + kernelName(config.kernel) + "' is not available yet");
    out.tracer = std::make_unique<WiderayTracer<N>>(accel, kernel, kernel);
    return out;
}

} // namespace

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
