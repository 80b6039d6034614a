// wideray bench: the same rays traced in the same process by each of our kernels and by Embree's
// counterparts, each timed several times after a warm-up; medians in Mrays/s, ratios ours / Embree.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <thread>

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "backends/accel_registry.h"
#include "backends/backend_registry.h"
#include "backends/course_structure.h"
#include "backends/embree_structure.h"
#include "backends/embree_tracer.h"
#include "backends/wideray_structure.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "kernels/kernel_registry.h"
#include "render/bench_rays.h"

namespace wideray::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchArgs {
    std::vector<std::string> inputs;
    std::string size = "1024x1024";
    int threads = 0;
    int runs = 5;
    std::string json;
    std::vector<std::string> kinds = [] {
        std::vector<std::string> all;
        for (const RayKindInfo& k : rayKinds()) all.push_back(k.name);
        return all;
    }();
    bool allIsas = false;
    std::string backend = "both";
    std::string quality = "fast";  ///< our builds: fast, high or both
    bool counters = false;         ///< also count our kernels' work per ray
    /// Our structures besides BVH8 (whose kernels are always measured): bvh4, bvh16 and the course's.
    std::vector<std::string> accels;
    std::string instancing = "auto";
};

constexpr size_t kChunk = 4096;  // rays per task: sixteen 16x16 tiles

/// One way of tracing a batch: closest hits (hits != null) or occlusion, and each ray's traversal
/// work where `costs` is given (only asked of candidates that count it).
using TraceFn = std::function<void(const Ray* rays, size_t count, Hit* hits, uint8_t* occluded, bool coherent,
                                   TraversalCost* costs)>;

struct Candidate {
    std::string backend, kernel, isa;
    std::string accel;        ///< the structure it traces: bvh8, bvh4, kdtree, ...; "embree" for Embree's
    std::string quality;      ///< the build it traces: ours "fast" or "high"; Embree's "medium" or "high"
    std::string counterpart;  ///< the Embree kernel ours is compared with
    TraceFn trace;
    bool countsWork = false;  ///< whether `trace` fills costs
    bool shadowOnly = false;  ///< traces shadow rays alone (the kernels with the shadow cache)
};

/// The whole ray set through a candidate, in tasks of kChunk rays.
void traceAll(const Candidate& c, const std::vector<Ray>& rays, bool anyHit, bool coherent, std::vector<Hit>& hits,
              std::vector<uint8_t>& occluded, TraversalCost* costs) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kChunk), [&](const tbb::blocked_range<size_t>& r) {
        c.trace(rays.data() + r.begin(), r.size(), anyHit ? nullptr : hits.data() + r.begin(),
                anyHit ? occluded.data() + r.begin() : nullptr, coherent, costs ? costs + r.begin() : nullptr);
    });
}

/// Work per ray, averaged over a ray set.
struct WorkPerRay {
    double nodes = 0, leaves = 0, primitives = 0, mailboxHits = 0;
};

struct Measurement {
    double mraysPerSecond = 0;
    size_t hits = 0;
    std::optional<WorkPerRay> work;
};

/// The kernel's work on the rays, traced once more with its counters on (not timed).
WorkPerRay countWork(const Candidate& c, const std::vector<Ray>& rays, bool anyHit, bool coherent) {
    std::vector<Hit> hits(anyHit ? 0 : rays.size());
    std::vector<uint8_t> occluded(anyHit ? rays.size() : 0);
    std::vector<TraversalCost> costs(rays.size());
    traceAll(c, rays, anyHit, coherent, hits, occluded, costs.data());
    WorkPerRay w;
    for (const TraversalCost& c : costs) {
        w.nodes += c.nodes;
        w.leaves += c.leaves;
        w.primitives += c.primitives;
        w.mailboxHits += c.mailboxHits;
    }
    const double n = double(std::max<size_t>(1, rays.size()));
    return {w.nodes / n, w.leaves / n, w.primitives / n, w.mailboxHits / n};
}

/// Every candidate on the same rays, the runs taken round-robin (one run of each candidate, then the
/// next run of each) so that the machine's drift over time touches every candidate alike; after one
/// warm-up run each (caches, page faults, thread start). Medians of the runs.
std::vector<Measurement> measureAll(const std::vector<const Candidate*>& candidates, const std::vector<Ray>& rays,
                                    bool anyHit, bool coherent, int runs, const std::string& label) {
    std::vector<Hit> hits(anyHit ? 0 : rays.size());
    std::vector<uint8_t> occluded(anyHit ? rays.size() : 0);
    auto once = [&](const Candidate& c) {
        auto start = Clock::now();
        traceAll(c, rays, anyHit, coherent, hits, occluded, nullptr);
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    std::vector<Measurement> m(candidates.size());
    std::vector<std::vector<double>> seconds(candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i) {
        fmt::print(stderr, "\r{} {} {}: warm-up...            ", label, candidates[i]->kernel, candidates[i]->isa);
        once(*candidates[i]);
        m[i].hits = anyHit ? size_t(std::count(occluded.begin(), occluded.end(), 1))
                           : size_t(std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.valid(); }));
    }
    for (int run = 0; run < runs; ++run) {
        fmt::print(stderr, "\r{}: run {} of {}...                              ", label, run + 1, runs);
        for (size_t i = 0; i < candidates.size(); ++i) seconds[i].push_back(once(*candidates[i]));
    }
    for (size_t i = 0; i < candidates.size(); ++i) {
        std::sort(seconds[i].begin(), seconds[i].end());
        const double median = seconds[i][seconds[i].size() / 2];
        m[i].mraysPerSecond = median > 0 ? double(rays.size()) / median * 1e-6 : 0.0;
    }
    return m;
}

/// Our kernels over a wide BVH (with `only`, those named there).
template <int N>
std::vector<Candidate> ourCandidates(const SceneAccel<N>& accel, const std::string& quality, bool allIsas,
                                     const std::vector<std::string>& only = {}) {
    std::vector<Candidate> out;
    SceneView<N> view = accel.view();
    const std::string accelName = "bvh" + std::to_string(N);
    for (Isa isa : supportedIsas()) {
        if (!allIsas && isa != bestIsa()) continue;
        for (const Kernel<N>& k : kernelTable<N>(isa).rows) {
            if (!k.available()) continue;
            if (!only.empty() && std::find(only.begin(), only.end(), k.name) == only.end()) continue;
            auto trace = [view, k](const Ray* r, size_t n, Hit* h, uint8_t* o, bool, TraversalCost* costs) {
                if (h) k.intersect(view, r, h, n, costs);
                else k.occluded(view, r, o, n, costs);
            };
            out.push_back({"wideray", k.name, isaName(isa), accelName, quality, k.embreeCounterpart, trace, true});
            // The shadow cache: one per task, so that each chunk of rays starts cold (as a renderer tile would).
            if (k.occludedCached)
                out.push_back({"wideray", std::string(k.name) + "+cache", isaName(isa), accelName, quality, k.embreeCounterpart,
                               [view, k](const Ray* r, size_t n, Hit* h, uint8_t* o, bool, TraversalCost*) {
                                   if (h) return;
                                   ShadowCache cache;
                                   k.occludedCached(view, r, o, n, cache);
                               },
                               false, true});
        }
    }
    return out;
}

/// A course structure's single-ray kernel for each ISA measured.
std::vector<Candidate> courseCandidates(std::shared_ptr<const CourseStructure> structure, const std::string& accel,
                                        bool allIsas) {
    std::vector<Candidate> out;
    for (Isa isa : supportedIsas()) {
        if (!allIsas && isa != bestIsa()) continue;
        out.push_back({"wideray", "single", isaName(isa), accel, "fast", "rtcIntersect1",
                       [structure, isa](const Ray* r, size_t n, Hit* h, uint8_t* o, bool, TraversalCost* costs) {
                           structure->trace(isa, r, n, h, o, costs);
                       },
                       true});
    }
    return out;
}

/// Each of Embree's entry points this CPU runs natively, over one Embree structure (but 16-wide
/// packets through instances, whose occlusion it traces as two 8-wide packets: EmbreeStructure::instanced).
std::vector<Candidate> embreeCandidates(const EmbreeStructure& embree, const std::string& quality) {
    std::vector<Candidate> out;
    for (EmbreeKernel kernel : {EmbreeKernel::Intersect1, EmbreeKernel::Packet4, EmbreeKernel::Packet8,
                                EmbreeKernel::Packet16, EmbreeKernel::Stream1M}) {
        if (!embreeSupports(kernel) || (kernel == EmbreeKernel::Packet16 && embree.instanced())) continue;
        std::shared_ptr<const Tracer> tracer = embree.tracer({embreeKernelName(kernel)});
        out.push_back({"embree", embreeKernelName(kernel), "embree", "embree", quality, "",
                       [tracer](const Ray* r, size_t n, Hit* h, uint8_t* o, bool coherent, TraversalCost*) {
                           Coherence c = coherent ? Coherence::Coherent : Coherence::Incoherent;
                           if (h) tracer->intersect({r, n}, {h, n}, c);
                           else tracer->occluded({r, n}, {o, n}, c);
                       }});
    }
    return out;
}

/// A structure bench builds: which backend, structure and quality, and the median of its timed builds.
struct PlannedBuild {
    std::string backend, accel, quality;
    double medianSeconds = 0;
    int runs = 0;
};

/// Builds every planned structure once to warm up (thread pool, page faults) and then `runs` more
/// times, round-robin as the kernels are timed, and keeps the median build time of each and its last
/// build. A structure that takes over a second is built at most three times in all.
std::vector<std::shared_ptr<const Structure>> buildAll(std::vector<PlannedBuild>& planned,
                                                       const std::shared_ptr<const SceneGeometry>& geometry, int runs,
                                                       const std::string& label) {
    std::vector<std::shared_ptr<const Structure>> built(planned.size());
    std::vector<std::vector<double>> seconds(planned.size());
    for (int run = 0; run <= runs; ++run) {
        fmt::print(stderr, "\r{}: {} {} of {}...            ", label, run == 0 ? "building, warm-up" : "build run", run,
                   runs);
        for (size_t i = 0; i < planned.size(); ++i) {
            if (run > 2 && seconds[i].back() > 1.0) continue;
            StructureOptions options;
            if (planned[i].accel != "bvh8" && planned[i].backend != "embree") options.accel = planned[i].accel;
            options.quality = planned[i].quality;
            built[i].reset();  // one copy at a time
            built[i] = findBackend(planned[i].backend).build(geometry, options);
            if (run > 0) seconds[i].push_back(built[i]->buildSeconds());
        }
    }
    fmt::print(stderr, "\r{:60}\r", "");
    for (size_t i = 0; i < planned.size(); ++i) {
        std::sort(seconds[i].begin(), seconds[i].end());
        planned[i].medianSeconds = seconds[i][seconds[i].size() / 2];
        planned[i].runs = int(seconds[i].size());
    }
    return built;
}

std::string shortName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

void benchOne(const BenchArgs& args, const std::string& input, nlohmann::json& results, nlohmann::json& builds,
              int threads) {
    auto [width, height] = parseSize(args.size);
    SceneDescription scene = loadSceneOrMesh(input, width, height);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
    // One geometry for every structure, so that all trace the same primitives.
    auto geometry = std::make_shared<const SceneGeometry>(scene, instancingFor(args.instancing, args.accels));
    const std::string name = shortName(input);
    // A scene file is seen from its own camera (an interior view, say); a bare mesh is framed from outside.
    const std::string workload = isSceneFile(input) ? "scene" : "framed";
    fmt::print(stderr, "{}: {} triangles, building BVHs...\n", name, geometry->triangleCount());

    // The structures: ours (fast, high or both), Embree at medium and high quality, then our others.
    std::vector<PlannedBuild> planned;
    for (const char* quality : {"fast", "high"})
        if (args.quality == quality || args.quality == "both") planned.push_back({"wideray", "bvh8", quality});
    for (const char* quality : {"medium", "high"}) planned.push_back({"embree", "embree", quality});
    for (const std::string& accel : args.accels) {
        if (accel == "bvh8") continue;
        for (const char* quality : {"fast", "high"})
            if (!isWideBvh(accel) ? quality == std::string("fast") : args.quality == quality || args.quality == "both")
                planned.push_back({"wideray", accel, quality});
    }
    const std::vector<std::shared_ptr<const Structure>> built = buildAll(planned, geometry, args.runs, name);

    // Our kernels are called directly on the BVH's view (the shadow-cache candidate needs a cache per task).
    std::vector<std::shared_ptr<const WideBvhStructure<8>>> ours;
    std::vector<std::pair<std::string, std::shared_ptr<const Structure>>> embree;
    std::vector<Candidate> others;  // BVH4 and BVH16 with their kernels, the course's structures with theirs
    for (size_t i = 0; i < planned.size(); ++i) {
        const PlannedBuild& p = planned[i];
        const std::shared_ptr<const Structure>& structure = built[i];
        nlohmann::json record = {{"scene", name}, {"backend", p.backend}, {"quality", p.quality},
                                 {"seconds", p.medianSeconds}, {"bytes", structure->bytes()}};
        if (p.backend == "wideray") {
            record["accel"] = p.accel;
            record["layout"] = structure->name();
        }
        if (p.backend == "embree") {
            embree.emplace_back(p.quality, structure);
        } else if (p.accel == "bvh8") {
            ours.push_back(std::static_pointer_cast<const WideBvhStructure<8>>(structure));
            record["references"] = ours.back()->accel().triangleReferences();
        } else if (p.accel == "bvh4") {
            auto bvh4 = std::static_pointer_cast<const WideBvhStructure<4>>(structure);
            for (Candidate& c : ourCandidates(bvh4->accel(), p.quality, args.allIsas, {"scalar", "single"}))
                others.push_back(std::move(c));
        } else if (p.accel == "bvh16") {
            auto bvh16 = std::static_pointer_cast<const WideBvhStructure<16>>(structure);
            for (Candidate& c : ourCandidates(bvh16->accel(), p.quality, args.allIsas))
                others.push_back(std::move(c));
        } else {
            for (Candidate& c : courseCandidates(std::dynamic_pointer_cast<const CourseStructure>(structure), p.accel,
                                                 args.allIsas))
                others.push_back(std::move(c));
        }
        builds.push_back(std::move(record));
        fmt::print("{}: build {} {}: {:.1f} ms (median of {}), {:.1f} MB\n", name,
                   p.backend == "embree" ? std::string("embree") : p.accel, p.quality, p.medianSeconds * 1e3,
                   p.runs, double(structure->bytes()) / 1e6);
    }

    BenchRays rays = makeBenchRays(scene, *ours.front()->tracer({"scalar"}), width, height);

    // Embree's kernels are measured on both of its builds; ours are compared with the faster.
    std::vector<Candidate> candidates;
    if (args.backend != "embree")
        for (const auto& structure : ours)
            for (Candidate& c : ourCandidates(structure->accel(), structure->qualityName(), args.allIsas))
                candidates.push_back(std::move(c));
    if (args.backend != "embree")
        for (Candidate& c : others) candidates.push_back(std::move(c));
    if (args.backend != "wideray")
        for (const auto& [quality, structure] : embree)
            for (Candidate& c : embreeCandidates(static_cast<const EmbreeStructure&>(*structure), quality))
                candidates.push_back(std::move(c));

    fmt::print("\n{:<28} {:<8} {:<8} {:<15} {:<8} {:<7} {:>10} {:>9} {}{}\n", "scene", "rays", "backend", "kernel",
               "isa", "build", "Mrays/s", "hits", args.counters ? "nodes/ray leaves/ray prims/ray " : "",
               "vs embree's faster build");
    for (const std::string& kindName : args.kinds) {
        const RayKindInfo& kind = *findRayKind(kindName);
        const std::vector<Ray>& set = rays.of(kind.kind);
        if (set.empty()) continue;
        const bool anyHit = kind.anyHit, coherent = kind.coherent;
        std::map<std::string, std::pair<double, std::string>> embreeBest;  // kernel -> (Mrays/s, quality)
        std::vector<const Candidate*> timed;
        for (const Candidate& c : candidates)
            if (anyHit || !c.shadowOnly) timed.push_back(&c);
        const std::vector<Measurement> times = measureAll(timed, set, anyHit, coherent, args.runs, name + " " + kindName);
        std::vector<std::pair<const Candidate*, Measurement>> measured;
        for (size_t i = 0; i < timed.size(); ++i) {
            const Candidate& c = *timed[i];
            Measurement m = times[i];
            if (args.counters && c.countsWork) m.work = countWork(c, set, anyHit, coherent);
            if (c.backend == "embree" && m.mraysPerSecond > embreeBest[c.kernel].first)
                embreeBest[c.kernel] = {m.mraysPerSecond, c.quality};
            measured.push_back({&c, m});
        }
        fmt::print(stderr, "\r{:60}\r", "");
        for (const auto& [c, m] : measured) {
            std::string kernel = anyHit && c->backend == "embree" ? std::string(c->kernel).replace(3, 9, "Occluded") : c->kernel;
            const std::string label = c->accel == "bvh8" || c->accel == "embree" ? kernel : c->accel + "/" + kernel;
            std::string versus;
            if (auto it = embreeBest.find(c->counterpart); it != embreeBest.end() && it->second.first > 0) {
                std::string counterpart = anyHit ? std::string(c->counterpart).replace(3, 9, "Occluded") : c->counterpart;
                versus = fmt::format("{:.2f}x {} ({})", m.mraysPerSecond / it->second.first, counterpart, it->second.second);
            }
            std::string work;
            if (m.work) work = fmt::format("{:>9.1f} {:>10.2f} {:>10.1f} ", m.work->nodes, m.work->leaves, m.work->primitives);
            else if (args.counters) work = fmt::format("{:>9} {:>10} {:>10} ", "-", "-", "-");
            fmt::print("{:<28} {:<8} {:<8} {:<15} {:<8} {:<7} {:>10.2f} {:>9} {}{}\n", name, kindName, c->backend, label,
                       c->isa, c->quality, m.mraysPerSecond, m.hits, work, versus);
            nlohmann::json result = {{"scene", name}, {"triangles", geometry->triangleCount()}, {"ray_kind", kindName},
                                     {"backend", c->backend}, {"accel", c->accel}, {"kernel", kernel}, {"isa", c->isa}, {"quality", c->quality},
                                     {"workload", workload}, {"threads", threads}, {"rays", set.size()}, {"hits", m.hits},
                                     {"mrays_per_s", m.mraysPerSecond}, {"runs", args.runs}};
            if (m.work) {
                result["nodes_per_ray"] = m.work->nodes;
                result["leaves_per_ray"] = m.work->leaves;
                result["primitives_per_ray"] = m.work->primitives;
                result["mailbox_hits_per_ray"] = m.work->mailboxHits;
            }
            results.push_back(std::move(result));
        }
        std::fflush(stdout);
    }
}

} // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<BenchArgs>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Trace the same primary, shadow, diffuse and bounce rays with each of our kernels and Embree's, in one "
                 "process; print Mrays/s (median of several runs) and the ratio ours / Embree");
    cmd->add_option("inputs", args->inputs, "Scene files (camera and first point light used) or meshes (framed by "
                                            "the rule in docs/performance.md)")
        ->required();
    cmd->add_option("--size", args->size, "Image size WxH of the ray sets")->capture_default_str();
    cmd->add_option("--threads", args->threads, "Worker threads (default: all hardware threads)")->check(CLI::Range(1, 4096));
    cmd->add_option("--runs", args->runs, "Timed runs per measurement (after one warm-up); the median is reported")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--rays", args->kinds, "Ray kinds: primary, shadow, diffuse, bounce (docs/performance.md)")
        ->check(CLI::IsMember(args->kinds))
        ->delimiter(',');
    cmd->add_option("--backend", args->backend, "Whose kernels to measure: wideray, embree or both")
        ->check(CLI::IsMember({"wideray", "embree", "both"}))
        ->capture_default_str();
    cmd->add_option("--quality", args->quality,
                    "Our builds to measure: fast, high (spatial splits) or both (Embree is always measured at "
                    "medium and high)")
        ->check(CLI::IsMember({"fast", "high", "both"}))
        ->capture_default_str();
    cmd->add_flag("--counters", args->counters,
                  "Also print our kernels' work per ray: inner nodes visited, leaves entered, primitives tested "
                  "(JSON: nodes_per_ray, leaves_per_ray, primitives_per_ray)");
    cmd->add_option("--accel", args->accels,
                    accelHelp(true) + ". BVH8 and all its kernels are always measured; bvh4 adds its scalar and single "
                                      "kernels, bvh16 all of its kernels, each of the others its single-ray kernel "
                                      "(JSON: accel)")
        ->check(CLI::IsMember(accelNames()))
        ->delimiter(',');
    cmd->add_flag("--all-isas", args->allIsas, "Measure our kernels for every ISA this CPU has, not only the best");
    addInstancingOption(*cmd, args->instancing);
    cmd->add_option("--json", args->json, "Write the results as JSON (fields: machine, results, builds)");
    cmd->callback([args, &exitCode] {
        FlushToZeroScope ftz;
        ftz.run([&] {
            int threads = args->threads > 0 ? args->threads : int(std::thread::hardware_concurrency());
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
            nlohmann::json results = nlohmann::json::array(), builds = nlohmann::json::array();
            for (const std::string& input : args->inputs) {
                try {
                    benchOne(*args, input, results, builds, threads);
                } catch (const std::exception& e) {
                    fmt::print(stderr, "error: {}\n", e.what());
                    exitCode = 1;
                }
            }
            if (!args->json.empty()) {
                nlohmann::json doc = {{"machine",
                                       {{"cpu", cpuModelName()},
                                        {"cores", std::thread::hardware_concurrency()},
                                        {"threads", threads},
                                        {"isa", isaName(bestIsa())}}},
                                      {"size", args->size},
                                      {"results", results},
                                      {"builds", builds}};
                std::filesystem::path path(args->json), temp = path;
                temp += ".tmp";
                if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
                std::ofstream(temp) << doc.dump(2) << "\n";
                std::filesystem::rename(temp, path);
            }
        });
    });
}

} // namespace wideray::cli
