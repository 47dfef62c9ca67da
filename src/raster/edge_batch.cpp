#include "raster/edge_batch.h"

#include <glm/geometric.hpp>

namespace streak::raster {

namespace {

// Four-lane values pass only between always-inline functions (see util/simd.h).
#pragma GCC diagnostic ignored "-Wpsabi"

using simd::Double4;
using simd::Mask4;

// The scalar twin: MovingTriangle's own per-sample code.
void evaluateScalar(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride, int count,
                    EdgeBatch& batch) {
    for (int i = 0; i < count; ++i) {
        const glm::dvec2& p = ndc[i * stride];
        batch.edges[std::size_t(i)] = moving.edgeFunctions(p);
        batch.staysOutside[std::size_t(i)] = moving.staysOutside(batch.edges[std::size_t(i)], p, orientation) ? 1 : 0;
        if (moving.isStill()) {
            const std::array<Quadratic, 3>& q = batch.edges[std::size_t(i)];
            batch.isInsideStill[std::size_t(i)] = isInsideByEdges(moving.edgeTerms().c, p, {q[0].c, q[1].c, q[2].c}) ? 1 : 0;
        }
    }
}

// glm::dot(v, (x, y, 1)) in four lanes, in glm's order: (v.x x + v.y y) + v.z 1.
[[gnu::always_inline]] inline Double4 dotPoint(const glm::dvec3& v, Double4 x, Double4 y) { return (v.x * x + v.y * y) + v.z * 1.0; }

// Quadratic::operator() in four lanes: (a u + b) u + c.
[[gnu::always_inline]] inline Double4 evaluate(Double4 a, Double4 b, Double4 c, Double4 u) { return (a * u + b) * u + c; }

// Four lanes from `first` on: MovingTriangle::edgeFunction and staysOutside(edges, ...), each
// operation the one the scalar code does, in its order.
[[gnu::always_inline]] inline void evaluateLanes(const MovingTriangle::EdgeTerms& terms, bool isStill, int orientation,
                                                 const glm::dvec2* ndc, std::ptrdiff_t stride, int first, int lanes, EdgeBatch& batch) {
    Double4 x{}, y{};
    for (int i = 0; i < lanes; ++i) x[i] = ndc[(first + i) * stride].x, y[i] = ndc[(first + i) * stride].y;
    const Double4 zero{}, one = zero + 1.0;
    const Double4 ax = simd::abs(x), ay = simd::abs(y);
    const double o = orientation;
    Mask4 outside{};
    for (int e = 0; e < 3; ++e) {
        const Double4 a = isStill ? zero : dotPoint(terms.a[e], x, y);
        const Double4 b = isStill ? zero : dotPoint(terms.b[e], x, y);
        const Double4 c = dotPoint(terms.c[e], x, y);
        for (int i = 0; i < lanes; ++i) batch.edges[std::size_t(first + i)][e] = {a[i], b[i], c[i]};
        if (orientation == 0) continue;
        // Quadratic::maxOnUnitInterval of o q: the larger end, or the vertex of a downward
        // parabola inside (0, 1); std::max(m, v) is (m < v ? v : m).
        const Double4 oa = a * o, ob = b * o, oc = c * o;
        const Double4 atStart = evaluate(oa, ob, oc, zero), atEnd = evaluate(oa, ob, oc, one);
        Double4 most = simd::select(atStart < atEnd, atEnd, atStart);
        const Double4 vertex = -ob / (2.0 * oa);
        const Double4 atVertex = evaluate(oa, ob, oc, vertex);
        const Mask4 hasVertex = (oa < 0.0) & (vertex > 0.0) & (vertex < 1.0);
        most = simd::select(hasVertex & (most < atVertex), atVertex, most);
        const Double4 size = (terms.bound[e].x * ax + terms.bound[e].y * ay) + terms.bound[e].z * 1.0;
        outside |= (most < 0.0) & (most < -2.0 * kOnEdgeTolerance * size);
    }
    for (int i = 0; i < lanes; ++i) batch.staysOutside[std::size_t(first + i)] = outside[i] != 0 ? 1 : 0;
    // (Not where every lane stays outside: the answer is not asked there, and a small still
    // triangle's box is mostly such lanes.)
    bool isAnyLeft = false;
    for (int i = 0; i < lanes; ++i) isAnyLeft = isAnyLeft || outside[i] == 0;
    if (!isStill || !isAnyLeft) return;
    // isInsideByEdges of the constant edges in lanes, its sequential rule as masks: the first
    // edge off its line sets the orientation (isSet: it is not zero; isPositive: > 0), a later
    // one of the other sign fails, and with an orientation set every edge on its line must pass
    // the top-left rule for it.
    Mask4 isSet{}, isPositive{}, fails{};
    std::array<Mask4, 3> isOn;
    std::array<Double4, 3> value;
    for (int e = 0; e < 3; ++e) {
        const glm::dvec3& v = terms.c[e];
        value[std::size_t(e)] = dotPoint(v, x, y);
        const Double4 scale = (simd::abs(v.x * x) + simd::abs(v.y * y)) + std::abs(v.z);
        isOn[std::size_t(e)] = simd::abs(value[std::size_t(e)]) <= kOnEdgeTolerance * scale;
        const Mask4 off = ~isOn[std::size_t(e)];
        const Mask4 positive = value[std::size_t(e)] > 0.0;
        fails |= off & isSet & (isPositive ^ positive);
        isPositive = (off & positive) | (~off & isPositive);
        isSet = (off & (value[std::size_t(e)] != 0.0)) | (~off & isSet);
    }
    Mask4 topLeftFails{};
    for (int e = 0; e < 3; ++e) {
        const glm::dvec3& v = terms.c[e];
        const Double4 sign = simd::select(isPositive, one, zero - 1.0);
        const Double4 vx = v.x * sign, vy = v.y * sign;
        topLeftFails |= isOn[std::size_t(e)] & ~((vx > 0.0) | ((vx == 0.0) & (vy < 0.0)));
    }
    const Mask4 inside = ~fails & (~isSet | ~topLeftFails);
    for (int i = 0; i < lanes; ++i) batch.isInsideStill[std::size_t(first + i)] = inside[i] != 0 ? 1 : 0;
}

[[gnu::always_inline]] inline void evaluateVector(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride,
                                                  int count, EdgeBatch& batch) {
    const MovingTriangle::EdgeTerms terms = moving.edgeTerms();
    const bool isStill = moving.isStill();
    for (int first = 0; first < count; first += 4) {
        const int lanes = count - first < 4 ? count - first : 4;
        if (isStill) evaluateLanes(terms, true, orientation, ndc, stride, first, lanes, batch);
        else evaluateLanes(terms, false, orientation, ndc, stride, first, lanes, batch);
    }
}

// The two vector entry points: the same code for baseline x86-64 and for AVX2 (no FMA, see
// util/simd.h).
void evaluateSse2(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride, int count, EdgeBatch& batch) {
    evaluateVector(moving, orientation, ndc, stride, count, batch);
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx2"))) void evaluateAvx2(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride,
                                                  int count, EdgeBatch& batch) {
    evaluateVector(moving, orientation, ndc, stride, count, batch);
}
#endif

}  // namespace

void evaluateEdgeBatch(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride, int count,
                       EdgeBatch& batch, simd::Level level) {
    batch.count = count;
    switch (level) {
    case simd::Level::scalar: evaluateScalar(moving, orientation, ndc, stride, count, batch); return;
    case simd::Level::sse2: evaluateSse2(moving, orientation, ndc, stride, count, batch); return;
    case simd::Level::avx2:
#if defined(__x86_64__) || defined(__i386__)
        evaluateAvx2(moving, orientation, ndc, stride, count, batch);
#else
        evaluateSse2(moving, orientation, ndc, stride, count, batch);
#endif
        return;
    }
}

}  // namespace streak::raster
