#include "raster/bernstein.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

namespace streak::raster {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// The solvers treat an end value within a few eps (per degree) of the largest coefficient as zero.
constexpr double kEndZero = 2.0 * kEpsilon;

// A double in [lo, hi) with 53 random bits (Rng::uniform has 24).
double uniformDouble(Rng& rng, double lo, double hi) { return lo + (hi - lo) * (double(rng.next() >> 11) * 0x1p-53); }

Bernstein randomBernstein(Rng& rng, int degree, double lo = -1.0, double hi = 1.0) {
    Bernstein p;
    p.degree = degree;
    for (int i = 0; i <= degree; ++i) p.coefficients[i] = uniformDouble(rng, lo, hi);
    return p;
}

double horner(const std::array<double, kMaxBernsteinDegree + 1>& a, int degree, double t) {
    double v = 0.0;
    for (int i = degree; i >= 0; --i) v = v * t + a[i];
    return v;
}

double maxAbsCoefficient(const Bernstein& p) {
    double m = 0.0;
    for (int i = 0; i <= p.degree; ++i) m = std::max(m, std::abs(p.coefficients[i]));
    return m;
}

// The size of p's terms at t, sum_i |b_i| B_i(t): what rounding in its coefficients is relative to.
double termSize(const Bernstein& p, double t) {
    Bernstein a = p;
    for (int i = 0; i <= p.degree; ++i) a.coefficients[i] = std::abs(a.coefficients[i]);
    return a(t);
}

// The power form of scale * prod (t - r_i).
std::vector<double> powerFromRoots(const std::vector<double>& roots, double scale) {
    std::vector<double> a{scale};
    for (double r : roots) {
        std::vector<double> next(a.size() + 1, 0.0);
        for (std::size_t i = 0; i < a.size(); ++i) next[i + 1] += a[i], next[i] -= r * a[i];
        a = next;
    }
    return a;
}

Bernstein fromRoots(const std::vector<double>& roots, double scale) { return Bernstein::fromPower(powerFromRoots(roots, scale)); }

using Solver = int (*)(const Bernstein&, std::span<double, kMaxBernsteinDegree>, BernsteinRootCounts*);

struct NamedSolver {
    const char* name;
    Solver solve;
};
const NamedSolver kSolvers[] = {{"clipping", rootsByBezierClipping}, {"closed form", rootsInClosedForm}};

std::vector<double> solve(Solver solver, const Bernstein& p, BernsteinRootCounts* counts = nullptr) {
    std::array<double, kMaxBernsteinDegree> roots;
    roots.fill(std::numeric_limits<double>::quiet_NaN());
    const int n = solver(p, roots, counts);
    return {roots.begin(), roots.begin() + n};
}

// The solvers' contract on p: at most p.degree roots, ascending, distinct, in [0, 1], and between
// consecutive roots (and the ends) p keeps one sign. Checked at samplesPerPiece points per piece;
// values within 1e-9 of the largest coefficient are ignored: there, p is close enough to zero
// that its sign does not matter to the caller (and near a cluster of roots closer than the
// solvers can resolve it is rounding noise).
testing::AssertionResult keepsSignBetweenRoots(const Bernstein& p, const std::vector<double>& roots, int samplesPerPiece = 20) {
    if (int(roots.size()) > p.degree) return testing::AssertionFailure() << roots.size() << " roots for degree " << p.degree;
    for (std::size_t i = 0; i < roots.size(); ++i) {
        if (!(roots[i] >= 0.0 && roots[i] <= 1.0)) return testing::AssertionFailure() << "root " << roots[i] << " outside [0, 1]";
        if (i > 0 && !(roots[i] > roots[i - 1])) return testing::AssertionFailure() << "roots not ascending at " << i;
    }
    const double tolerance = 1e-9 * maxAbsCoefficient(p);
    std::vector<double> breaks{0.0};
    breaks.insert(breaks.end(), roots.begin(), roots.end());
    breaks.push_back(1.0);
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        int sign = 0;
        for (int j = 0; j <= samplesPerPiece; ++j) {
            const double t = breaks[k] + (breaks[k + 1] - breaks[k]) * j / samplesPerPiece;
            const double v = p(t);
            if (std::abs(v) <= tolerance) continue;
            const int s = v > 0.0 ? 1 : -1;
            if (sign != 0 && s != sign)
                return testing::AssertionFailure() << "sign changes inside [" << breaks[k] << ", " << breaks[k + 1] << "] at " << t;
            sign = s;
        }
    }
    return testing::AssertionSuccess();
}

// How far rounding of p's coefficients can move its simple root x: a few eps of the terms' size
// over the slope. Near-double roots (small slope) are correspondingly less determined.
double rootTolerance(const Bernstein& p, double x) {
    const double slope = std::abs(p.derivative()(x));
    return 1e-9 + 1e3 * kEpsilon * termSize(p, x) / slope;
}

// The root near r of p as stored (its coefficients rounded from the exact product, which moves
// clustered roots by far more than the solvers' error): Newton's method in long double.
double storedRoot(const Bernstein& p, double r) {
    long double x = r;
    for (int k = 0; k < 60; ++k) {
        std::array<long double, kMaxBernsteinDegree + 1> c;
        for (int i = 0; i <= p.degree; ++i) c[i] = p.coefficients[i];
        for (int level = p.degree; level > 1; --level)
            for (int i = 0; i < level; ++i) c[i] = (1.0L - x) * c[i] + x * c[i + 1];
        const long double value = (1.0L - x) * c[0] + x * c[1], slope = p.degree * (c[1] - c[0]);
        if (slope == 0.0L) break;
        const long double step = value / slope;
        if (std::abs(step) > 1e-3L) return r;  // not converging here: keep the exact root
        x -= step;
    }
    return double(x);
}

// Solves scale * prod (t - r_i) with both solvers and checks: the contract above; every returned
// root near a true root (simple: within rootTolerance of the stored polynomial's root, a
// conditioning bound of about 1e-9 for separated roots; multiple roots of multiplicity m are only
// determined to within (eps)^(1/m) and are checked by the sign pattern alone); every simple root
// in [0, 1] at least 1e-6 from the others returned.
void expectRoots(const std::vector<double>& exactRoots, double scale) {
    const Bernstein p = fromRoots(exactRoots, scale);
    std::vector<double> trueRoots = exactRoots;
    for (double& r : trueRoots)
        if (std::count(exactRoots.begin(), exactRoots.end(), r) == 1 && r != 0.0 && r != 1.0) r = storedRoot(p, r);
    for (const NamedSolver& solver : kSolvers) {
        SCOPED_TRACE(solver.name);
        const std::vector<double> got = solve(solver.solve, p);
        EXPECT_TRUE(keepsSignBetweenRoots(p, got));
        for (double x : got) {
            std::size_t nearest = 0;
            for (std::size_t i = 0; i < trueRoots.size(); ++i)
                if (std::abs(trueRoots[i] - x) < std::abs(trueRoots[nearest] - x)) nearest = i;
            const double r = trueRoots[nearest];
            const int multiplicity = int(std::count(exactRoots.begin(), exactRoots.end(), exactRoots[nearest]));
            if (multiplicity == 1) EXPECT_NEAR(x, r, rootTolerance(p, r)) << "returned root " << x;
            else EXPECT_NEAR(x, r, 1e-4) << "returned root " << x << " of a root of multiplicity " << multiplicity;
        }
        for (std::size_t i = 0; i < trueRoots.size(); ++i) {
            const double r = trueRoots[i];
            if (r < 0.0 || r > 1.0) continue;
            // A root at an end is only one to the solvers when p is zero there to rounding; the
            // conversion from the power form may have moved it just outside.
            if ((r == 0.0 || r == 1.0) && std::abs(p(r)) > kEndZero * (p.degree + 1) * maxAbsCoefficient(p)) continue;
            bool separated = true;
            for (std::size_t j = 0; j < trueRoots.size(); ++j)
                if (j != i && std::abs(trueRoots[j] - r) < 1e-6) separated = false;
            if (!separated) continue;
            const double tolerance = rootTolerance(p, r);
            EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](double x) { return std::abs(x - r) <= tolerance; }))
                << "missing root " << r;
        }
    }
}

// The roots of the solver's answer where p changes sign: a root separating pieces of opposite
// sign (a piece's sign is that of its largest sample; pieces where p is rounding noise are
// skipped, so a tight cluster returned as one or as several roots gives the same answer).
std::vector<double> signChangingRoots(const Bernstein& p, const std::vector<double>& roots) {
    const double noise = 1e-12 * maxAbsCoefficient(p);
    std::vector<double> breaks{0.0};
    breaks.insert(breaks.end(), roots.begin(), roots.end());
    breaks.push_back(1.0);
    std::vector<double> changes;
    int lastSign = 0;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        double best = 0.0;
        for (int j = 1; j < 20; ++j) {
            const double v = p(breaks[k] + (breaks[k + 1] - breaks[k]) * j / 20.0);
            if (std::abs(v) > std::abs(best)) best = v;
        }
        if (std::abs(best) <= noise) continue;
        const int sign = best > 0.0 ? 1 : -1;
        if (lastSign != 0 && sign != lastSign) changes.push_back(breaks[k]);
        lastSign = sign;
    }
    return changes;
}

}  // namespace

// ---- Bernstein algebra ----

TEST(Bernstein, HandCheckedQuadratic) {
    // (t - 1/4)(t - 3/4) = t^2 - t + 3/16: b_0 = 3/16, b_1 = 3/16 - 1/2, b_2 = 3/16 - 1 + 1.
    const std::array<double, 3> power{3.0 / 16.0, -1.0, 1.0};
    const Bernstein p = Bernstein::fromPower(power);
    ASSERT_EQ(p.degree, 2);
    EXPECT_DOUBLE_EQ(p.coefficients[0], 3.0 / 16.0);
    EXPECT_DOUBLE_EQ(p.coefficients[1], -5.0 / 16.0);
    EXPECT_DOUBLE_EQ(p.coefficients[2], 3.0 / 16.0);
    EXPECT_DOUBLE_EQ(p(0.5), -1.0 / 16.0);
    EXPECT_DOUBLE_EQ(p.lowerBound(), -5.0 / 16.0);
    EXPECT_DOUBLE_EQ(p.upperBound(), 3.0 / 16.0);
    const auto back = p.toPower();
    for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(back[i], power[i]);
    for (const NamedSolver& solver : kSolvers) {
        const std::vector<double> roots = solve(solver.solve, p);
        ASSERT_EQ(roots.size(), 2u) << solver.name;
        EXPECT_NEAR(roots[0], 0.25, 1e-15) << solver.name;
        EXPECT_NEAR(roots[1], 0.75, 1e-15) << solver.name;
    }
}

TEST(Bernstein, EvaluationMatchesPowerForm) {
    // Both evaluations are stable to a few eps of the terms' size; 1e-13 of the power
    // coefficients' sum bounds either.
    Rng rng(1);
    for (int trial = 0; trial < 200; ++trial) {
        const Bernstein p = randomBernstein(rng, int(rng.next() % 7));
        const auto a = p.toPower();
        double size = 0.0;
        for (int i = 0; i <= p.degree; ++i) size += std::abs(a[i]);
        for (int k = 0; k <= 50; ++k) {
            const double t = k / 50.0;
            EXPECT_NEAR(p(t), horner(a, p.degree, t), 1e-13 * size) << p.degree << " " << t;
        }
        // fromPower after toPower is the identity (to rounding of the conversions).
        const Bernstein q = Bernstein::fromPower(std::span<const double>(a.data(), p.degree + 1));
        ASSERT_EQ(q.degree, p.degree);
        for (int i = 0; i <= p.degree; ++i) EXPECT_NEAR(q.coefficients[i], p.coefficients[i], 1e-13 * size);
    }
}

TEST(Bernstein, ElevationRestrictionAndDerivative) {
    Rng rng(2);
    // Every degree, and every way restricted() cuts: at t1 only, at t0 only, nearer 0, nearer 1.
    for (int trial = 0; trial < 280; ++trial) {
        const int degree = trial % 7;
        const Bernstein p = randomBernstein(rng, degree);
        const Bernstein e = p.elevated(kMaxBernsteinDegree);
        ASSERT_EQ(e.degree, kMaxBernsteinDegree);
        double t0 = uniformDouble(rng, 0.0, 1.0), t1 = uniformDouble(rng, 0.0, 1.0);
        if (t0 > t1) std::swap(t0, t1);
        if (trial / 7 % 4 == 1) t0 = 0.0;
        if (trial / 7 % 4 == 2) t1 = 1.0;
        const Bernstein r = p.restricted(t0, t1);
        const Bernstein dp = p.derivative();
        const auto a = p.toPower();
        for (int k = 0; k <= 20; ++k) {
            const double s = k / 20.0;
            // Coefficients are O(1): all these are stable to a few eps times the degree.
            EXPECT_NEAR(e(s), p(s), 1e-14);
            EXPECT_NEAR(r(s), p(t0 + s * (t1 - t0)), 1e-14);
            double powerSlope = 0.0;
            for (int i = degree; i >= 1; --i) powerSlope = powerSlope * s + i * a[i];
            EXPECT_NEAR(dp(s), powerSlope, 1e-11);
            // Central difference: truncation h^2 p''' / 6 and rounding eps / h, both below 1e-6.
            const double h = 1e-5;
            EXPECT_NEAR(dp(s), (p(s + h) - p(s - h)) / (2.0 * h), 1e-6);
        }
        EXPECT_EQ(dp.degree, std::max(degree - 1, 0));
    }
    // Degree 0 stays degree 0 with derivative zero; restricting to [0, 1] changes nothing.
    Bernstein c;
    c.coefficients[0] = 3.0;
    EXPECT_EQ(c.derivative().degree, 0);
    EXPECT_EQ(c.derivative().coefficients[0], 0.0);
    const Bernstein p = randomBernstein(rng, 5);
    EXPECT_EQ(p.restricted(0.0, 1.0).coefficients, p.coefficients);
}

TEST(Bernstein, ArithmeticIsPointwise) {
    Rng rng(3);
    for (int trial = 0; trial < 200; ++trial) {
        const int m = int(rng.next() % 4), n = int(rng.next() % (kMaxBernsteinDegree - m + 1));
        const Bernstein a = randomBernstein(rng, m), b = randomBernstein(rng, n);
        const double s = uniformDouble(rng, -3.0, 3.0);
        const Bernstein sum = a + b, difference = a - b, scaled = s * a, product = a * b;
        EXPECT_EQ(sum.degree, std::max(m, n));
        EXPECT_EQ(product.degree, m + n);
        for (int k = 0; k <= 20; ++k) {
            const double t = k / 20.0;
            EXPECT_NEAR(sum(t), a(t) + b(t), 1e-14);
            EXPECT_NEAR(difference(t), a(t) - b(t), 1e-14);
            EXPECT_NEAR(scaled(t), s * a(t), 1e-14);
            EXPECT_NEAR(product(t), a(t) * b(t), 1e-14);
        }
    }
}

TEST(Bernstein, LeastSquaresFitOfSamples) {
    // With n + 1 samples the fit is the curve through them; with more it reproduces any curve of
    // degree <= n exactly (the residual is zero).
    for (int n = 1; n <= 3; ++n) {
        const std::vector<double> through = bezierFittingSamples(n, n + 1);
        const auto w = bezierThroughSamples(n);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) EXPECT_NEAR(through[std::size_t(j * (n + 1) + i)], w[std::size_t(j)][std::size_t(i)], 1e-12);
        const int samples = 4 * n + 1;
        const std::vector<double> fit = bezierFittingSamples(n, samples);
        Bernstein curve;
        curve.degree = n;
        for (int j = 0; j <= n; ++j) curve.coefficients[std::size_t(j)] = 0.3 * j * j - 0.7 * j + 0.1;
        for (int j = 0; j <= n; ++j) {
            double control = 0.0;
            for (int i = 0; i < samples; ++i) control += fit[std::size_t(j * samples + i)] * curve(double(i) / (samples - 1));
            EXPECT_NEAR(control, curve.coefficients[std::size_t(j)], 1e-12) << "n " << n << " control " << j;
        }
    }
}

TEST(Bernstein, InterpolationAndBezierThroughSamples) {
    Rng rng(4);
    for (int size = 1; size <= kMaxBernsteinDegree + 1; ++size) {
        std::vector<double> values(size);
        for (double& v : values) v = uniformDouble(rng, -2.0, 2.0);
        const Bernstein p = Bernstein::interpolating(values);
        ASSERT_EQ(p.degree, size - 1);
        for (int i = 0; i < size; ++i) EXPECT_NEAR(p(size == 1 ? 0.5 : double(i) / (size - 1)), values[i], 1e-13) << size;
    }
    // P1 = 2 P(1/2) - (P0 + P2) / 2, exactly; for cubics P1 = (-5 P0 + 18 P(1/3) - 9 P(2/3) + 2 P3) / 6.
    const auto w2 = bezierThroughSamples(2);
    EXPECT_EQ(w2[1][0], -0.5);
    EXPECT_EQ(w2[1][1], 2.0);
    EXPECT_EQ(w2[1][2], -0.5);
    EXPECT_EQ(w2[0][0], 1.0);
    EXPECT_EQ(w2[2][2], 1.0);
    const auto w3 = bezierThroughSamples(3);
    EXPECT_DOUBLE_EQ(w3[1][0], -5.0 / 6.0);
    EXPECT_DOUBLE_EQ(w3[1][1], 3.0);
    EXPECT_DOUBLE_EQ(w3[1][2], -1.5);
    EXPECT_DOUBLE_EQ(w3[1][3], 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(w3[2][0], 1.0 / 3.0);
    for (int n = 1; n <= 3; ++n) {
        const auto w = bezierThroughSamples(n);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                if (j > n || i > n) {
                    EXPECT_EQ(w[j][i], 0.0);
                }
        std::array<double, 4> samples;
        for (double& s : samples) s = uniformDouble(rng, -5.0, 5.0);
        Bernstein curve;
        curve.degree = n;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) curve.coefficients[j] += w[j][i] * samples[i];
        for (int i = 0; i <= n; ++i) EXPECT_NEAR(curve(double(i) / n), samples[i], 1e-13) << n;
    }
}

// ---- Roots ----

TEST(BernsteinRoots, KnownSimpleRoots) {
    expectRoots({0.5}, 1.0);
    expectRoots({0.3, 0.7}, 2.0);
    expectRoots({0.1, 0.45, 0.8}, -1.0);
    expectRoots({0.05, 0.3, 0.55, 0.95}, 3.0);
    expectRoots({0.1, 0.25, 0.4, 0.6, 0.8}, 1.0);
    expectRoots({0.02, 0.2, 0.35, 0.5, 0.7, 0.98}, -5.0);
}

TEST(BernsteinRoots, RootsAtTheEnds) {
    expectRoots({0.0}, 1.0);
    expectRoots({1.0}, 1.0);
    expectRoots({0.0, 1.0}, -1.0);
    expectRoots({0.0, 0.4, 1.0}, 1.0);
    expectRoots({0.0, 0.25, 0.6, 1.0}, 2.0);
    expectRoots({0.0, 0.1, 0.5, 0.9, 1.0, 1.5}, 1.0);
    // The ends must be returned, and exactly.
    for (const NamedSolver& solver : kSolvers) {
        const std::vector<double> roots = solve(solver.solve, fromRoots({0.0, 0.5, 1.0}, 1.0));
        ASSERT_EQ(roots.size(), 3u) << solver.name;
        EXPECT_EQ(roots[0], 0.0) << solver.name;
        EXPECT_EQ(roots[2], 1.0) << solver.name;
    }
}

TEST(BernsteinRoots, RootsOutsideAreNotReturned) {
    for (const NamedSolver& solver : kSolvers) {
        EXPECT_TRUE(solve(solver.solve, fromRoots({-0.5, 1.5}, 1.0)).empty()) << solver.name;
        EXPECT_TRUE(solve(solver.solve, fromRoots({-0.01, 1.01, 2.0, -3.0}, 1.0)).empty()) << solver.name;
        EXPECT_TRUE(solve(solver.solve, fromRoots({-1e-6, 1.0 + 1e-6}, 1.0)).empty()) << solver.name;
    }
    expectRoots({-0.3, 0.4, 1.2}, 1.0);
    expectRoots({-2.0, 0.6, 3.0, 0.2}, 1.0);
    expectRoots({-0.5, -0.2, 0.5, 1.3, 1.7, 0.9}, 1.0);
}

TEST(BernsteinRoots, DoubleRoots) {
    // Tangencies: returned once, twice or not at all, the sign pattern stays right.
    expectRoots({0.5, 0.5}, 1.0);
    expectRoots({0.3, 0.3, 0.8}, 1.0);
    expectRoots({0.2, 0.6, 0.6, 0.9}, -1.0);
    expectRoots({0.0, 0.0, 0.5}, 1.0);
    expectRoots({0.4, 1.0, 1.0}, 1.0);
    expectRoots({0.25, 0.25, 0.75, 0.75}, 1.0);
    expectRoots({0.1, 0.5, 0.5, 0.5, 0.7, 0.7}, 1.0);
    // A double root just off the axis (no real root) and just below it (two).
    for (const NamedSolver& solver : kSolvers) {
        const std::array<double, 3> above{0.25 + 1e-14, -1.0, 1.0};
        EXPECT_TRUE(keepsSignBetweenRoots(Bernstein::fromPower(above), solve(solver.solve, Bernstein::fromPower(above)))) << solver.name;
    }
}

TEST(BernsteinRoots, ClusteredRoots) {
    expectRoots({0.5, 0.5 + 1e-4}, 1.0);
    expectRoots({0.5, 0.5 + 1e-6}, 1.0);
    expectRoots({0.5, 0.5 + 1e-7}, 1.0);
    expectRoots({0.2, 0.5, 0.5 + 1e-4, 0.9}, 1.0);
    expectRoots({0.2, 0.5, 0.5 + 1e-6, 0.9}, 1.0);
    expectRoots({0.2, 0.5, 0.5 + 1e-7, 0.9}, 1.0);
    expectRoots({0.3, 0.3 + 1e-4, 0.7, 0.7 + 1e-7}, 1.0);
    expectRoots({0.1, 0.4, 0.4 + 1e-4, 0.4 + 2e-4, 0.8, 0.95}, 1.0);
    expectRoots({0.1, 0.4, 0.4 + 1e-6, 0.8, 0.8 + 1e-7, 0.95}, 1.0);
    // Near-double roots that cross twice are both found.
    for (const NamedSolver& solver : kSolvers)
        for (double gap : {1e-4, 1e-6, 1e-7}) {
            const std::vector<double> roots = solve(solver.solve, fromRoots({0.2, 0.5, 0.5 + gap, 0.9}, 1.0));
            // To within the roots' conditioning: about 1e-9 for the 1e-7 pair.
            const Bernstein p = fromRoots({0.2, 0.5, 0.5 + gap, 0.9}, 1.0);
            ASSERT_EQ(roots.size(), 4u) << solver.name << " " << gap;
            EXPECT_NEAR(roots[1], 0.5, rootTolerance(p, 0.5)) << solver.name << " " << gap;
            EXPECT_NEAR(roots[2], 0.5 + gap, rootTolerance(p, 0.5 + gap)) << solver.name << " " << gap;
        }
}

TEST(BernsteinRoots, HardClusters) {
    // Found by fuzzing: three or four roots within 1e-3 (where the closed forms lose most digits
    // and hand over to clipping), a triple root beside a close pair (where dividing out the
    // triple root's loosely placed roots would swamp the pair), and close roots next to the ends
    // (where the terms are tiny and an ulp of t is not).
    expectRoots({0.3, 0.3009, 0.301}, 1.0);
    expectRoots({0.851, 0.852, 0.853, 0.85300003}, 1.0);
    expectRoots({0.5404, 0.5404, 0.5414, 0.5424}, -1.0);
    expectRoots({0.2, 0.40, 0.4001, 0.4002, 0.8}, 1.0);
    expectRoots({0.37707718, 0.37707718, 0.37707718, 0.64046, 0.64047}, 1.0);
    expectRoots({0.28064928, 0.28064928, 0.28074928, 0.2939, 0.4489, -0.2}, -1.0);
    expectRoots({0.999999, 1.0 - 1e-10}, 1.0);
    expectRoots({0.9999, 0.99990003, 0.7}, 1.0);
    expectRoots({1e-6, 1.1e-5, 0.5}, 1.0);
}

TEST(BernsteinRoots, ScalesAndDegrees) {
    // Tolerances are relative to the coefficients: the scale does not matter.
    for (double scale : {1e-8, 1e8, -1e-8, -1e8, 1e-40}) {
        SCOPED_TRACE(scale);
        expectRoots({0.5}, scale);
        expectRoots({0.3, 0.7}, scale);
        expectRoots({0.0, 0.35, 0.65}, scale);
        expectRoots({0.1, 0.45, 0.5, 1.0}, scale);
        expectRoots({0.1, 0.3, 0.5, 0.7, 0.9}, scale);
        expectRoots({0.05, 0.2, 0.4, 0.41, 0.6, 0.99}, scale);
        expectRoots({0.6, 0.6, 0.2, 0.5 + 1e-6, 0.5}, scale);
    }
}

TEST(BernsteinRoots, NearConstantAndZero) {
    for (const NamedSolver& solver : kSolvers) {
        SCOPED_TRACE(solver.name);
        Bernstein zero;
        for (int d = 0; d <= kMaxBernsteinDegree; ++d) {
            zero.degree = d;
            EXPECT_TRUE(solve(solver.solve, zero).empty());
        }
        // Below 1e-100 every coefficient is noise of nothing.
        Bernstein tiny;
        tiny.degree = 3;
        tiny.coefficients = {1e-120, -1e-120, 1e-120, -1e-120};
        EXPECT_TRUE(solve(solver.solve, tiny).empty());
        // Constant to within rounding, of either sign: no roots.
        Bernstein flat;
        flat.degree = 4;
        flat.coefficients = {1.0, 1.0 + 2e-16, 1.0 - 2e-16, 1.0, 1.0 + 4e-16};
        EXPECT_TRUE(solve(solver.solve, flat).empty());
        EXPECT_TRUE(solve(solver.solve, -1.0 * flat).empty());
        // A constant that is zero to rounding at one end: the end is its root.
        Bernstein edge;
        edge.degree = 2;
        edge.coefficients = {1e-17, 1.0, 1.0};
        const std::vector<double> roots = solve(solver.solve, edge);
        EXPECT_TRUE(keepsSignBetweenRoots(edge, roots));
        EXPECT_TRUE(roots.empty() || roots[0] < 1e-12);
        BernsteinRootCounts counts;
        solve(solver.solve, flat, &counts);
        EXPECT_EQ(counts.noSignChange, 1);
        EXPECT_EQ(counts.solves, 0);
    }
}

TEST(BernsteinRoots, NegligibleLeadingCoefficients) {
    // Leading power coefficients ~1e-13 of the rest: effectively one degree lower, and the
    // solvers must neither lose the remaining roots nor invent roots from the huge ones.
    for (const NamedSolver& solver : kSolvers) {
        SCOPED_TRACE(solver.name);
        for (double lead : {1e-13, -1e-13, 1e-12, 1e-10, 1e-16, 0.0}) {
            SCOPED_TRACE(lead);
            for (const std::vector<double>& roots : std::vector<std::vector<double>>{{0.3}, {0.2, 0.7}, {0.1, 0.5, 0.85}, {0.0, 0.4, 0.6, 1.0}, {0.3, 0.3 + 1e-5}}) {
                // One or two degrees more, with negligible coefficients.
                std::vector<double> a = powerFromRoots(roots, 1.0);
                a.push_back(lead);
                if (a.size() < 6) a.push_back(lead * 1e-3);
                const Bernstein p = Bernstein::fromPower(a);
                const std::vector<double> got = solve(solver.solve, p);
                EXPECT_TRUE(keepsSignBetweenRoots(p, got));
                for (double r : roots) {
                    if (r == 0.0 || r == 1.0) continue;  // may have moved outside
                    // The true roots moved by the leading term: |lead| / slope at most.
                    const double tolerance = rootTolerance(p, r) + 10.0 * std::abs(lead) / std::abs(p.derivative()(r));
                    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](double x) { return std::abs(x - r) <= tolerance; }))
                        << "missing root " << r;
                }
            }
        }
    }
}

TEST(BernsteinRoots, RandomPolynomialsSolversAgree) {
    // 2000 random quartics in Bernstein form: the two solvers find the same sign changes, to
    // within 1e-9 (or the root's conditioning, for the rare near-double pairs), and the sign of p
    // never changes between returned roots.
    Rng rng(5);
    BernsteinRootCounts clipping, closed;
    int withRoots = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Bernstein p = randomBernstein(rng, 4);
        const std::vector<double> a = solve(rootsByBezierClipping, p, &clipping), b = solve(rootsInClosedForm, p, &closed);
        ASSERT_TRUE(keepsSignBetweenRoots(p, a)) << "clipping, trial " << trial;
        ASSERT_TRUE(keepsSignBetweenRoots(p, b)) << "closed form, trial " << trial;
        const std::vector<double> ca = signChangingRoots(p, a), cb = signChangingRoots(p, b);
        ASSERT_EQ(ca.size(), cb.size()) << "trial " << trial;
        for (std::size_t i = 0; i < ca.size(); ++i) EXPECT_NEAR(ca[i], cb[i], rootTolerance(p, ca[i])) << "trial " << trial;
        withRoots += !ca.empty();
    }
    EXPECT_GT(withRoots, 500);  // the test is not vacuous
    EXPECT_EQ(clipping.solves + clipping.noSignChange, 2000);
    EXPECT_EQ(closed.solves + closed.noSignChange, 2000);
    EXPECT_EQ(clipping.noSignChange, closed.noSignChange);
}

TEST(BernsteinRoots, RandomSexticsKeepTheirSign) {
    // Degree 6 (both solvers: the closed form falls back to clipping), random coefficients and
    // random products of known roots.
    Rng rng(6);
    for (int trial = 0; trial < 2000; ++trial) {
        const Bernstein p = randomBernstein(rng, 6);
        for (const NamedSolver& solver : kSolvers) ASSERT_TRUE(keepsSignBetweenRoots(p, solve(solver.solve, p))) << solver.name << " " << trial;
    }
    for (int trial = 0; trial < 300; ++trial) {
        const int degree = 1 + int(rng.next() % kMaxBernsteinDegree);
        std::vector<double> roots(degree);
        for (double& r : roots) r = uniformDouble(rng, -0.2, 1.2);
        if (degree > 1 && trial % 3 == 0) roots[1] = roots[0] + (trial % 2 ? 1e-5 : 1e-3);
        if (trial % 5 == 0) roots[0] = trial % 10 ? 0.0 : 1.0;
        SCOPED_TRACE(trial);
        expectRoots(roots, uniformDouble(rng, 0.5, 2.0) * (trial % 2 ? -1.0 : 1.0));
    }
}

TEST(BernsteinRoots, CountsAddUp) {
    BernsteinRootCounts counts;
    solve(rootsByBezierClipping, fromRoots({0.2, 0.6}, 1.0), &counts);
    solve(rootsInClosedForm, fromRoots({0.2, 0.6}, 1.0), &counts);
    solve(rootsInClosedForm, fromRoots({2.0}, 1.0), &counts);  // all coefficients one sign
    EXPECT_EQ(counts.solves, 2);
    EXPECT_EQ(counts.noSignChange, 1);
    EXPECT_EQ(counts.roots, 4);
    EXPECT_GT(counts.iterations, 0);
    BernsteinRootCounts total;
    total.add(counts);
    total.add(counts);
    EXPECT_EQ(total.roots, 8);
}

TEST(BernsteinRoots, SpeedOnRandomQuartics) {
    // Informational: the time per solve of each solver on the random quartic set.
    Rng rng(5);
    std::vector<Bernstein> set;
    for (int i = 0; i < 2000; ++i) set.push_back(randomBernstein(rng, 4));
    for (const NamedSolver& solver : kSolvers) {
        std::array<double, kMaxBernsteinDegree> roots;
        BernsteinRootCounts counts;
        const int repeats = 50;
        const auto start = std::chrono::steady_clock::now();
        for (int r = 0; r < repeats; ++r)
            for (const Bernstein& p : set) solver.solve(p, roots, &counts);
        const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / (repeats * set.size());
        std::cout << solver.name << ": " << ns << " ns per quartic (" << double(counts.solves) / (repeats * set.size()) * 100.0
                  << "% solved, " << double(counts.iterations) / std::max<std::int64_t>(counts.solves, 1) << " iterations per solve)\n";
    }
}

// ---- Slefes ----

TEST(Slefe, EnclosesItsPolynomial) {
    // Exactly: the enclosure's margin covers the subdivision's rounding and the evaluation's.
    Rng rng(7);
    for (int trial = 0; trial < 300; ++trial) {
        const int degree = 2 + int(rng.next() % 5), segments = 1 + int(rng.next() % Slefe::kMaxSegments);
        const Bernstein p = (trial % 3 == 0 ? 1e6 : 1.0) * randomBernstein(rng, degree);
        const Slefe s = slefeOf(p, segments);
        ASSERT_EQ(s.segments, segments);
        for (int k = 0; k <= 1000; ++k) {
            const double t = k / 1000.0;
            const int i = std::min(int(t * segments), segments - 1);
            const double f = t * segments - i;
            const double lower = (1.0 - f) * s.lower[i] + f * s.lower[i + 1], upper = (1.0 - f) * s.upper[i] + f * s.upper[i + 1];
            const double v = p(t);
            ASSERT_LE(lower, v) << "trial " << trial << " t " << t;
            ASSERT_GE(upper, v) << "trial " << trial << " t " << t;
        }
    }
}

TEST(Slefe, TighterThanCoefficientBounds) {
    // A curved cubic: the coefficients' range is loose, chords over short pieces hug the curve
    // (width O(1 / segments^2)).
    const std::array<double, 4> power{0.1, -2.0, 3.0, -1.2};
    const Bernstein p = Bernstein::fromPower(power);
    const double coefficientWidth = p.upperBound() - p.lowerBound();
    double previous = std::numeric_limits<double>::infinity();
    for (int segments : {1, 2, 4, 8}) {
        const Slefe s = slefeOf(p, segments);
        double total = 0.0, widest = 0.0;
        for (int i = 0; i <= segments; ++i) total += s.upper[i] - s.lower[i], widest = std::max(widest, s.upper[i] - s.lower[i]);
        EXPECT_LT(total, (segments + 1) * coefficientWidth) << segments;
        // Each doubling of the segments at least halves the width (asymptotically: quarters it).
        EXPECT_LT(widest, 0.5 * previous) << segments;
        previous = widest;
    }
    // A line is its own enclosure.
    const Slefe line = slefeOf(Bernstein::fromPower(std::array<double, 2>{0.5, 2.0}), 4);
    for (int i = 0; i <= 4; ++i) EXPECT_NEAR(line.upper[i] - line.lower[i], 0.0, 1e-13);  // the rounding margin
}

}  // namespace streak::raster
