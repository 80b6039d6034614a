#pragma once
// The records of wavefront path tracing: the paths of a tile advance one bounce at a time, each
// bounce's rays traced as one batch, and the shadow rays they create traced as another.
#include <cstdint>

#include <glm/glm.hpp>

#include "core/ray.h"

namespace wideray {

/// The dielectrics a path is inside, innermost last, by material index. Entering pushes; leaving
/// removes that material wherever it is, so overlapping volumes unwind in any order. A path nested
/// deeper than the capacity forgets the outermost medium.
class MediumStack {
public:
    static constexpr int kCapacity = 4;

    bool empty() const { return size_ == 0; }
    uint32_t innermost() const { return materials_[size_ - 1]; }
    bool contains(uint32_t material) const {
        for (int i = 0; i < size_; ++i)
            if (materials_[i] == material) return true;
        return false;
    }
    void push(uint32_t material) {
        if (size_ == kCapacity) remove(materials_[0]);
        materials_[size_++] = material;
    }
    /// Removes the innermost entry of `material`, if any.
    void remove(uint32_t material) {
        for (int i = size_ - 1; i >= 0; --i) {
            if (materials_[i] != material) continue;
            for (int j = i; j + 1 < size_; ++j) materials_[j] = materials_[j + 1];
            --size_;
            return;
        }
    }

private:
    uint32_t materials_[kCapacity] = {};
    int size_ = 0;
};

/// Throughput factors for s- and p-polarized light, per channel.
struct PolarizedFactor {
    glm::vec3 s, p;
};

/// One path of one pixel sample, about to trace `ray`. The throughput is kept separately for light
/// polarized perpendicular (s) and parallel (p) to the planes of incidence; unpolarized light is
/// their average. Without polarization tracking both always hold the same value.
struct PathState {
    Ray ray;
    glm::vec3 throughputS{1.0f}, throughputP{1.0f};
    uint32_t pixelX = 0, pixelY = 0;
    uint32_t key = 0;    ///< the sample index for primary paths; distinct for every path split from it
    int depth = 0;       ///< reflections and refractions so far
    bool glossySplit = false;  ///< has already branched into several glossy samples
    /// Path tracing: the density over solid angle with which `ray`'s direction was sampled, where the
    /// vertex it leaves also sampled the lights; 0 where it did not (the camera, specular events).
    float scatterPdf = 0.0f;
    MediumStack media;

    glm::vec3 throughput() const { return 0.5f * (throughputS + throughputP); }

    /// Multiplies the throughput by an event's s and p factors; without polarization tracking, by their average.
    void scaleThroughput(const PolarizedFactor& factor, bool polarized) {
        if (polarized) {
            throughputS *= factor.s;
            throughputP *= factor.p;
        } else {
            const glm::vec3 average = 0.5f * (factor.s + factor.p);
            throughputS *= average;
            throughputP *= average;
        }
    }
};

/// A shadow ray and the color it adds to its pixel if nothing occludes it.
struct ShadowSample {
    Ray ray;
    glm::vec3 contribution;
    uint32_t pixelX, pixelY;
};

} // namespace wideray
