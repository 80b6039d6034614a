#include <algorithm>
#include <cstdio>

#include <fmt/core.h>
#include <fmt/format.h>

#include "backends/accel_registry.h"
#include "cli/commands.h"
#include "core/error.h"
#include "kernels/kernel_registry.h"

namespace wideray::cli {

void addEngineOptions(CLI::App& app, EngineOptions& options) {
    app.add_option("--threads", options.threads, "Worker threads (default: all hardware threads)")
        ->check(CLI::Range(1, 4096));
    // The kernels are the registry's rows (every table has the same rows), plus "auto".
    const KernelTable<8> table = kernelTable<8>(Isa::Sse42);
    std::vector<std::string> names;
    std::string help = "Traversal kernel:";
    for (const Kernel<8>& k : table.rows) {
        names.push_back(k.name);
        help += fmt::format(" {} ({}{});", k.name, k.description,
                            k.minimumIsa == Isa::Sse42 ? "" : fmt::format(", needs {}", isaName(k.minimumIsa)));
    }
    names.push_back("auto");
    help += " or auto (packets for coherent rays, the fastest measured kernel for incoherent ones)";
    app.add_option("--kernel", options.kernel, help)->check(CLI::IsMember(names))->capture_default_str();
    app.add_option("--isa", options.isa,
                   "Instruction set of the kernels: sse42, avx2, avx512 or auto (the best this CPU has); "
                   "asking for one the CPU lacks is an error")
        ->check(CLI::IsMember({"sse42", "avx2", "avx512", "auto"}))
        ->capture_default_str();
    app.add_option("--shadow-cache", options.shadowCache,
                   "Last-occluder cache per thread and recursion depth for shadow rays, where the kernel has one "
                   "(single and the packets; auto's shadow rays of camera hits go through 16-wide packets with it, "
                   "its incoherent ones as streams, which are faster): on or off (see "
                   "docs/performance-analysis.md for what it saves)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    app.add_option("--bvh-width", options.bvhWidth, "Children per BVH node: 4, 8 or 16")
        ->check(CLI::IsMember({4, 8, 16}))
        ->capture_default_str();
    addQualityOption(app, options.quality);
    app.add_option("--accel", options.accel, accelHelp(false))->check(CLI::IsMember(accelNames()));
    addInstancingOption(app, options.instancing);
}

void addInstancingOption(CLI::App& app, std::string& instancing) {
    app.add_option("--instancing", instancing,
                   "Instances of a mesh: two-level (one BVH per mesh, a top-level BVH over the instances), flatten "
                   "(every still instance's triangles copied into one BVH; moving ones stay two-level) or auto (two-level where the copies would add "
                   "65536 triangles or more; flattened for the course's structures)")
        ->check(CLI::IsMember({"auto", "flatten", "two-level"}))
        ->capture_default_str();
}

Instancing instancingFor(const std::string& option, const std::vector<std::string>& accels) {
    const bool singleLevel = std::any_of(accels.begin(), accels.end(), [](const std::string& a) {
        return !a.empty() && !isWideBvh(a);
    });
    if (option == "flatten") return Instancing::Flatten;
    if (option == "two-level") {
        if (singleLevel)
            throw InputError("--instancing", "",
                             fmt::format("the course's structures are single-level: two-level instances need --accel "
                                         "{} (or --instancing auto, which flattens for them)",
                                         fmt::join(wideBvhNames(), ", ")));
        return Instancing::TwoLevel;
    }
    return singleLevel ? Instancing::Flatten : Instancing::Auto;
}

std::vector<std::string> accelNames() {
    std::vector<std::string> names;
    for (const Accel& a : accels()) names.push_back(a.name);
    return names;
}

std::vector<std::string> wideBvhNames() {
    std::vector<std::string> names;
    for (const Accel& a : accels())
        if (a.wideBvh) names.push_back(a.name);
    return names;
}

std::string accelHelp(bool list) {
    std::string help = list ? "Acceleration structures to measure, comma-separated:" : "Acceleration structure:";
    for (const Accel& a : accels()) help += fmt::format(" {} ({});", a.name, a.description);
    help += fmt::format(" the course's structures (all but {}) trace one ray at a time (docs/accelerators.md)",
                        fmt::join(wideBvhNames(), ", "));
    return help;
}

void addQualityOption(CLI::App& app, std::string& quality) {
    app.add_option("--quality", quality,
                   "BVH build: fast (binned SAH over objects) or high (spatial splits too: slower to build, "
                   "faster to trace); with --backend embree, Embree's medium or high quality")
        ->check(CLI::IsMember({"fast", "high"}))
        ->capture_default_str();
}

KernelChoice kernelChoice(const EngineOptions& options) {
    KernelChoice choice;
    choice.kernel = options.kernel;
    if (options.isa != "auto") choice.isa = parseIsa(options.isa);
    choice.shadowCache = options.shadowCache == "on";
    return choice;
}

std::pair<int, int> parseSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 ||
        h < 1 || w > 65536 || h > 65536)
        throw CLI::ValidationError("--size", "expected WxH with 1 <= W, H <= 65536, e.g. 1024x768; got '" + text + "'");
    return {w, h};
}

} // namespace wideray::cli
