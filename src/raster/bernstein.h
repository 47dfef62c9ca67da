#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace streak::raster {

// Bernstein polynomials on [0, 1]: the form of Bezier vertex motion of order n <= 3 and of the
// edge equations it gives (degree 2n <= 6; Gribel et al. 2013). A polynomial is its
// coefficients b_0 .. b_d in the basis B_i^d(t) = C(d, i) t^i (1 - t)^(d - i): they enclose it
// (convex hull property), de Casteljau evaluates and subdivides it stably, and products and
// degree elevation stay in the basis.
constexpr int kMaxBernsteinDegree = 6;

struct Bernstein {
    int degree = 0;
    std::array<double, kMaxBernsteinDegree + 1> coefficients{};

    // De Casteljau evaluation.
    double operator()(double t) const;
    // The coefficients' min and max: a bound of the polynomial over [0, 1].
    double lowerBound() const;
    double upperBound() const;

    // The same polynomial in degree newDegree >= degree.
    Bernstein elevated(int newDegree) const;
    // The polynomial over [t0, t1] reparametrized to [0, 1] (de Casteljau subdivision): its
    // value at s is this at t0 + s (t1 - t0).
    Bernstein restricted(double t0, double t1) const;
    // The derivative, degree - 1 (degree 0 stays 0).
    Bernstein derivative() const;

    // From / to the power basis a_0 + a_1 t + ... + a_d t^d.
    static Bernstein fromPower(std::span<const double> power);
    std::array<double, kMaxBernsteinDegree + 1> toPower() const;
    // The polynomial of degree values.size() - 1 through values[i] at t = i / (size - 1)
    // (a single value: the constant).
    static Bernstein interpolating(std::span<const double> values);
};

Bernstein operator+(const Bernstein& a, const Bernstein& b);  ///< elevates the lower degree
Bernstein operator-(const Bernstein& a, const Bernstein& b);
Bernstein operator*(double s, const Bernstein& a);
Bernstein operator*(const Bernstein& a, const Bernstein& b);  ///< degree a + b <= kMaxBernsteinDegree

// The weights W (rows: control points, columns: samples) of the degree-n Bezier curve through
// n + 1 samples at t = i / n: control_j = sum_i W[j][i] sample_i. For n = 2,
// P1 = 2 P(1/2) - (P0 + P2) / 2. n <= 3.
std::array<std::array<double, 4>, 4> bezierThroughSamples(int n);

// The weights W (row-major, (n + 1) x samples) of the degree-n Bezier curve fitted by least
// squares to samples at t = i / (samples - 1): control_j = sum_i W[j * samples + i] sample_i.
// samples >= n + 1 (equal: bezierThroughSamples); n <= 3.
std::vector<double> bezierFittingSamples(int n, int samples);

// How the roots of the edge equations were found, for --stats and for the solvers' comparison.
struct BernsteinRootCounts {
    std::int64_t solves = 0;       ///< polynomials solved
    std::int64_t noSignChange = 0; ///< all coefficients of one sign: no root, nothing solved
    std::int64_t roots = 0;        ///< roots in [0, 1] returned
    std::int64_t iterations = 0;   ///< clipping steps or Newton polishes
    void add(const BernsteinRootCounts& o) { solves += o.solves, noSignChange += o.noSignChange, roots += o.roots, iterations += o.iterations; }
};

// All roots of p in [0, 1], ascending, each once (a double root may be returned once or not at
// all: it does not change the sign); at most p.degree of them. A polynomial zero to within
// rounding of its coefficients has none. Both solvers find the roots of one polynomial to
// within 1e-9 of each other.
//
// Bezier clipping (Sederberg & Nishita 1990): the convex hull of the control polygon
// (i / d, b_i) meets the t axis in an interval holding every root; clip to it and repeat,
// halving when it shrinks by less than half; each root found is divided out (deflation) so the
// rest converge alone.
int rootsByBezierClipping(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts* counts = nullptr);
// Closed form for degree <= 4 (quartic by Ferrari's resolvent cubic, Neumark's conditioning;
// cubic by the trigonometric / Cardano forms; quadratic without cancellation), each root
// polished by Newton steps. Degree > 4: falls back to Bezier clipping.
int rootsInClosedForm(const Bernstein& p, std::span<double, kMaxBernsteinDegree> roots, BernsteinRootCounts* counts = nullptr);

// A slefe (Peters 2003): piecewise-linear lower and upper enclosures of p over [0, 1] with
// breakpoints at t = i / segments, lower[i] <= p(t) <= upper[i] interpolated linearly between
// breakpoints.
struct Slefe {
    static constexpr int kMaxSegments = 8;
    int segments = 0;
    std::array<double, kMaxSegments + 1> lower{}, upper{};
};
Slefe slefeOf(const Bernstein& p, int segments);

}  // namespace streak::raster
