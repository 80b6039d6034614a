#include "backends/wideray_structure.h"

#include <fmt/core.h>

#include "accel/bvh_stats.h"
#include "backends/wideray_tracer.h"
#include "core/error.h"

namespace wideray {

Isa chosenIsa(const KernelChoice& choice) {
    const Isa isa = choice.isa.value_or(bestIsa());
    if (!cpuSupports(isa))
        throw InputError("--isa", "", std::string("this CPU cannot run ") + isaName(isa) + " code (it has up to " +
                                          isaName(bestIsa()) + ")");
    return isa;
}

template <int N>
BvhBuildConfig buildConfig(BuildQuality quality) {
    BvhBuildConfig config = SceneAccel<N>::defaultConfig();
    config.quality = quality;
    return config;
}

template <int N>
WideBvhStructure<N>::WideBvhStructure(std::shared_ptr<const SceneGeometry> geometry, BuildQuality quality)
    : Structure(geometry), quality_(quality), accel_(std::move(geometry), buildConfig<N>(quality)) {}

template <int N>
std::string WideBvhStructure<N>::summary() const {
    BvhStats s = wideBvhStats(accel_.bvh(), SceneAccel<N>::defaultConfig());
    const uint64_t triangles = geometry().triangleCount();
    const double bytesPerTriangle = triangles == 0 ? 0.0 : double(bytes()) / double(triangles);
    const BuildTimings& t = accel_.timings();
    size_t blocks = accel_.blocks().size();
    for (const auto& mesh : accel_.instancedMeshes()) blocks += mesh->blocks().size();
    const uint64_t references = accel_.triangleReferences();
    const double blockFill = blocks ? double(references) / double(blocks * kBlockSize) : 0.0;
    return fmt::format("BVH{} ({} quality): {} inner nodes ({:.2f} of {} children each), {} leaves ({} blocks of {} triangles, "
                       "{:.0f}% full), {:.3f} references per triangle, depth {}, SAH cost {:.2f}, {:.1f} "
                       "bytes/triangle, build {:.1f} ms (binned SAH {:.1f} ms + collapse {:.1f} ms)",
                       N, qualityName(), s.innerNodes, s.childrenPerNode(), N, s.leaves, blocks, kBlockSize, 100.0 * blockFill,
                       triangles ? double(references) / double(triangles) : 0.0, s.depth, s.sahCost, bytesPerTriangle, t.totalSeconds() * 1e3, t.binarySeconds * 1e3,
                       t.collapseSeconds * 1e3) +
           instancingSummary();
}

template <int N>
std::string WideBvhStructure<N>::instancingSummary() const {
    const InstanceGeometry* instances = geometry().instances();
    if (!instances) return "";
    return fmt::format("; two-level: {} instances of {} meshes, {} instanced triangles, {:.1f} MB against about {:.1f} "
                       "MB flattened (each instance a copy of its mesh's structure)",
                       instances->primitiveCount(), instances->meshes().size(), geometry().instancedTriangleCount(),
                       double(bytes()) / 1e6, double(accel_.flattenedBytes()) / 1e6);
}

template <int N>
std::unique_ptr<Tracer> WideBvhStructure<N>::tracer(const KernelChoice& choice) const {
    const Isa isa = chosenIsa(choice);
    const KernelTable<N> table = kernelTable<N>(isa);
    Kernel<N> coherent, incoherent;
    std::string coherentName;
    if (choice.kernel == "auto") {
        // Camera rays share an origin, which is where interval culling shines; coherent shadow rays
        // start on surfaces, where 256-ray packets can visit far more leaves than they hit (8x
        // slower on the coffee maker, docs/performance-analysis.md), so they take 16-wide packets.
        const Kernel<N>* widest = nullptr;
        for (const char* name : {"packet16", "packet8", "packet4"})
            if (!widest && table.find(name)->available()) widest = table.find(name);
        coherent = *table.find("packet256");
        coherent.occluded = widest->occluded;
        coherent.occludedCached = widest->occludedCached;
        coherentName = std::string("packet256+") + widest->name;
        // Incoherent batches (a bounce of a tile's paths) go to streams, which beat single rays on
        // them (bench's diffuse and bounce rays, docs/performance.md).
        // Their shadow rays too: streams beat the single-ray kernel with its shadow cache there
        // (path-traced scenes/sponza_path.json: 1.21-1.26 s against 1.29-1.33 s).
        incoherent = *table.find("stream");
    } else {
        const Kernel<N>* k = table.find(choice.kernel);
        if (!k) throw InputError("--kernel", "", "no kernel is named '" + choice.kernel + "'");
        if (!k->available() && int(isa) < int(k->minimumIsa))
            throw InputError("--kernel", "", "kernel '" + choice.kernel + "' is not available with ISA " +
                                                 isaName(isa) + " (it needs " + isaName(k->minimumIsa) + ")");
        if (!k->available())
            throw InputError("--kernel", "", "kernel '" + choice.kernel + "' does not traverse " + std::to_string(N) +
                                                 "-wide nodes (use --bvh-width 8)");
        coherent = incoherent = *k;
        coherentName = k->name;
    }
    std::string name = fmt::format("wideray BVH{} {}/{} {}", N, coherentName, incoherent.name, isaName(isa));
    return std::make_unique<WiderayTracer<N>>(shared_from_this(), accel_, coherent, incoherent, std::move(name),
                                              choice.shadowCache);
}

std::shared_ptr<const Structure> buildWideBvh(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options) {
    BuildQuality quality;
    if (options.quality.empty() || options.quality == "fast") quality = BuildQuality::Fast;
    else if (options.quality == "high") quality = BuildQuality::High;
    else throw InputError("--quality", "", "our build quality is fast or high, not '" + options.quality + "'");
    if (options.bvhWidth == 4) return std::make_shared<WideBvhStructure<4>>(std::move(geometry), quality);
    if (options.bvhWidth == 8) return std::make_shared<WideBvhStructure<8>>(std::move(geometry), quality);
    if (options.bvhWidth == 16) return std::make_shared<WideBvhStructure<16>>(std::move(geometry), quality);
    throw InputError("--bvh-width", "", "the BVH width must be 4, 8 or 16");
}

template class WideBvhStructure<4>;
template class WideBvhStructure<8>;
template class WideBvhStructure<16>;

} // namespace wideray
