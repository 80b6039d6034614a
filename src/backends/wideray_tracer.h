#pragma once
// Our tracer: the scene's wide BVH traced by the kernels chosen for coherent and incoherent rays.
#include <memory>
#include <vector>

#include <tbb/task_arena.h>

#include "accel/scene_accel.h"
#include "backends/tracer.h"
#include "kernels/kernel_set.h"

namespace wideray {

template <int N>
class WiderayTracer final : public Tracer {
public:
    /// With `shadowCache`, incoherent shadow rays that name their depth go through the kernel's
    /// last-occluder cache (one per worker thread and depth), where the kernel has one.
    WiderayTracer(std::shared_ptr<const SceneAccel<N>> accel, KernelSet<N> coherent, KernelSet<N> incoherent,
                  bool shadowCache = false)
        : accel_(std::move(accel)), view_(accel_->view()), coherent_(coherent), incoherent_(incoherent),
          caches_(shadowCache && incoherent.occludedCached
                      ? size_t(tbb::this_task_arena::max_concurrency()) * kCachedDepths
                      : 0) {}

    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                   TraversalCost* costs) const override {
        kernel(coherence).intersect(view_, rays.data(), hits.data(), rays.size(), costs);
    }
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                  int depth = -1) const override {
        int thread = tbb::this_task_arena::current_thread_index();
        if (coherence == Coherence::Incoherent && depth >= 0 && depth < kCachedDepths && !caches_.empty() &&
            thread >= 0 && size_t(thread) * kCachedDepths < caches_.size()) {
            ShadowCache& cache = caches_[size_t(thread) * kCachedDepths + size_t(depth)];
            incoherent_.occludedCached(view_, rays.data(), occluded.data(), rays.size(), cache);
            return;
        }
        kernel(coherence).occluded(view_, rays.data(), occluded.data(), rays.size());
    }

    /// Queries and hits of the shadow caches so far (zeros without a cache).
    std::pair<uint64_t, uint64_t> shadowCacheStats() const override {
        uint64_t queries = 0, hits = 0;
        for (const ShadowCache& c : caches_) {
            queries += c.queries;
            hits += c.hits;
        }
        return {queries, hits};
    }
    const Geometry& geometry(uint32_t geomId) const override { return accel_->geometry(geomId); }
    std::string description() const override {
        return std::string("wideray BVH") + std::to_string(N) + " " + coherent_.name + "/" + incoherent_.name;
    }

private:
    const KernelSet<N>& kernel(Coherence c) const { return c == Coherence::Coherent ? coherent_ : incoherent_; }

    std::shared_ptr<const SceneAccel<N>> accel_;
    SceneView<N> view_;
    KernelSet<N> coherent_, incoherent_;
    static constexpr int kCachedDepths = 16;
    mutable std::vector<ShadowCache> caches_;  ///< [thread][depth]; each touched by its thread alone
};

} // namespace wideray
