#include "raster/bernstein.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace streak::raster {

namespace {

constexpr int kMaxCoefficients = kMaxBernsteinDegree + 1;
using Coefficients = std::array<double, kMaxCoefficients>;
using Matrix = std::array<std::array<double, kMaxCoefficients>, kMaxCoefficients>;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// Pascal's triangle: C(n, k) for n <= kMaxBernsteinDegree.
constexpr Matrix kBinomial = [] {
    Matrix c{};
    for (int n = 0; n < kMaxCoefficients; ++n) {
        c[n][0] = c[n][n] = 1.0;
        for (int k = 1; k < n; ++k) c[n][k] = c[n - 1][k - 1] + c[n - 1][k];
    }
    return c;
}();

// The inverse of the Bernstein-Vandermonde matrix M[k][i] = B_i^d(k / d) for each degree d: the
// coefficients through values at t = k / d are inverse[d] * values. Gauss-Jordan with partial
// pivoting in long double (these matrices are well conditioned for d <= 6), so that the weights
// come out correctly rounded, e.g. exactly (-1/2, 2, -1/2) for d = 2.
const std::array<Matrix, kMaxCoefficients>& interpolationInverses() {
    static const std::array<Matrix, kMaxCoefficients> inverses = [] {
        using Row = std::array<long double, kMaxCoefficients>;
        std::array<Matrix, kMaxCoefficients> result{};
        result[0][0][0] = 1.0;
        for (int d = 1; d <= kMaxBernsteinDegree; ++d) {
            const int n = d + 1;
            std::array<Row, kMaxCoefficients> m{}, inv{};
            for (int k = 0; k < n; ++k) {
                const long double t = (long double)k / d;
                for (int i = 0; i < n; ++i) m[k][i] = kBinomial[d][i] * std::pow(t, i) * std::pow(1.0L - t, d - i);
                inv[k][k] = 1.0L;
            }
            for (int col = 0; col < n; ++col) {
                int pivot = col;
                for (int r = col + 1; r < n; ++r)
                    if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
                std::swap(m[col], m[pivot]);
                std::swap(inv[col], inv[pivot]);
                const long double scale = 1.0L / m[col][col];
                for (int c = 0; c < n; ++c) m[col][c] *= scale, inv[col][c] *= scale;
                for (int r = 0; r < n; ++r) {
                    if (r == col || m[r][col] == 0.0L) continue;
                    const long double f = m[r][col];
                    for (int c = 0; c < n; ++c) m[r][c] -= f * m[col][c], inv[r][c] -= f * inv[col][c];
                }
            }
            for (int i = 0; i < n; ++i)
                for (int k = 0; k < n; ++k) result[d][i][k] = double(inv[i][k]);
        }
        return result;
    }();
    return inverses;
}

double maxAbsCoefficient(const Bernstein& p) {
    double m = 0.0;
    for (int i = 0; i <= p.degree; ++i) m = std::max(m, std::abs(p.coefficients[i]));
    return m;
}

// De Casteljau's algorithm is the solvers' inner loop, at degrees <= 6. GCC 12 at -O3 vectorizes
// its short in-place loops into code three times slower (alias checks and epilogues around one or
// two vector steps), so those kernels are kept scalar.
#if defined(__GNUC__) && !defined(__clang__)
#define STREAK_SCALAR_LOOPS __attribute__((optimize("no-tree-vectorize")))
#else
#define STREAK_SCALAR_LOOPS
#endif

// De Casteljau at t, in place, keeping [0, t]: c[k] ends as the first point of level k.
STREAK_SCALAR_LOOPS void keepLeft(Coefficients& c, int d, double t) {
    const double s = 1.0 - t;
    for (int k = 1; k <= d; ++k)
        for (int i = d; i >= k; --i) c[i] = s * c[i - 1] + t * c[i];
}

// De Casteljau at t, in place, keeping [t, 1]: c[d - k] ends as the last point of level k.
STREAK_SCALAR_LOOPS void keepRight(Coefficients& c, int d, double t) {
    const double s = 1.0 - t;
    for (int k = 1; k <= d; ++k)
        for (int i = 0; i <= d - k; ++i) c[i] = s * c[i] + t * c[i + 1];
}

struct ValueAndSlope {
    double value, slope;
};

// De Casteljau stopped one level early: the last two points give the value and the derivative.
STREAK_SCALAR_LOOPS ValueAndSlope evaluateWithSlope(const Bernstein& p, double t) {
    if (p.degree == 0) return {p.coefficients[0], 0.0};
    Coefficients c = p.coefficients;
    const double s = 1.0 - t;
    for (int level = p.degree; level > 1; --level)
        for (int i = 0; i < level; ++i) c[i] = s * c[i] + t * c[i + 1];
    return {s * c[0] + t * c[1], p.degree * (c[1] - c[0])};
}

#undef STREAK_SCALAR_LOOPS

// ---- Root finding ----------------------------------------------------------------------------
//
// Both solvers work on p normalized to max |coefficient| 1, so every tolerance below is relative
// to the polynomial's own size (scale invariance).

// Every coefficient below this is nothing but noise: the polynomial is zero. Far below any edge
// equation in pixel units, far above underflow.
constexpr double kZeroScale = 1e-100;
// An end value (or a coefficient) of a normalized polynomial within this of zero is zero to
// rounding: a few eps per degree of the largest coefficient.
double roundingBand(int degree) { return 4.0 * (degree + 1) * kEpsilon; }
// The rounding of a polynomial restricted to an interval [a, b] by de Casteljau subdivisions:
// each computed coefficient is the exact restriction of coefficients perturbed by about 2 d eps
// relative, so its error is bounded by that much of the restriction of |b| (the size of the
// terms there, which near a root can be far below the largest coefficient); and the interval's
// ends are doubles, only good to an ulp, which moves the values by the slope times that (near
// t = 1 a root can sit where the terms are tiny but an ulp of t is not). Clipping against a band
// of twice that around the axis, instead of the axis, keeps a root on an interval's end or at a
// clip boundary from being cut away by rounding, and a polynomial inside the band on an interval
// is zero there to rounding.
constexpr double kBandFactor = 8.0;
double localBand(const Bernstein& local, const Bernstein& size, double a, double b) {
    const int d = local.degree;
    double step = 0.0;  // max |c_{i+1} - c_i|: the slope is at most d step / (b - a)
    for (int i = 0; i < d; ++i) step = std::max(step, std::abs(local.coefficients[i + 1] - local.coefficients[i]));
    const double slope = b > a ? d * step / (b - a) : 0.0;
    return kBandFactor * ((d + 1) * kEpsilon * size.upperBound() + kEpsilon * std::max(std::abs(a), std::abs(b)) * slope);
}
// Roots closer than this are one root.
constexpr double kMergeDistance = 1e-12;
// Candidates this far outside [0, 1] (after polishing) are clamped onto it, farther ones dropped.
constexpr double kOutside = 1e-9;
// A Newton polish never moves a root by more than this (nor by half the gap to its neighbours).
constexpr double kMaxPolishStep = 1e-3;
// Clipping stops on intervals this narrow.
constexpr double kWidthTolerance = 1e-13;
// A clip keeping more than this fraction of the interval is followed by a split in halves.
constexpr double kSplitFraction = 0.5;
// Safety net against pathological inputs; ordinary polynomials take tens of steps.
constexpr int kMaxClipSteps = 2000;
// Leading power coefficients below this (|a_k| t^k changes p by at most that on [0, 1]) are
// dropped before the closed forms, which lose accuracy with huge monic coefficients.
constexpr double kNegligibleLeading = 1e-12;
// A leading power coefficient this small beside the next means a root beyond ~1 / kFarLeading,
// divided out before the closed forms.
constexpr double kFarLeading = 1e-3;
// Complex pairs this close to the real axis may be a near-double pair of real roots lost to the
// discriminant's rounding: checked against p's own Taylor expansion.
constexpr double kPairImaginary = 1e-5;
// Real candidates closer than this are refined as a pair.
constexpr double kPairGap = 1e-3;
// Closed forms of three or more roots (cubic roots, or the quartic's resolvent roots) clustered
// within this, relative, are too inaccurate to polish: Bezier clipping solves those.
constexpr double kClusterSpread = 1e-2;
// A polished closed-form root with |p| above this many times its rounding did not converge.
constexpr double kResidualLimit = 1e3;

// Normalizes p; false (counted as nothing solved) when there is nothing to solve: zero, or every
// coefficient strictly of one sign with the end values clear of rounding (a root at 0 or 1 to
// rounding is returned, so those polynomials are solved).
bool normalizedForSolving(const Bernstein& p, Bernstein& normalized, BernsteinRootCounts& counts) {
    const double scale = maxAbsCoefficient(p);
    if (!(scale > kZeroScale) || !std::isfinite(scale)) {
        ++counts.noSignChange;
        return false;
    }
    normalized = (1.0 / scale) * p;
    const auto& c = normalized.coefficients;
    const int d = p.degree;
    const double band = roundingBand(d);
    const bool positive = std::all_of(c.begin(), c.begin() + d + 1, [](double x) { return x > 0.0; });
    const bool negative = std::all_of(c.begin(), c.begin() + d + 1, [](double x) { return x < 0.0; });
    if ((positive || negative) && std::abs(c[0]) > band && std::abs(c[d]) > band) {
        ++counts.noSignChange;
        return false;
    }
    return true;
}

Bernstein absolute(const Bernstein& p) {
    Bernstein a = p;
    for (int i = 0; i <= p.degree; ++i) a.coefficients[i] = std::abs(a.coefficients[i]);
    return a;
}

Bernstein normalized(const Bernstein& p) {
    const double scale = maxAbsCoefficient(p);
    return scale > 0.0 ? (1.0 / scale) * p : p;
}

// p / (t - r) for p(r) = 0 (to rounding), in Bernstein form. With t - r = -r B_0^1 + (1 - r) B_1^1
// the product formula gives p_k = -r (d - k) / d q_k + (1 - r) k / d q_{k-1}. Solving it upwards
// from p_0 amplifies errors by k (1 - r) / ((d - k) r) per step, downwards from p_d by the inverse:
// each is used where it shrinks them (k below and above d r), meeting at k = m, whose equation is
// the dropped remainder.
Bernstein deflated(const Bernstein& p, double r) {
    const int d = p.degree;
    assert(d >= 1);
    Bernstein q;
    q.degree = d - 1;
    const auto& a = p.coefficients;
    auto& b = q.coefficients;
    const int m = std::clamp(int(std::lround(d * r)), 0, d);
    for (int k = 0; k < m; ++k) {
        const double previous = k > 0 ? b[k - 1] : 0.0;
        b[k] = (k * (1.0 - r) * previous - d * a[k]) / ((d - k) * r);
    }
    for (int k = d; k > m; --k) {
        const double next = k < d ? b[k] : 0.0;
        b[k - 1] = (d * a[k] + (d - k) * r * next) / (k * (1.0 - r));
    }
    return q;
}

// p / t for p(0) = 0: p_k = k / d q_{k-1}; exact up to the dropped p_0.
Bernstein withoutRootAtZero(const Bernstein& p) {
    const int d = p.degree;
    Bernstein q;
    q.degree = d - 1;
    for (int k = 1; k <= d; ++k) q.coefficients[k - 1] = p.coefficients[k] * d / k;
    return q;
}

// p / (1 - t) for p(1) = 0: p_k = (d - k) / d q_k.
Bernstein withoutRootAtOne(const Bernstein& p) {
    const int d = p.degree;
    Bernstein q;
    q.degree = d - 1;
    for (int k = 0; k < d; ++k) q.coefficients[k] = p.coefficients[k] * d / (d - k);
    return q;
}

// Where the lower boundary of the convex hull of the points (i / d, y_i), y_0 > level, first comes
// down to level, walking it from the left (gift wrapping: the next vertex is the one seen at the
// least slope); 2 when it never does.
double lowerHullCrossing(const Coefficients& y, int d, double level) {
    for (int i = 0; i < d;) {
        int next = i + 1;
        for (int k = i + 2; k <= d; ++k)
            if ((y[k] - y[i]) * (next - i) <= (y[next] - y[i]) * (k - i)) next = k;  // ties: the farther
        if (y[next] <= level) return (i + (next - i) * (y[i] - level) / (y[i] - y[next])) / d;
        i = next;
    }
    return 2.0;
}

// The range of x in [0, 1] where the convex hull of the control points (i / d, c_i) meets the band
// |y| <= band: it holds every root of the polynomial and of anything within the band of it. From
// an end outside the band, the section begins where the hull's near boundary (the lower one from
// above the band, the upper one from below) reaches the band; the far side of the hull is there
// already.
bool clipToBand(const Coefficients& c, int d, double band, double& lo, double& hi) {
    Coefficients y;
    auto from = [&](bool right) {
        const double end = right ? c[d] : c[0];
        if (std::abs(end) <= band) return 0.0;
        const double s = end > 0.0 ? 1.0 : -1.0;  // mirrored so that the end is above the band
        for (int i = 0; i <= d; ++i) y[i] = s * (right ? c[d - i] : c[i]);
        return lowerHullCrossing(y, d, band);
    };
    lo = from(false);
    if (lo > 1.0) return false;
    hi = 1.0 - from(true);
    return lo <= hi;
}

bool withinBand(const Coefficients& c, int d, double band) {
    for (int i = 0; i <= d; ++i)
        if (std::abs(c[i]) > band) return false;
    return true;
}

// Newton steps on p from r while each shortens no further than maxStep and does not increase
// |p|: a polish refines a root, it never wanders off to a neighbouring one. None once p is
// rounding noise at r (a few eps of its terms' size there): from there Newton's steps are noise.
double polished(const Bernstein& p, double r, double maxStep, int maxSteps, std::int64_t& iterations) {
    ValueAndSlope f = evaluateWithSlope(p, r);
    const double noise = (p.degree + 1) * kEpsilon * absolute(p)(r);
    for (int k = 0; k < maxSteps && std::abs(f.value) > noise && f.slope != 0.0; ++k) {
        const double step = f.value / f.slope;
        if (!(std::abs(step) <= maxStep)) break;
        const double next = r - step;
        const ValueAndSlope g = evaluateWithSlope(p, next);
        ++iterations;
        if (!(std::abs(g.value) <= std::abs(f.value))) break;
        r = next, f = g;
        if (std::abs(step) <= 2.0 * kEpsilon) break;  // converged to rounding
    }
    return r;
}

// Sorts and merges candidates closer than kMergeDistance; returns the new count.
int sortedUnique(double* values, int count) {
    std::sort(values, values + count);
    int n = 0;
    for (int i = 0; i < count; ++i)
        if (n == 0 || values[i] - values[n - 1] > kMergeDistance) values[n++] = values[i];
    return n;
}

// The sign of p over [a, b] judged by its largest sample: 0 when p is rounding noise there.
int pieceSign(const Bernstein& p, double a, double b) {
    double best = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double v = p(a + (b - a) * (k + 0.5) / 3.0);
        if (std::abs(v) > std::abs(best)) best = v;
    }
    return std::abs(best) <= roundingBand(p.degree) ? 0 : (best > 0.0 ? 1 : -1);
}

// The candidate roots of the normalized polynomial p made into the solvers' answer: polished on p
// (each by at most half the gap to its neighbours, so no two collapse onto one root), clamped onto
// [0, 1], ascending, merged, at most p.degree of them.
int finishedRoots(const Bernstein& p, double* candidates, int count, int polishSteps, std::span<double, kMaxBernsteinDegree> roots,
                  BernsteinRootCounts& counts, bool* converged = nullptr) {
    count = sortedUnique(candidates, count);
    std::array<double, 2 * kMaxCoefficients> result;
    int n = 0;
    for (int i = 0; i < count; ++i) {
        double r = candidates[i];
        if (r != 0.0 && r != 1.0) {  // exact end roots stay exact
            double maxStep = kMaxPolishStep;
            if (i > 0) maxStep = std::min(maxStep, 0.5 * (r - candidates[i - 1]));
            if (i + 1 < count) maxStep = std::min(maxStep, 0.5 * (candidates[i + 1] - r));
            r = polished(p, r, maxStep, polishSteps, counts.iterations);
            if (converged && std::abs(p(r)) > kResidualLimit * roundingBand(p.degree) * absolute(p)(r)) *converged = false;
        }
        if (r < -kOutside || r > 1.0 + kOutside) continue;
        result[n++] = std::clamp(r, 0.0, 1.0);
    }
    n = sortedUnique(result.data(), n);
    // More roots than the degree (ends zero to rounding beside roots just inside them, or a pair
    // split by its Taylor expansion): drop those that separate no change of sign, ends first,
    // then the closest.
    while (n > p.degree) {
        int drop = -1;
        for (int pass = 0; pass < 2 && drop < 0; ++pass)
            for (int i = 0; i < n && drop < 0; ++i) {
                if (pass == 0 && result[i] != 0.0 && result[i] != 1.0) continue;
                const double a = i > 0 ? result[i - 1] : 0.0, b = i + 1 < n ? result[i + 1] : 1.0;
                if (pieceSign(p, a, result[i]) * pieceSign(p, result[i], b) >= 0) drop = i;
            }
        if (drop < 0) {
            drop = 1;
            for (int i = 2; i < n; ++i)
                if (result[i] - result[i - 1] < result[drop] - result[drop - 1]) drop = i;
        }
        std::copy(result.begin() + drop + 1, result.begin() + n, result.begin() + drop);
        --n;
    }
    std::copy(result.begin(), result.begin() + n, roots.begin());
    counts.roots += n;
    return n;
}

// Bezier clipping of the normalized polynomial p. Each root found is divided out of the working
// polynomial q, and the search goes on with q on the intervals still pending: every remaining
// root of q lies in one of them, and a root clustered with the one removed no longer shares an
// interval with it.
int clippedRoots(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts& counts) {
    ++counts.solves;
    // Roots divided out, then (after them) roots only recorded: the space finishedRoots takes.
    std::array<double, 2 * kMaxCoefficients> found;
    int count = 0, loose = 0;
    std::array<double, kMaxCoefficients> looseRoots;
    Bernstein q = p;
    // Exact roots at the ends divide out exactly. Ends zero only to rounding are roots too, but
    // recorded, not divided out: the polynomial may still have finer structure near them, with
    // roots just inside, which the search below resolves.
    while (q.degree > 0 && q.coefficients[0] == 0.0) found[count++] = 0.0, q = normalized(withoutRootAtZero(q));
    while (q.degree > 0 && q.coefficients[q.degree] == 0.0) found[count++] = 1.0, q = normalized(withoutRootAtOne(q));
    const bool zeroAtStart = std::abs(q.coefficients[0]) <= roundingBand(q.degree);
    const bool zeroAtEnd = std::abs(q.coefficients[q.degree]) <= roundingBand(q.degree);
    if (zeroAtStart) looseRoots[loose++] = 0.0;
    if (zeroAtEnd) looseRoots[loose++] = 1.0;
    Bernstein size = absolute(q);

    // An interval carries the signs of q at (just inside) its ends, fixed once for all: at a
    // split the midpoint's value decides both halves' shared sign, and a clip keeps the signs
    // (what it cuts off has no root). So a change of sign is seen by exactly one of the intervals
    // it could fall in, however rounding splits the hairs at their boundaries. Pending intervals
    // all lie right of the current one (the left half goes first), so dividing out a root of the
    // current one leaves their signs alone.
    // A sign is certain where the value was clear of the band.
    struct Interval {
        double a, b;
        bool negativeA, negativeB, certainA, certainB;
    };
    // Each split leaves one half pending; halving depth is bounded by kWidthTolerance.
    std::array<Interval, 128> pending;
    int top = 0;
    pending[top++] = {0.0, 1.0, q.coefficients[0] < 0.0, q.coefficients[q.degree] < 0.0, !zeroAtStart, !zeroAtEnd};
    // A change of sign between certain signs is a root as accurate as rounding allows, divided
    // out. One at a sign that was noise (inside a cluster of roots, or a flat stretch, within
    // rounding of zero) is only recorded: its position may be off by the stretch's width, and
    // dividing it out would leave a remainder that could swamp finer structure elsewhere.
    auto addRoot = [&](double r, bool certain) {
        if (certain) {
            found[count++] = r;
            q = normalized(deflated(q, r));
            size = absolute(q);
        } else if (loose < int(looseRoots.size())) {
            looseRoots[loose++] = r;
        }
    };
    int steps = 0;
    while (top > 0 && q.degree > 0 && steps < kMaxClipSteps) {
        Interval iv = pending[--top];
        while (steps < kMaxClipSteps) {
            ++steps;
            const Bernstein local = q.restricted(iv.a, iv.b);
            const double band = localBand(local, size.restricted(iv.a, iv.b), iv.a, iv.b);
            double lo, hi;
            if (!clipToBand(local.coefficients, q.degree, band, lo, hi)) {
                // No root here: clear of the band throughout. Unless its ends' signs differ: then
                // an end value's sign was rounding noise and the change of sign sits at that end.
                if (iv.negativeA != iv.negativeB)
                    addRoot(std::abs(local.coefficients[0]) < std::abs(local.coefficients[q.degree]) ? iv.a : iv.b, false);
                break;
            }
            const double w = iv.b - iv.a;
            // What a clip cuts off is clear of the band: the signs it leaves are certain.
            const Interval clipped{lo <= 0.0 ? iv.a : iv.a + lo * w, hi >= 1.0 ? iv.b : iv.a + hi * w, iv.negativeA, iv.negativeB,
                                   iv.certainA || lo > 0.0, iv.certainB || hi < 1.0};
            if (clipped.b - clipped.a <= kWidthTolerance || withinBand(local.coefficients, q.degree, band)) {
                // Converged (or zero to rounding throughout). Without a change of sign, a tangency
                // (or a pair within rounding): no root to report.
                if (iv.negativeA != iv.negativeB) addRoot(0.5 * (clipped.a + clipped.b), clipped.certainA && clipped.certainB);
                break;
            }
            if (hi - lo > kSplitFraction && top < int(pending.size())) {
                // Too little progress: several roots (or a tangency) here. Split them apart.
                const double mid = 0.5 * (clipped.a + clipped.b), atMid = q(mid);
                const bool certainMid = std::abs(atMid) > band;
                pending[top++] = {mid, clipped.b, atMid < 0.0, clipped.negativeB, certainMid, clipped.certainB};
                iv = {clipped.a, mid, clipped.negativeA, atMid < 0.0, clipped.certainA, certainMid};
            } else {
                iv = clipped;
            }
        }
        if (steps >= kMaxClipSteps && top < int(pending.size())) pending[top++] = iv;
    }
    // Out of steps (never seen in practice): the unresolved intervals' midpoints stand in for
    // their roots, so that a root is at worst inaccurate, not missing.
    if (steps >= kMaxClipSteps)
        while (top > 0 && count < p.degree) {
            const Interval iv = pending[--top];
            found[count++] = 0.5 * (iv.a + iv.b);
        }
    counts.iterations += steps;
    std::copy(looseRoots.begin(), looseRoots.begin() + loose, found.begin() + count);
    return finishedRoots(p, found.data(), count + loose, 2, roots, counts);
}

// ---- Closed forms (power basis) ----

struct ClosedFormCandidates {
    std::array<double, 2 * kMaxCoefficients> real;
    int realCount = 0;
    // Complex pairs near the real axis: re +- i im.
    std::array<double, 4> pairRe, pairIm;
    int pairCount = 0;

    // The closed form cannot be trusted here: a cluster of three or more roots (or resolvent
    // roots), whose formulas lose most digits.
    bool illConditioned = false;

    void addReal(double x) { real[realCount++] = x; }
    void addPair(double re, double im) {
        if (pairCount < int(pairRe.size())) pairRe[pairCount] = re, pairIm[pairCount++] = im;
    }
};

// b^2 - 4ac with the products' rounding errors recovered by fma (Kahan): the discriminant is the
// difference of nearly equal terms exactly when the roots are nearly double.
double discriminant(double a, double b, double c) {
    const double bb = b * b, bbError = std::fma(b, b, -bb);
    const double ac = 4.0 * a * c, acError = std::fma(4.0 * a, c, -ac);
    return (bb - ac) + (bbError - acError);
}

// a x^2 + b x + c, a != 0, without cancellation (Numerical Recipes 5.6).
void solveQuadratic(double a, double b, double c, ClosedFormCandidates& out) {
    const double disc = discriminant(a, b, c);
    if (disc < 0.0) {
        out.addPair(-b / (2.0 * a), std::sqrt(-disc) / (2.0 * std::abs(a)));
        return;
    }
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) {  // b = 0 and disc = 0: c = 0, a double root at 0
        out.addReal(0.0);
        return;
    }
    out.addReal(q / a);
    out.addReal(c / q);
}

// Real roots of x^3 + a x^2 + b x + c (1 or 3 of them, written to x), and the complex pair when
// there is one (Numerical Recipes 5.6: trigonometric for three real roots, Cardano otherwise).
int solveCubicMonic(double a, double b, double c, double* x, double* pairRe = nullptr, double* pairIm = nullptr) {
    const double q = (a * a - 3.0 * b) / 9.0;
    const double r = (a * (2.0 * a * a - 9.0 * b) + 27.0 * c) / 54.0;
    const double q3 = q * q * q, r2 = r * r;
    const double shift = a / 3.0;
    if (r2 < q3) {
        const double theta = std::acos(std::clamp(r / std::sqrt(q3), -1.0, 1.0));
        const double m = -2.0 * std::sqrt(q);
        constexpr double kTwoPi = 2.0 * std::numbers::pi;
        x[0] = m * std::cos(theta / 3.0) - shift;
        x[1] = m * std::cos((theta + kTwoPi) / 3.0) - shift;
        x[2] = m * std::cos((theta - kTwoPi) / 3.0) - shift;
        return 3;
    }
    const double big = -std::copysign(std::cbrt(std::abs(r) + std::sqrt(r2 - q3)), r);
    const double small = big != 0.0 ? q / big : 0.0;
    x[0] = big + small - shift;
    if (pairRe) *pairRe = -0.5 * (big + small) - shift, *pairIm = 0.5 * std::sqrt(3.0) * std::abs(big - small);
    return 1;
}

void solveCubic(double a3, double a2, double a1, double a0, ClosedFormCandidates& out) {
    std::array<double, 3> x;
    double re = 0.0, im = 0.0;
    const int n = solveCubicMonic(a2 / a3, a1 / a3, a0 / a3, x.data(), &re, &im);
    for (int i = 0; i < n; ++i) out.addReal(x[i]);
    if (n == 1) out.addPair(re, im);
    // All three roots within kClusterSpread: the formulas' differences of nearly equal terms
    // (q ~ spread^2, r ~ spread^3) leave few digits.
    const double spread = n == 3 ? std::max({x[0], x[1], x[2]}) - std::min({x[0], x[1], x[2]}) : std::abs(x[0] - re) + im;
    if (spread < kClusterSpread * (1.0 + std::abs(x[0]))) out.illConditioned = true;
}

// Newton steps on the monic cubic y^3 + a y^2 + b y + c, kept while they reduce it.
double polishedCubicRoot(double a, double b, double c, double y) {
    auto value = [&](double v) { return ((v + a) * v + b) * v + c; };
    double f = value(y);
    for (int k = 0; k < 2 && f != 0.0; ++k) {
        const double slope = (3.0 * y + 2.0 * a) * y + b;
        if (slope == 0.0) break;
        const double next = y - f / slope, g = value(next);
        if (!(std::abs(g) < std::abs(f))) break;
        y = next, f = g;
    }
    return y;
}

// x^4 + a x^3 + b x^2 + c x + d = (x^2 + G x + H)(x^2 + g x + h) by Neumark's method (as in
// Herbison-Evans, "Solving quartics and cubics for graphics"): with y = G g, G and g are the roots
// of z^2 - a z + y and H, h those of z^2 - (b - y) z + d, y a root of the resolvent cubic
// y^3 - 2b y^2 + (b^2 + ac - 4d) y + (c^2 - abc + a^2 d). The most isolated resolvent root whose
// factors are real is used (see below); of the two square roots the better conditioned one is
// taken and the other half-difference derived from it, and each factor pair's smaller member
// comes from its product (G g = y, H h = d) rather than from a cancelling difference.
void solveQuarticMonic(double a, double b, double c, double d, ClosedFormCandidates& out) {
    const double rp = -2.0 * b, rq = b * b + a * c - 4.0 * d, rr = (c - a * b) * c + a * a * d;
    std::array<double, 3> ys;
    double pairRe = 0.0, pairIm = 0.0;
    const int ny = solveCubicMonic(rp, rq, rr, ys.data(), &pairRe, &pairIm);
    for (int i = 0; i < ny; ++i) ys[i] = polishedCubicRoot(rp, rq, rr, ys[i]);
    // Descending (at most three; by hand, since std::sort's insertion sort trips -Warray-bounds).
    for (int i = 1; i < ny; ++i)
        for (int j = i; j > 0 && ys[j] > ys[j - 1]; --j) std::swap(ys[j], ys[j - 1]);
    // The most isolated resolvent root first: the pairings y = (x_i + x_j)(x_k + x_l) that split a
    // cluster of roots differ only by swapping clustered roots, so they are nearly equal (and
    // their cubic roots inaccurate), while the one keeping each cluster in one factor stands
    // alone. Neumark's largest root is preferred on ties.
    const double isolation = ny == 3 ? std::max(ys[0] - ys[1], ys[1] - ys[2]) : std::hypot(ys[0] - pairRe, pairIm);
    if (ny == 3 && ys[1] - ys[2] > ys[0] - ys[1]) std::swap(ys[0], ys[2]);
    // No resolvent root stands alone: three or four clustered roots, where the factorization is
    // ill-conditioned too (its error grows as the inverse square of the cluster's spread).
    const double yScale = std::max({std::abs(ys[0]), std::abs(ys[ny - 1]), std::abs(b), 1e-300});
    if (isolation < kClusterSpread * yScale) {
        out.illConditioned = true;
        return;
    }

    const double asq = a * a;
    for (int i = 0; i < ny; ++i) {
        const double y = ys[i];
        const double bmy = b - y;
        double gdis = asq - 4.0 * y, hdis = bmy * bmy - 4.0 * d;
        // Rounding scales of the two discriminants.
        const double gerr = 8.0 * kEpsilon * (asq + 4.0 * std::abs(y)), herr = 8.0 * kEpsilon * (bmy * bmy + 4.0 * std::abs(d));
        if ((gdis < -gerr || hdis < -herr) && i + 1 < ny) continue;  // complex factors: another root
        gdis = std::max(gdis, 0.0), hdis = std::max(hdis, 0.0);
        const double g1 = 0.5 * a, h1 = 0.5 * bmy;
        // g2 h2 = (a h1 - c) / 2 pairs the signs: H = h1 + h2 goes with G = g1 + g2.
        double g2, h2;
        if (gdis * (bmy * bmy + 4.0 * std::abs(d)) >= hdis * (asq + 4.0 * std::abs(y))) {
            const double root = std::sqrt(gdis);
            g2 = 0.5 * root;
            h2 = root != 0.0 ? (a * h1 - c) / root : 0.5 * std::sqrt(hdis);
        } else {
            const double root = std::sqrt(hdis);
            h2 = 0.5 * root;
            g2 = root != 0.0 ? (a * h1 - c) / root : 0.5 * std::sqrt(gdis);
        }
        double bigG = g1 + g2, smallG = g1 - g2;
        if (std::abs(smallG) > std::abs(bigG)) std::swap(bigG, smallG), h2 = -h2;
        if (bigG != 0.0) smallG = y / bigG;
        double bigH = h1 + h2, smallH = h1 - h2;  // bigH pairs with bigG
        if (std::abs(bigH) >= std::abs(smallH)) {
            if (bigH != 0.0) smallH = d / bigH;
        } else if (smallH != 0.0) {
            bigH = d / smallH;
        }
        solveQuadratic(1.0, bigG, bigH, out);
        solveQuadratic(1.0, smallG, smallH, out);
        return;
    }
}

// A close pair of roots around center (two close real candidates, or a complex pair near the real
// axis that may be a real pair lost to the discriminant's rounding): p's own second-order Taylor
// expansion there says whether it is a real pair and where, far more accurately than the closed
// forms' power coefficients. Newton's method, by contrast, crawls towards a near-double pair.
// Repeated at the pair's midpoint, where the expansion is most accurate. False (roots untouched)
// when the expansion has no real roots within reach.
bool refinedPair(const Bernstein& p, double center, double reach, double& r0, double& r1) {
    if (p.degree < 2) return false;
    const Bernstein second = p.derivative().derivative();
    for (int k = 0; k < 2; ++k) {
        const ValueAndSlope f = evaluateWithSlope(p, center);
        const double curvature = second(center);
        if (curvature == 0.0) return false;
        // curvature / 2 h^2 + slope h + value = 0, without cancellation
        const double disc = discriminant(0.5 * curvature, f.slope, f.value);
        if (disc < 0.0) return false;  // complex, or a double root: no change of sign
        const double q = -0.5 * (f.slope + std::copysign(std::sqrt(disc), f.slope));
        const double h0 = q / (0.5 * curvature), h1 = q != 0.0 ? f.value / q : 0.0;
        if (!(std::max(std::abs(h0), std::abs(h1)) <= reach)) return false;
        r0 = center + std::min(h0, h1), r1 = center + std::max(h0, h1);
        center = 0.5 * (r0 + r1);
    }
    return true;
}

// Lowers the degree of the power form a (of a normalized polynomial) while its leading
// coefficient is small: the closed forms' monic coefficients would be huge, and the small roots
// they give differences of huge numbers. With a_d small beside a_{d-1} there is a real root
// X ~ -a_{d-1} / a_d far outside [0, 1]; dividing p by (1 - w x), w = 1 / X the small root of the
// reversed polynomial, gives the rest: s_k = a_k + w s_{k-1}, which only damps errors (|w| < 1).
// Failing that, a leading coefficient below kNegligibleLeading is dropped (changing p by at most
// that on [0, 1]).
int reducedPowerDegree(Coefficients& a, int degree) {
    while (degree > 0) {
        const double lead = a[degree], next = a[degree - 1];
        if (std::abs(lead) < kFarLeading * std::abs(next)) {
            // Newton on the reversed polynomial r(w) = sum_k a_k w^(d - k) from its linear root.
            const double w0 = -lead / next;
            double w = w0;
            for (int k = 0; k < 2; ++k) {
                double r = 0.0, slope = 0.0;
                for (int i = 0; i <= degree; ++i) slope = slope * w + r, r = r * w + a[i];
                if (slope == 0.0) break;
                w -= r / slope;
            }
            if (std::isfinite(w) && std::abs(w) <= 2.0 * std::abs(w0)) {  // Newton stayed with the far root
                for (int k = 1; k < degree; ++k) a[k] += w * a[k - 1];
                a[degree] = 0.0;
                --degree;
                continue;
            }
        }
        if (std::abs(lead) > kNegligibleLeading) break;
        a[degree--] = 0.0;
    }
    return degree;
}

int closedFormRoots(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts& counts) {
    Coefficients a = p.toPower();
    const int degree = reducedPowerDegree(a, p.degree);
    if (degree > 4) return clippedRoots(p, roots, counts);
    ClosedFormCandidates c;
    const double band = roundingBand(p.degree);
    if (std::abs(p.coefficients[0]) <= band) c.addReal(0.0);
    if (std::abs(p.coefficients[p.degree]) <= band) c.addReal(1.0);
    switch (degree) {
        case 1: c.addReal(-a[0] / a[1]); break;
        case 2: solveQuadratic(a[2], a[1], a[0], c); break;
        case 3: solveCubic(a[3], a[2], a[1], a[0], c); break;
        case 4: solveQuarticMonic(a[3] / a[4], a[2] / a[4], a[1] / a[4], a[0] / a[4], c); break;
        default: break;  // a constant: nothing but the ends
    }
    if (c.illConditioned) return clippedRoots(p, roots, counts);
    // Only candidates near [0, 1] are worth polishing.
    int n = 0;
    for (int i = 0; i < c.realCount; ++i)
        if (c.real[i] >= -1e-6 && c.real[i] <= 1.0 + 1e-6) c.real[n++] = c.real[i];
    std::sort(c.real.begin(), c.real.begin() + n);
    // Close pairs: refined together where that leaves them closer to roots (not where, say, a
    // third root nearby spoils the expansion).
    for (int i = 0; i + 1 < n; ++i) {
        const double gap = c.real[i + 1] - c.real[i];
        double r0, r1;
        if (gap < kPairGap && c.real[i] != 0.0 && c.real[i + 1] != 1.0 &&
            refinedPair(p, 0.5 * (c.real[i] + c.real[i + 1]), 2.0 * gap + kPairImaginary, r0, r1) &&
            std::max(std::abs(p(r0)), std::abs(p(r1))) < std::max(std::abs(p(c.real[i])), std::abs(p(c.real[i + 1])))) {
            c.real[i] = r0, c.real[i + 1] = r1;
            ++i;
        }
    }
    for (int i = 0; i < c.pairCount; ++i) {
        double r0, r1;
        if (c.pairIm[i] <= kPairImaginary && c.pairRe[i] >= -kPairImaginary && c.pairRe[i] <= 1.0 + kPairImaginary &&
            refinedPair(p, c.pairRe[i], 4.0 * kPairImaginary, r0, r1))
            c.real[n++] = r0, c.real[n++] = r1;
    }
    BernsteinRootCounts attempt;
    bool converged = true;
    const int count = finishedRoots(p, c.real.data(), n, 2, roots, attempt, &converged);
    counts.iterations += attempt.iterations;
    if (!converged) return clippedRoots(p, roots, counts);  // a root the polish could not pin down
    ++counts.solves;
    counts.roots += attempt.roots;
    return count;
}

}  // namespace

double Bernstein::operator()(double t) const { return evaluateWithSlope(*this, t).value; }

double Bernstein::lowerBound() const { return *std::min_element(coefficients.begin(), coefficients.begin() + degree + 1); }
double Bernstein::upperBound() const { return *std::max_element(coefficients.begin(), coefficients.begin() + degree + 1); }

Bernstein Bernstein::elevated(int newDegree) const {
    assert(newDegree >= degree && newDegree <= kMaxBernsteinDegree);
    Bernstein r = *this;
    // One degree at a time: b'_i = i / (d + 1) b_{i-1} + (1 - i / (d + 1)) b_i.
    for (int d = degree; d < newDegree; ++d) {
        Coefficients next{};
        next[0] = r.coefficients[0];
        next[d + 1] = r.coefficients[d];
        for (int i = 1; i <= d; ++i) next[i] = (i * r.coefficients[i - 1] + (d + 1 - i) * r.coefficients[i]) / (d + 1);
        r.coefficients = next;
        r.degree = d + 1;
    }
    return r;
}

Bernstein Bernstein::restricted(double t0, double t1) const {
    Bernstein r = *this;
    auto& c = r.coefficients;
    if (t0 == 0.0) {
        if (t1 != 1.0) keepLeft(c, degree, t1);
    } else if (t1 == 1.0) {
        keepRight(c, degree, t0);
    } else if (1.0 - t1 < t0) {
        // Nearer 1: cut at t0 exactly first; the rounded second parameter then moves only t1, by
        // an ulp of the interval's width.
        keepRight(c, degree, t0);
        keepLeft(c, degree, (t1 - t0) / (1.0 - t0));
    } else {
        keepLeft(c, degree, t1);
        keepRight(c, degree, t0 / t1);
    }
    return r;
}

Bernstein Bernstein::derivative() const {
    Bernstein r;
    if (degree == 0) return r;
    r.degree = degree - 1;
    for (int i = 0; i < degree; ++i) r.coefficients[i] = degree * (coefficients[i + 1] - coefficients[i]);
    return r;
}

Bernstein Bernstein::fromPower(std::span<const double> power) {
    assert(power.size() <= std::size_t(kMaxCoefficients));
    Bernstein r;
    if (power.empty()) return r;
    const int d = int(power.size()) - 1;
    r.degree = d;
    // t^j = sum_{i >= j} C(i, j) / C(d, j) B_i^d.
    for (int i = 0; i <= d; ++i) {
        double sum = 0.0;
        for (int j = 0; j <= i; ++j) sum += kBinomial[i][j] / kBinomial[d][j] * power[j];
        r.coefficients[i] = sum;
    }
    return r;
}

std::array<double, kMaxBernsteinDegree + 1> Bernstein::toPower() const {
    // B_i^d = C(d, i) t^i (1 - t)^(d - i) expanded: a_j = C(d, j) sum_{i <= j} (-1)^(j - i) C(j, i) b_i.
    Coefficients a{};
    for (int j = 0; j <= degree; ++j) {
        double sum = 0.0;
        for (int i = 0; i <= j; ++i) sum += ((j - i) % 2 ? -1.0 : 1.0) * kBinomial[j][i] * coefficients[i];
        a[j] = kBinomial[degree][j] * sum;
    }
    return a;
}

Bernstein Bernstein::interpolating(std::span<const double> values) {
    assert(values.size() <= std::size_t(kMaxCoefficients));
    Bernstein r;
    if (values.empty()) return r;
    const int d = int(values.size()) - 1;
    const Matrix& inverse = interpolationInverses()[d];
    r.degree = d;
    for (int i = 0; i <= d; ++i) {
        double sum = 0.0;
        for (int k = 0; k <= d; ++k) sum += inverse[i][k] * values[k];
        r.coefficients[i] = sum;
    }
    return r;
}

Bernstein operator+(const Bernstein& a, const Bernstein& b) {
    const int d = std::max(a.degree, b.degree);
    Bernstein r = a.elevated(d);
    const Bernstein e = b.elevated(d);
    for (int i = 0; i <= d; ++i) r.coefficients[i] += e.coefficients[i];
    return r;
}

Bernstein operator-(const Bernstein& a, const Bernstein& b) { return a + (-1.0) * b; }

Bernstein operator*(double s, const Bernstein& a) {
    Bernstein r = a;
    for (int i = 0; i <= a.degree; ++i) r.coefficients[i] *= s;
    return r;
}

Bernstein operator*(const Bernstein& a, const Bernstein& b) {
    const int m = a.degree, n = b.degree;
    assert(m + n <= kMaxBernsteinDegree);
    Bernstein r;
    r.degree = m + n;
    // B_i^m B_j^n = C(m, i) C(n, j) / C(m + n, i + j) B_{i+j}^{m+n}.
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j)
            r.coefficients[i + j] += kBinomial[m][i] * kBinomial[n][j] / kBinomial[m + n][i + j] * a.coefficients[i] * b.coefficients[j];
    return r;
}

std::array<std::array<double, 4>, 4> bezierThroughSamples(int n) {
    assert(n >= 0 && n <= 3);
    std::array<std::array<double, 4>, 4> w{};
    const Matrix& inverse = interpolationInverses()[n];
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) w[j][i] = inverse[j][i];
    return w;
}

std::vector<double> bezierFittingSamples(int n, int samples) {
    assert(n >= 0 && n <= 3 && samples >= n + 1);
    // The normal equations (A^T A) W = A^T with A[i][j] = B_j^n(t_i), by Gauss-Jordan in long
    // double: (n + 1) x (n + 1), well conditioned for evenly spaced samples.
    const int m = n + 1;
    std::vector<long double> a(std::size_t(samples) * std::size_t(m));
    for (int i = 0; i < samples; ++i) {
        const long double t = (long double)i / (samples - 1);
        for (int j = 0; j < m; ++j) a[std::size_t(i * m + j)] = kBinomial[n][j] * std::pow(t, j) * std::pow(1.0L - t, n - j);
    }
    std::vector<long double> normal(std::size_t(m * m), 0.0L), rhs(std::size_t(m * samples), 0.0L);
    for (int j = 0; j < m; ++j) {
        for (int k = 0; k < m; ++k)
            for (int i = 0; i < samples; ++i) normal[std::size_t(j * m + k)] += a[std::size_t(i * m + j)] * a[std::size_t(i * m + k)];
        for (int i = 0; i < samples; ++i) rhs[std::size_t(j * samples + i)] = a[std::size_t(i * m + j)];
    }
    for (int col = 0; col < m; ++col) {
        int pivot = col;
        for (int r = col + 1; r < m; ++r)
            if (std::abs(normal[std::size_t(r * m + col)]) > std::abs(normal[std::size_t(pivot * m + col)])) pivot = r;
        for (int c = 0; c < m; ++c) std::swap(normal[std::size_t(col * m + c)], normal[std::size_t(pivot * m + c)]);
        for (int c = 0; c < samples; ++c) std::swap(rhs[std::size_t(col * samples + c)], rhs[std::size_t(pivot * samples + c)]);
        const long double scale = 1.0L / normal[std::size_t(col * m + col)];
        for (int c = 0; c < m; ++c) normal[std::size_t(col * m + c)] *= scale;
        for (int c = 0; c < samples; ++c) rhs[std::size_t(col * samples + c)] *= scale;
        for (int r = 0; r < m; ++r) {
            if (r == col) continue;
            const long double f = normal[std::size_t(r * m + col)];
            for (int c = 0; c < m; ++c) normal[std::size_t(r * m + c)] -= f * normal[std::size_t(col * m + c)];
            for (int c = 0; c < samples; ++c) rhs[std::size_t(r * samples + c)] -= f * rhs[std::size_t(col * samples + c)];
        }
    }
    return std::vector<double>(rhs.begin(), rhs.end());
}

int rootsByBezierClipping(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts* counts) {
    BernsteinRootCounts local;
    Bernstein q;
    const int n = normalizedForSolving(p, q, local) ? clippedRoots(q, roots, local) : 0;
    if (counts) counts->add(local);
    return n;
}

int rootsInClosedForm(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts* counts) {
    BernsteinRootCounts local;
    Bernstein q;
    const int n = normalizedForSolving(p, q, local) ? closedFormRoots(q, roots, local) : 0;
    if (counts) counts->add(local);
    return n;
}

Slefe slefeOf(const Bernstein& p, int segments) {
    assert(segments >= 1 && segments <= Slefe::kMaxSegments);
    Slefe s;
    s.segments = segments;
    const int d = p.degree;
    s.lower.fill(std::numeric_limits<double>::infinity());
    s.upper.fill(-std::numeric_limits<double>::infinity());
    // On each piece p is its chord plus sum_j (c_j - chord_j) B_j (the chord in degree d has the
    // coefficients c_0 + (c_d - c_0) j / d), so by the convex hull property it lies between the
    // chord shifted by the least and by the greatest difference. At a breakpoint the enclosure
    // takes the looser of the two adjacent pieces' lines: below (above) both at both ends of each
    // piece, its linear interpolation stays below (above) each piece's line, hence p.
    for (int i = 0; i < segments; ++i) {
        const Bernstein piece = p.restricted(double(i) / segments, i + 1 == segments ? 1.0 : double(i + 1) / segments);
        const double c0 = piece.coefficients[0], cd = piece.coefficients[d];
        double below = 0.0, above = 0.0;
        for (int j = 1; j < d; ++j) {
            const double difference = piece.coefficients[j] - (c0 + (cd - c0) * j / d);
            below = std::min(below, difference), above = std::max(above, difference);
        }
        s.lower[i] = std::min(s.lower[i], c0 + below), s.lower[i + 1] = std::min(s.lower[i + 1], cd + below);
        s.upper[i] = std::max(s.upper[i], c0 + above), s.upper[i + 1] = std::max(s.upper[i + 1], cd + above);
    }
    // The subdivision's rounding (and an evaluation's) is a few d eps of the coefficients' size:
    // widen by more than that so the enclosure holds in floating point too.
    const double margin = 8.0 * (d + 1) * kEpsilon * maxAbsCoefficient(p);
    for (int i = 0; i <= segments; ++i) s.lower[i] -= margin, s.upper[i] += margin;
    for (int i = segments + 1; i <= Slefe::kMaxSegments; ++i) s.lower[i] = s.upper[i] = 0.0;
    return s;
}

}  // namespace streak::raster
