// SplitTriangle::split, the clipping of spatial splits, against exact clipping in double: each side's
// box holds every point of the triangle's part on that side within the given box (conservative), and
// is no larger than the exact part's bounds within that box plus the clipping's slack (tight).
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "accel/triangle_splitter.h"

namespace wideray {
namespace {

using Point = std::array<double, 3>;
using Polygon = std::vector<Point>;

/// The part of `polygon` where sign * (p[axis] - position) <= 0 (Sutherland-Hodgman, in double).
Polygon clip(const Polygon& polygon, int axis, double position, double sign) {
    Polygon out;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const Point& a = polygon[i];
        const Point& b = polygon[(i + 1) % polygon.size()];
        const double da = sign * (a[axis] - position), db = sign * (b[axis] - position);
        if (da <= 0) out.push_back(a);
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            const double t = da / (da - db);
            Point p;
            for (int k = 0; k < 3; ++k) p[k] = a[k] + t * (b[k] - a[k]);
            p[axis] = position;
            out.push_back(p);
        }
    }
    return out;
}

Polygon clipToBox(Polygon polygon, const BuildBox& box) {
    for (int axis = 0; axis < 3 && !polygon.empty(); ++axis) {
        polygon = clip(polygon, axis, box.lowerAt(axis), -1.0);
        if (!polygon.empty()) polygon = clip(polygon, axis, box.upperAt(axis), 1.0);
    }
    return polygon;
}

struct Check {
    std::mt19937 random{7};
    int crossings = 0, emptySides = 0;

    float coordinate(std::uniform_real_distribution<float>& d, int grid) {
        // Coordinates on a coarse grid too, so that vertices lie on planes and edges in them.
        const float x = d(random);
        return grid ? std::round(x * float(grid)) / float(grid) : x;
    }

    void run(const glm::vec3 (&v)[3], const BuildBox& box, int axis, float position) {
        const SplitTriangle triangle(v[0], v[1], v[2]);
        BuildBox left, right;
        triangle.split(box, axis, position, left, right);
        const Polygon whole{{v[0].x, v[0].y, v[0].z}, {v[1].x, v[1].y, v[1].z}, {v[2].x, v[2].y, v[2].z}};
        double magnitude = 0;
        for (const Point& p : whole)
            for (double c : p) magnitude = std::max(magnitude, std::abs(c));
        // The clipping widens crossing points by (|a| + |b|) 2^-20, and their rounding adds a few ulps.
        const double slack = 3 * magnitude * 0x1p-20;
        for (int side = 0; side < 2; ++side) {
            const BuildBox& result = side == 0 ? left : right;
            const double sign = side == 0 ? 1.0 : -1.0;
            const Polygon part = clip(whole, axis, position, sign);
            const Polygon inside = clipToBox(part, box);
            for (const Point& p : inside)
                for (int k = 0; k < 3; ++k) {
                    ASSERT_FALSE(result.empty()) << "side " << side << " lost a point of its part";
                    EXPECT_LE(result.lowerAt(k), p[k]);
                    EXPECT_GE(result.upperAt(k), p[k]);
                }
            if (result.empty()) {
                ++emptySides;
                continue;
            }
            // Tight: within the part's bounds (clipped by the box) plus the slack.
            ASSERT_FALSE(part.empty()) << "side " << side << " has a box but no part";
            for (int k = 0; k < 3; ++k) {
                double lo = part[0][k], hi = part[0][k];
                for (const Point& p : part) lo = std::min(lo, p[k]), hi = std::max(hi, p[k]);
                lo = std::max(lo, double(box.lowerAt(k)));
                hi = std::min(hi, double(box.upperAt(k)));
                EXPECT_GE(result.lowerAt(k), lo - slack) << "axis " << k;
                EXPECT_LE(result.upperAt(k), hi + slack) << "axis " << k;
            }
        }
        if (!left.empty() && !right.empty()) ++crossings;
    }
};

TEST(TriangleSplitter, SidesHoldTheExactPartsAndNoMoreThanTheSlack) {
    Check check;
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.0f, 1.0f);
    for (int trial = 0; trial < 20000; ++trial) {
        const int grid = trial % 3 == 0 ? 4 : 0;
        glm::vec3 v[3];
        for (glm::vec3& p : v) p = {check.coordinate(unit, grid), check.coordinate(unit, grid), check.coordinate(unit, grid)};
        if (trial % 7 == 0) v[2][trial % 3] = v[0][trial % 3] = v[1][trial % 3];  // in a plane of one axis
        BuildBox box;
        for (const glm::vec3& p : v) box.grow(_mm_setr_ps(p.x, p.y, p.z, 0.0f));
        if (trial % 2) {  // a reference already clipped: a random sub-box of the triangle's bounds
            for (int k = 0; k < 3; ++k) {
                const float lo = box.lowerAt(k), hi = box.upperAt(k);
                float a = lo + (hi - lo) * fraction(check.random), b = lo + (hi - lo) * fraction(check.random);
                if (a > b) std::swap(a, b);
                alignas(16) float l[4], u[4];
                _mm_store_ps(l, box.lower);
                _mm_store_ps(u, box.upper);
                l[k] = a;
                u[k] = b;
                box = BuildBox(_mm_load_ps(l), _mm_load_ps(u));
            }
        }
        const int axis = trial % 3;
        const float lo = box.lowerAt(axis), hi = box.upperAt(axis);
        float position = lo + (hi - lo) * fraction(check.random);
        if (grid && trial % 6 == 0) position = v[trial % 2][axis];  // through a vertex
        if (trial % 11 == 0) position = lo - 0.25f;                  // beside the triangle
        check.run(v, box, axis, position);
        if (HasFatalFailure()) FAIL() << "trial " << trial;
    }
    EXPECT_GT(check.crossings, 5000);
    EXPECT_GT(check.emptySides, 1000);
}

} // namespace
} // namespace wideray
