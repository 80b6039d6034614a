#pragma once
// Real roots of polynomials of degree up to 6 in an interval, robustly: the roots of the derivative
// split the interval into pieces where the polynomial is monotonic, and each piece with a sign change
// is solved by Newton's method kept inside its bracket (bisection where a step would leave it). No
// closed-form quartic formula, whose cancellations lose the roots of grazing rays.
#include <cmath>

namespace wideray {

/// c[0] + c[1] x + ... + c[degree] x^degree at x (Horner).
inline double evaluatePolynomial(const double* c, int degree, double x) {
    double y = c[degree];
    for (int i = degree - 1; i >= 0; --i) y = y * x + c[i];
    return y;
}

namespace detail {

/// The root of a monotonic polynomial between a and b, where it changes sign.
inline double bracketedRoot(const double* c, const double* dc, int degree, double a, double b, double fa) {
    double x = 0.5 * (a + b);
    for (int i = 0; i < 100; ++i) {
        const double f = evaluatePolynomial(c, degree, x);
        if (f == 0.0) return x;
        if ((f < 0.0) == (fa < 0.0)) a = x, fa = f;
        else b = x;
        const double df = evaluatePolynomial(dc, degree - 1, x);
        double next = df != 0.0 ? x - f / df : 0.5 * (a + b);
        if (!(next > a && next < b)) next = 0.5 * (a + b);  // Newton would leave the bracket
        if (std::fabs(next - x) <= 1e-15 * std::fabs(x) || b - a <= 1e-15 * (std::fabs(a) + std::fabs(b))) return next;
        x = next;
    }
    return x;
}

} // namespace detail

/// The real roots of c[0] + ... + c[degree] x^degree in [lo, hi], ascending; returns their count
/// (`roots` needs room for 8; degree <= 6). A polynomial that is zero everywhere has none. Roots of even multiplicity
/// (the polynomial touches zero without crossing) are found only where it reaches exactly zero.
inline int polynomialRoots(const double* c, int degree, double lo, double hi, double* roots) {
    while (degree > 0 && c[degree] == 0.0) --degree;
    if (degree == 0 || !(lo <= hi)) return 0;
    if (degree == 1) {
        const double x = -c[0] / c[1];
        if (!(x >= lo && x <= hi)) return 0;
        roots[0] = x;
        return 1;
    }
    double dc[6] = {};
    for (int i = 0; i < degree; ++i) dc[i] = double(i + 1) * c[i + 1];
    double ends[9];
    int n = 0;
    ends[n++] = lo;
    n += polynomialRoots(dc, degree - 1, lo, hi, ends + 1);
    ends[n++] = hi;
    int count = 0;
    double fa = evaluatePolynomial(c, degree, ends[0]);
    if (fa == 0.0) roots[count++] = ends[0];
    for (int i = 0; i + 1 < n; ++i) {
        const double a = ends[i], b = ends[i + 1];
        const double fb = evaluatePolynomial(c, degree, b);
        if (fb == 0.0) {
            if (count == 0 || roots[count - 1] != b) roots[count++] = b;
        } else if (fa != 0.0 && (fa < 0.0) != (fb < 0.0)) {
            roots[count++] = detail::bracketedRoot(c, dc, degree, a, b, fa);
        }
        fa = fb;
    }
    return count;
}

} // namespace wideray
