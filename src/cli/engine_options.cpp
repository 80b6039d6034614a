#include <cstdio>

#include "cli/commands.h"

namespace wideray::cli {

void addEngineOptions(CLI::App& app, EngineOptions& options) {
    app.add_option("--threads", options.threads, "Worker threads (default: all hardware threads)")
        ->check(CLI::Range(1, 4096));
    app.add_option("--kernel", options.kernel,
                   "Traversal kernel: scalar (the reference), single (one ray, SIMD across children), "
                   "packet4, packet8, packet16, packet256 (256-ray packets with interval culling), stream, drst "
                   "(streams in which each ray keeps its own order), or auto (packets for coherent rays, the fastest measured kernel for incoherent ones)")
        ->check(CLI::IsMember({"scalar", "single", "packet4", "packet8", "packet16", "packet256", "stream", "drst", "auto"}))
        ->capture_default_str();
    app.add_option("--isa", options.isa,
                   "Instruction set of the kernels: sse42, avx2, avx512 or auto (the best this CPU has); "
                   "asking for one the CPU lacks is an error")
        ->check(CLI::IsMember({"sse42", "avx2", "avx512", "auto"}))
        ->capture_default_str();
    app.add_option("--shadow-cache", options.shadowCache,
                   "Last-occluder cache per thread and recursion depth for incoherent shadow rays (single-ray "
                   "kernel): on or off (see docs/performance-analysis.md for what it saves)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    app.add_option("--bvh-width", options.bvhWidth, "Children per BVH node: 4 or 8")
        ->check(CLI::IsMember({4, 8}))
        ->capture_default_str();
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
