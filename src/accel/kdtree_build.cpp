#include "accel/kdtree_build.h"

#include <algorithm>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

namespace wideray {
namespace {

enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

/// A side of an item's box on one axis. Sorted by position, then ends before planars before starts,
/// which is the order the sweep needs.
struct Event {
    float pos;
    uint32_t type;
    uint32_t item;
    bool operator<(const Event& o) const {
        if (pos != o.pos) return pos < o.pos;
        if (type != o.type) return type < o.type;
        return item < o.item;
    }
};

using Events = std::vector<Event>;

/// The events of one node, one sorted list per axis.
struct NodeEvents {
    Events axis[3];
};

void addEvents(NodeEvents& e, const Bounds3f& box, uint32_t item) {
    for (int a = 0; a < 3; ++a) {
        if (box.lower[a] == box.upper[a]) {
            e.axis[a].push_back({box.lower[a], kPlanar, item});
        } else {
            e.axis[a].push_back({box.lower[a], kStart, item});
            e.axis[a].push_back({box.upper[a], kEnd, item});
        }
    }
}

enum Side : uint8_t { kBoth, kLeftOnly, kRightOnly };

struct Split {
    int axis = -1;
    float pos = 0;
    bool planarLeft = true;
    float cost = 0;
};

/// Nodes with more items build their two subtrees as parallel tasks.
constexpr size_t kParallelItems = 4096;

/// Appends a subtree built on its own: its child indices and item ranges move by where it lands.
void append(KdTree& out, const KdTree& piece) {
    const uint32_t nodeOffset = uint32_t(out.nodes.size()), itemOffset = uint32_t(out.items.size());
    for (KdNode n : piece.nodes) {
        if (n.isLeaf()) n.payload += itemOffset;
        else n.bits += nodeOffset << 2;
        out.nodes.push_back(n);
    }
    out.items.insert(out.items.end(), piece.items.begin(), piece.items.end());
    out.depth = std::max(out.depth, piece.depth);
    out.leaves += piece.leaves;
    out.emptyLeaves += piece.emptyLeaves;
}

class KdBuilder {
public:
    KdBuilder(const PrimitiveTable& table, const KdTreeConfig& config) : table_(table), config_(config) {
        maxDepth_ = config.maxDepth > 0 ? config.maxDepth
                                        : int(8.0 + 1.3 * std::log2(double(std::max<uint32_t>(table.size(), 1))));
        maxDepth_ = std::min(maxDepth_, kMaxKdTreeDepth);
    }

    /// Builds the subtree of a node into `out` (its root first, lower subtrees before upper ones).
    void build(NodeEvents& events, const Bounds3f& voxel, size_t count, int depth, KdTree& out) {
        out.depth = std::max(out.depth, depth + 1);
        const Split split = findSplit(events, voxel, count);
        if (depth + 1 >= maxDepth_ || split.axis < 0 || split.cost >= config_.intersectionCost * float(count)) {
            leaf(events, count, out);
            return;
        }
        NodeEvents left, right;
        size_t leftCount = 0, rightCount = 0;
        divide(events, split, left, right, leftCount, rightCount);
        events = NodeEvents();
        Bounds3f leftVoxel = voxel, rightVoxel = voxel;
        leftVoxel.upper[split.axis] = split.pos;
        rightVoxel.lower[split.axis] = split.pos;
        const size_t index = out.nodes.size();
        out.nodes.emplace_back();
        uint32_t upper;
        if (count >= kParallelItems) {
            KdTree lower, higher;
            tbb::parallel_invoke([&] { build(left, leftVoxel, leftCount, depth + 1, lower); },
                                 [&] { build(right, rightVoxel, rightCount, depth + 1, higher); });
            append(out, lower);
            upper = uint32_t(out.nodes.size());
            append(out, higher);
        } else {
            build(left, leftVoxel, leftCount, depth + 1, out);
            upper = uint32_t(out.nodes.size());
            build(right, rightVoxel, rightCount, depth + 1, out);
        }
        KdNode& node = out.nodes[index];
        node.split = split.pos;
        node.bits = (upper << 2) | uint32_t(split.axis);
    }

private:
    /// The sweep over each axis' events: left, planar and right counts at every candidate plane.
    Split findSplit(const NodeEvents& events, const Bounds3f& voxel, size_t count) const {
        Split best;
        best.cost = std::numeric_limits<float>::infinity();
        const glm::vec3 e = voxel.extent();
        const float area = e.x * e.y + e.y * e.z + e.z * e.x;
        if (!(area > 0.0f)) return best;
        const float kt = config_.traversalCost, ki = config_.intersectionCost;
        for (int k = 0; k < 3; ++k) {
            const int u = (k + 1) % 3, v = (k + 2) % 3;
            const float cap = e[u] * e[v], perimeter = e[u] + e[v];
            const Events& list = events.axis[k];
            size_t nl = 0, nr = count;
            for (size_t i = 0; i < list.size();) {
                const float p = list[i].pos;
                size_t ends = 0, planars = 0, starts = 0;
                for (; i < list.size() && list[i].pos == p && list[i].type == kEnd; ++i) ++ends;
                for (; i < list.size() && list[i].pos == p && list[i].type == kPlanar; ++i) ++planars;
                for (; i < list.size() && list[i].pos == p && list[i].type == kStart; ++i) ++starts;
                nr -= planars + ends;
                if (p > voxel.lower[k] && p < voxel.upper[k]) {
                    const float pl = (cap + (p - voxel.lower[k]) * perimeter) / area;
                    const float pr = (cap + (voxel.upper[k] - p) * perimeter) / area;
                    auto cost = [&](size_t l, size_t r) {
                        const float c = kt + ki * (pl * float(l) + pr * float(r));
                        return l == 0 || r == 0 ? c * config_.emptyBonus : c;
                    };
                    const float withLeft = cost(nl + planars, nr), withRight = cost(nl, nr + planars);
                    const float c = std::min(withLeft, withRight);
                    if (c < best.cost) best = {k, p, withLeft <= withRight, c};
                }
                nl += starts + planars;
            }
        }
        return best;
    }

    /// Classifies the items by the plane (Wald and Havran's algorithm 4), clips those across it to
    /// either side, and splits the event lists, keeping them sorted.
    void divide(const NodeEvents& events, const Split& s, NodeEvents& left, NodeEvents& right, size_t& leftCount,
                size_t& rightCount) {
        // The thread's scratch, per item; held only within this call (no task runs in between).
        Scratch& scratch = scratch_.local();
        if (scratch.side.empty()) {
            scratch.side.resize(table_.size());
            scratch.boxes.resize(table_.size());
        }
        std::vector<uint8_t>& side = scratch.side;
        std::vector<Bounds3f>& boxes = scratch.boxes;
        for (const Event& e : events.axis[0])
            if (e.type != kEnd) side[e.item] = kBoth;
        for (const Event& e : events.axis[s.axis]) {
            if (e.type == kEnd && e.pos <= s.pos) side[e.item] = kLeftOnly;
            else if (e.type == kStart && e.pos >= s.pos) side[e.item] = kRightOnly;
            else if (e.type == kPlanar)
                side[e.item] = e.pos < s.pos || (e.pos == s.pos && s.planarLeft) ? kLeftOnly : kRightOnly;
        }
        // The boxes (within this node) of the items across the plane, from their events.
        for (int a = 0; a < 3; ++a)
            for (const Event& e : events.axis[a]) {
                if (side[e.item] != kBoth) continue;
                if (e.type != kEnd) boxes[e.item].lower[a] = e.pos;
                if (e.type != kStart) boxes[e.item].upper[a] = e.pos;
            }
        NodeEvents newLeft, newRight;
        for (const Event& e : events.axis[0]) {
            if (e.type == kEnd) continue;
            if (side[e.item] == kLeftOnly) ++leftCount;
            if (side[e.item] == kRightOnly) ++rightCount;
            if (side[e.item] != kBoth) continue;
            Bounds3f l, r;
            clip(e.item, boxes[e.item], s, l, r);
            if (!l.empty()) {
                addEvents(newLeft, l, e.item);
                ++leftCount;
            }
            if (!r.empty()) {
                addEvents(newRight, r, e.item);
                ++rightCount;
            }
        }
        for (int a = 0; a < 3; ++a) {
            std::sort(newLeft.axis[a].begin(), newLeft.axis[a].end());
            std::sort(newRight.axis[a].begin(), newRight.axis[a].end());
            Events onlyLeft, onlyRight;
            for (const Event& e : events.axis[a]) {
                if (side[e.item] == kLeftOnly) onlyLeft.push_back(e);
                else if (side[e.item] == kRightOnly) onlyRight.push_back(e);
            }
            left.axis[a].resize(onlyLeft.size() + newLeft.axis[a].size());
            std::merge(onlyLeft.begin(), onlyLeft.end(), newLeft.axis[a].begin(), newLeft.axis[a].end(), left.axis[a].begin());
            right.axis[a].resize(onlyRight.size() + newRight.axis[a].size());
            std::merge(onlyRight.begin(), onlyRight.end(), newRight.axis[a].begin(), newRight.axis[a].end(),
                       right.axis[a].begin());
        }
    }

    /// The parts of an item's box (within the node) on either side of the plane: a triangle clipped
    /// (split clipping), a user primitive's box cut.
    void clip(uint32_t item, const Bounds3f& box, const Split& s, Bounds3f& l, Bounds3f& r) const {
        if (table_.isTriangle(item)) {
            const BuildBox b(_mm_setr_ps(box.lower.x, box.lower.y, box.lower.z, 0.0f),
                             _mm_setr_ps(box.upper.x, box.upper.y, box.upper.z, 0.0f));
            BuildBox lb, rb;
            table_.triangle(item).split(b, s.axis, s.pos, lb, rb);
            l = lb.empty() ? Bounds3f() : lb.bounds();
            r = rb.empty() ? Bounds3f() : rb.bounds();
            if (l.empty() && r.empty()) l = r = box;  // cannot happen for a box across the plane; kept safe
        } else {
            l = r = box;
            l.upper[s.axis] = std::min(l.upper[s.axis], s.pos);
            r.lower[s.axis] = std::max(r.lower[s.axis], s.pos);
        }
    }

    static void leaf(const NodeEvents& events, size_t count, KdTree& out) {
        KdNode node;
        node.payload = uint32_t(out.items.size());
        node.bits = (uint32_t(count) << 2) | KdNode::kLeafAxis;
        for (const Event& e : events.axis[0])
            if (e.type != kEnd) out.items.push_back(e.item);
        out.nodes.push_back(node);
        ++out.leaves;
        out.emptyLeaves += count == 0 ? 1 : 0;
    }

    /// Per item, for the node being divided: which side it goes to, its box within the node.
    struct Scratch {
        std::vector<uint8_t> side;
        std::vector<Bounds3f> boxes;
    };

    const PrimitiveTable& table_;
    const KdTreeConfig& config_;
    int maxDepth_ = kMaxKdTreeDepth;
    tbb::enumerable_thread_specific<Scratch> scratch_;
};

} // namespace

KdTree buildKdTree(const PrimitiveTable& table, const KdTreeConfig& config) {
    KdTree out;
    if (table.size() == 0) return out;
    out.bounds = table.bounds();
    NodeEvents events;
    for (auto& list : events.axis) list.reserve(2 * size_t(table.size()));
    for (uint32_t i = 0; i < table.size(); ++i) addEvents(events, table.box(i), i);
    for (auto& list : events.axis) tbb::parallel_sort(list.begin(), list.end());
    KdBuilder(table, config).build(events, out.bounds, table.size(), 0, out);
    return out;
}

} // namespace wideray
