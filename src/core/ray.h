#pragma once
// A single ray and its closest hit, the currency of every tracer (the public wideray/ray.h), and the
// work a ray took.
#include <cstdint>

#include "wideray/ray.h"

namespace wideray {

/// Traversal work for one ray: the cost AOV and the kernel statistics.
struct TraversalCost {
    uint32_t nodes = 0;       ///< inner nodes whose children were tested
    uint32_t leaves = 0;      ///< leaves entered
    uint32_t primitives = 0;  ///< primitive tests (a triangle block counts its kBlockSize slots)
    uint32_t mailboxHits = 0; ///< kd-tree and grids: tests skipped, the ray having tested the primitive before

    TraversalCost& operator+=(const TraversalCost& o) {
        nodes += o.nodes;
        leaves += o.leaves;
        primitives += o.primitives;
        mailboxHits += o.mailboxHits;
        return *this;
    }
};

} // namespace wideray
