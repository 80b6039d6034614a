#pragma once
// Our tracer: a wide BVH traced by the kernels chosen for coherent and incoherent rays.
#include <memory>
#include <vector>

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include "accel/scene_accel.h"
#include "backends/tracer.h"
#include "kernels/kernel_registry.h"

namespace wideray {

template <int N>
class WiderayTracer final : public Tracer {
public:
    /// With `shadowCache`, shadow rays that name their depth go through their kernel's last-occluder
    /// cache (one per worker thread and depth), where the kernel has one. `owner` keeps the structure
    /// that `accel` belongs to alive.
    WiderayTracer(std::shared_ptr<const void> owner, const SceneAccel<N>& accel, Kernel<N> coherent,
                  Kernel<N> incoherent, std::string name, bool shadowCache)
        : owner_(std::move(owner)), accel_(accel), view_(accel.view()), coherent_(coherent), incoherent_(incoherent),
          name_(std::move(name)),
          caches_(shadowCache && (coherent.occludedCached || incoherent.occludedCached)
                      ? size_t(tbb::this_task_arena::max_concurrency()) * kCachedDepths
                      : 0) {}

    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                   TraversalCost* costs) const override {
        kernel(coherence).intersect(view_, rays.data(), hits.data(), rays.size(), costs);
    }
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                  int depth = -1) const override {
        const Kernel<N>& k = kernel(coherence);
        int thread = tbb::this_task_arena::current_thread_index();
        if (k.occludedCached && depth >= 0 && depth < kCachedDepths && !caches_.empty() && thread >= 0 &&
            size_t(thread) * kCachedDepths < caches_.size()) {
            ShadowCache& cache = caches_[size_t(thread) * kCachedDepths + size_t(depth)];
            k.occludedCached(view_, rays.data(), occluded.data(), rays.size(), cache);
            return;
        }
        k.occluded(view_, rays.data(), occluded.data(), rays.size(), nullptr);
    }

    const SceneGeometry& geometry() const override { return accel_.geometry(); }
    std::string statsReport() const override {
        uint64_t queries = 0, hits = 0;
        for (const ShadowCache& c : caches_) {
            queries += c.queries;
            hits += c.hits;
        }
        if (queries == 0) return {};
        return fmt::format("shadow cache: {} of {} shadow rays answered by the cached occluder ({:.1f}%)", hits,
                           queries, 100.0 * double(hits) / double(queries));
    }
    std::string description() const override { return name_; }

private:
    const Kernel<N>& kernel(Coherence c) const { return c == Coherence::Coherent ? coherent_ : incoherent_; }

    std::shared_ptr<const void> owner_;
    const SceneAccel<N>& accel_;
    SceneView<N> view_;
    Kernel<N> coherent_, incoherent_;
    std::string name_;
    static constexpr int kCachedDepths = 16;
    mutable std::vector<ShadowCache> caches_;  ///< [thread][depth]; each touched by its thread alone
};

} // namespace wideray
