#include "geometry/heightfield_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wideray {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Walks the cells of an n x n grid of cells of side `size` from (lowerX, lowerZ) that the ray's part
/// [t0, t1] crosses, in order, calling visit(i, j, ta, tb) with the ray's part in each; stops when
/// it returns true (and returns true).
template <class Visit>
bool walkCells(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, double lowerX, double lowerZ, double size,
               int n, Visit&& visit) {
    const double px = o.x + t0 * d.x, pz = o.z + t0 * d.z;
    auto cellOf = [&](double p, double lower) {
        const double f = std::floor((p - lower) / size);
        return !(f >= 0.0) ? 0 : (f >= double(n) ? n - 1 : int(f));
    };
    int i = cellOf(px, lowerX), j = cellOf(pz, lowerZ);
    const int stepI = d.x > 0 ? 1 : -1, stepJ = d.z > 0 ? 1 : -1;
    auto next = [&](int cell, int step, double lower, double o, double dir) {
        return dir == 0.0 ? kInf : (lower + double(cell + (step > 0 ? 1 : 0)) * size - o) / dir;
    };
    double nextI = next(i, stepI, lowerX, o.x, d.x), nextJ = next(j, stepJ, lowerZ, o.z, d.z);
    double ta = t0;
    for (;;) {
        const bool alongI = nextI < nextJ;
        const double tb = std::min(alongI ? nextI : nextJ, t1);
        if (visit(i, j, ta, tb)) return true;
        if (tb >= t1) return false;
        if (alongI) {
            i += stepI;
            if (i < 0 || i >= n) return false;
            nextI = next(i, stepI, lowerX, o.x, d.x);
        } else {
            j += stepJ;
            if (j < 0 || j >= n) return false;
            nextJ = next(j, stepJ, lowerZ, o.z, d.z);
        }
        ta = tb;
    }
}

/// Moeller and Trumbore's test in double, edges included; t in [tnear, tfar].
bool intersectTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                       const glm::dvec3& c, double tnear, double tfar, double& t) {
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return false;
    const double inv = 1.0 / det;
    const glm::dvec3 s = o - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    const double tHit = glm::dot(e2, q) * inv;
    if (!(tHit >= tnear && tHit <= tfar)) return false;
    t = tHit;
    return true;
}

} // namespace

HeightFieldGeometry::HeightFieldGeometry(const std::vector<HeightField>& fields) : models_(fields) {
    for (const HeightField& model : models_) {
        Field f{&model, ObjectSpace(model.transform)};
        const int res = model.terrain.resolution;
        f.tiles = (res + kTileCells - 1) / kTileCells;
        f.tileLow.assign(size_t(f.tiles) * size_t(f.tiles), std::numeric_limits<float>::infinity());
        f.tileHigh.assign(f.tileLow.size(), -std::numeric_limits<float>::infinity());
        for (int j = 0; j <= res; ++j)
            for (int i = 0; i <= res; ++i) {
                const float h = model.heights[size_t(j) * size_t(res + 1) + size_t(i)];
                // A vertex belongs to the tiles of every cell it is a corner of.
                for (int tj = std::max(0, (j - 1) / kTileCells); tj <= std::min(f.tiles - 1, j / kTileCells); ++tj)
                    for (int ti = std::max(0, (i - 1) / kTileCells); ti <= std::min(f.tiles - 1, i / kTileCells); ++ti) {
                        const size_t k = size_t(tj) * size_t(f.tiles) + size_t(ti);
                        f.tileLow[k] = std::min(f.tileLow[k], h);
                        f.tileHigh[k] = std::max(f.tileHigh[k], h);
                    }
            }
        const auto [lo, hi] = std::minmax_element(model.heights.begin(), model.heights.end());
        f.low = *lo;
        f.high = *hi;
        f.worldBounds = f.space.bounds({-1.0, f.low, -1.0}, {1.0, f.high, 1.0});
        fields_.push_back(std::move(f));
    }
}

double HeightFieldGeometry::height(const Field& f, int i, int j) const {
    const int res = f.model->terrain.resolution;
    return f.model->heights[size_t(j) * size_t(res + 1) + size_t(i)];
}

void HeightFieldGeometry::cellTriangle(const Field& f, int i, int j, int which, glm::dvec3& a, glm::dvec3& b,
                                       glm::dvec3& c) const {
    const double size = 2.0 / double(f.model->terrain.resolution);
    auto vertex = [&](int x, int z) { return glm::dvec3(-1.0 + x * size, height(f, x, z), -1.0 + z * size); };
    a = vertex(i, j);
    if (which == 0) {
        b = vertex(i + 1, j + 1);
        c = vertex(i + 1, j);
    } else {
        b = vertex(i, j + 1);
        c = vertex(i + 1, j + 1);
    }
}

bool HeightFieldGeometry::intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const {
    const Field& f = fields_[primId];
    glm::dvec3 o, d;
    f.space.ray(ray, o, d);
    double t0 = ray.tnear, t1 = tfar;
    if (!boxInterval({-1.0, f.low, -1.0}, {1.0, f.high, 1.0}, o, d, t0, t1)) return false;
    const int res = f.model->terrain.resolution;
    const double cell = 2.0 / double(res), tile = cell * kTileCells;
    double best = kInf;
    int bestCell[3] = {0, 0, 0};
    auto inCells = [&](int ti, int tj, double ta, double tb) {
        // Skip the tile if the ray's heights over its part miss the tile's height range.
        const double ya = o.y + ta * d.y, yb = o.y + tb * d.y;
        const size_t k = size_t(tj) * size_t(f.tiles) + size_t(ti);
        if (std::min(ya, yb) > f.tileHigh[k] + 1e-9 || std::max(ya, yb) < f.tileLow[k] - 1e-9) return false;
        return walkCells(o, d, ta, tb, -1.0 + ti * tile, -1.0 + tj * tile, cell, kTileCells, [&](int ci, int cj, double, double cb) {
            const int i = ti * kTileCells + ci, j = tj * kTileCells + cj;
            if (i >= res || j >= res) return false;
            for (int which = 0; which < 2; ++which) {
                glm::dvec3 a, b, c;
                cellTriangle(f, i, j, which, a, b, c);
                double tHit;
                if (intersectTriangle(o, d, a, b, c, ray.tnear, std::min(best, double(tfar)), tHit) && tHit < best) {
                    best = tHit;
                    bestCell[0] = i;
                    bestCell[1] = j;
                    bestCell[2] = which;
                }
            }
            // Cells come in order along the ray: a hit before this cell's exit is the closest.
            return best <= cb * (1.0 + 1e-12) + 1e-300;
        });
    };
    walkCells(o, d, t0, t1, -1.0, -1.0, tile, f.tiles, inCells);
    if (best == kInf) return false;
    t = float(best);
    if (!(t >= ray.tnear && t <= tfar)) return false;
    u = float(bestCell[0] * 2 + bestCell[2]);
    v = float(bestCell[1]);
    return true;
}

SurfacePoint HeightFieldGeometry::surface(const Ray& ray, const Hit& hit) const {
    const Field& f = fields_[hit.primId];
    const int code = int(hit.u), i = code / 2, which = code % 2, j = int(hit.v);
    glm::dvec3 a, b, c;
    cellTriangle(f, i, j, which, a, b, c);
    glm::dvec3 o, d;
    f.space.ray(ray, o, d);
    const glm::dvec3 p = o + double(hit.t) * d;
    SurfacePoint sp;
    sp.position = f.space.point(p);
    sp.geometricNormal = sp.shadingNormal = f.space.normal(glm::cross(b - a, c - a));
    sp.uv = {float(0.5 * (p.x + 1.0)), float(0.5 * (p.z + 1.0))};
    sp.material = f.model->material;
    return sp;
}

} // namespace wideray
