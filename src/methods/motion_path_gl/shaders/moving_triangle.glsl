// The GLSL twin of raster/moving_triangle.cpp, in double precision as on the CPU: a triangle
// whose clip-space corners move linearly over one segment, u in [0, 1]. In homogeneous 2D its
// edge functions are quadratics in u with fixed vector coefficients (Gribel et al. 2010).

struct MovingTriangle {
    dvec3 a[3], b[3], c[3];     // edge e (corners e, e + 1): (a u^2 + b u + c) . (x, y, 1)
    dvec3 corner[3], delta[3];  // (x, y, w) at u = 0 and its change to u = 1
};

struct HomogeneousSample {
    dvec3 bary;
    double viewDepth;
    bool isValid;
    bool isFrontFacing;
};

MovingTriangle movingTriangle(vec4 open[3], vec4 close[3]) {
    MovingTriangle m;
    for (int i = 0; i < 3; ++i) {
        m.corner[i] = dvec3(open[i].xyw);
        m.delta[i] = dvec3(close[i].xyw) - m.corner[i];
    }
    for (int e = 0; e < 3; ++e) {
        int f = (e + 1) % 3;
        m.a[e] = cross(m.delta[e], m.delta[f]);
        m.b[e] = cross(m.corner[e], m.delta[f]) + cross(m.delta[e], m.corner[f]);
        m.c[e] = cross(m.corner[e], m.corner[f]);
    }
    return m;
}

// Edge e's quadratic at a point: (a, b, c) coefficients of u^2, u, 1.
dvec3 edgeFunction(MovingTriangle m, int e, dvec2 ndc) {
    dvec3 p = dvec3(ndc, 1.0);
    return dvec3(dot(m.a[e], p), dot(m.b[e], p), dot(m.c[e], p));
}

double quadraticAt(dvec3 q, double u) { return (q.x * u + q.y) * u + q.z; }

// raster::solveQuadratic: robust real roots, ascending.
int solveQuadratic(dvec3 q, out double r0, out double r1) {
    r0 = 0.0;
    r1 = 0.0;
    double scale = max(abs(q.x), max(abs(q.y), abs(q.z)));
    if (scale == 0.0) return 0;
    if (abs(q.x) <= 1e-12 * scale) {
        if (q.y == 0.0) return 0;
        r0 = -q.z / q.y;
        return 1;
    }
    double discriminant = q.y * q.y - 4.0 * q.x * q.z;
    if (discriminant < 0.0) return 0;
    if (discriminant == 0.0) {
        r0 = -q.y / (2.0 * q.x);
        return 1;
    }
    double root = sqrt(discriminant);
    double s = -0.5 * (q.y + (q.y >= 0.0 ? root : -root));
    r0 = s / q.x;
    r1 = s != 0.0 ? q.z / s : -r0;
    if (r0 > r1) {
        double t = r0;
        r0 = r1;
        r1 = t;
    }
    return 2;
}

dvec3 cornerAt(MovingTriangle m, int i, double u) { return m.corner[i] + u * m.delta[i]; }
dvec3 edgeVector(MovingTriangle m, int e, double u) { return (m.a[e] * u + m.b[e]) * u + m.c[e]; }

HomogeneousSample sampleFromEdges(dvec3 edges[3], dvec3 w, dvec2 ndc, bool isFront) {
    dvec3 p = dvec3(ndc, 1.0);
    dvec3 e = dvec3(dot(edges[0], p), dot(edges[1], p), dot(edges[2], p));
    double sum = e.x + e.y + e.z;
    HomogeneousSample s;
    s.isFrontFacing = isFront;
    s.isValid = !(sum == 0.0 || isinf(sum) || isnan(sum));
    s.bary = s.isValid ? e / sum : dvec3(0.0);
    s.viewDepth = s.isValid ? dot(s.bary, w) : 0.0;
    return s;
}

// Barycentrics (perspective correct), view depth and facing at (u, ndc); optionally at two
// neighbouring points too, sharing the edge vectors.
void sampleWithNeighbours(MovingTriangle m, double u, dvec2 ndc, dvec2 offset0, dvec2 offset1, out HomogeneousSample centre,
                          out HomogeneousSample n0, out HomogeneousSample n1) {
    dvec3 edges[3] = dvec3[3](edgeVector(m, 1, u), edgeVector(m, 2, u), edgeVector(m, 0, u));
    dvec3 w = dvec3(cornerAt(m, 0, u).z, cornerAt(m, 1, u).z, cornerAt(m, 2, u).z);
    bool isFront = dot(cornerAt(m, 0, u), edges[0]) > 0.0;
    centre = sampleFromEdges(edges, w, ndc, isFront);
    n0 = sampleFromEdges(edges, w, ndc + offset0, isFront);
    n1 = sampleFromEdges(edges, w, ndc + offset1, isFront);
}

HomogeneousSample sampleAt(MovingTriangle m, double u, dvec2 ndc) {
    dvec3 edges[3] = dvec3[3](edgeVector(m, 1, u), edgeVector(m, 2, u), edgeVector(m, 0, u));
    dvec3 w = dvec3(cornerAt(m, 0, u).z, cornerAt(m, 1, u).z, cornerAt(m, 2, u).z);
    return sampleFromEdges(edges, w, ndc, dot(cornerAt(m, 0, u), edges[0]) > 0.0);
}

bool isFrontFacingAt(MovingTriangle m, double u) { return dot(cornerAt(m, 0, u), edgeVector(m, 1, u)) > 0.0; }

// raster::isInsideByEdges: all edges of one sign (either orientation), and an edge within
// float precision of zero (|value| <= 1e-6 of its terms' scale, kOnEdgeTolerance) goes by the
// rasterizer's top-left rule, so that two triangles sharing an edge through the sample cover it
// once: inside right of the edge in raster x, or below a horizontal one.
bool isInsideByEdges(dvec3 edges[3], dvec2 ndc, double values[3]) {
    bool isOn[3];
    double orientation = 0.0;
    bool isOutside = false;
    for (int e = 0; e < 3; ++e) {
        double scale = abs(edges[e].x * ndc.x) + abs(edges[e].y * ndc.y) + abs(edges[e].z);
        isOn[e] = abs(values[e]) <= 1e-6 * scale;
        if (!isOn[e]) {
            if (orientation != 0.0 && (orientation > 0.0) != (values[e] > 0.0)) isOutside = true;
            orientation = values[e];
        }
    }
    if (isOutside) return false;
    if (orientation == 0.0) return true;  // every edge through the sample: a degenerate instant
    for (int e = 0; e < 3; ++e) {
        if (!isOn[e]) continue;
        // Inward gradient in NDC (y up); raster y points down.
        dvec3 v = edges[e] * (orientation > 0.0 ? 1.0 : -1.0);
        if (!(v.x > 0.0 || (v.x == 0.0 && v.y < 0.0))) return false;
    }
    return true;
}

// MovingTriangle::insideSpans: the spans of u in which the sample lies inside (either
// orientation; beyond the near plane when checkNearPlane). Start/end pairs; returns the count.
int insideSpans(MovingTriangle m, dvec2 ndc, double zNear, bool checkNearPlane, out double bounds[8]) {
    double breaks[8];
    int n = 0;
    breaks[n++] = 0.0;
    dvec3 q[3];
    for (int e = 0; e < 3; ++e) {
        q[e] = edgeFunction(m, e, ndc);
        double r0, r1;
        int count = solveQuadratic(q[e], r0, r1);
        if (count > 0 && r0 > 0.0 && r0 < 1.0) breaks[n++] = r0;
        if (count > 1 && r1 > 0.0 && r1 < 1.0) breaks[n++] = r1;
    }
    breaks[n++] = 1.0;
    // Sorted by an odd-even transposition network over all 8 slots (unused ones past 1): fixed
    // indices throughout. llvmpipe miscompiles an insertion sort's swaps of a double array at
    // variable indices (values come out duplicated).
    for (int i = n; i < 8; ++i) breaks[i] = 2.0;
    for (int pass = 0; pass < 8; ++pass)
        for (int i = pass & 1; i + 1 < 8; i += 2) {
            double lo = min(breaks[i], breaks[i + 1]), hi = max(breaks[i], breaks[i + 1]);
            breaks[i] = lo;
            breaks[i + 1] = hi;
        }
    int count = 0;
    bool wasInside = false;
    for (int i = 0; i < 8; ++i) bounds[i] = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(breaks[i + 1] > breaks[i])) continue;
        double u = 0.5 * (breaks[i] + breaks[i + 1]);
        double e0 = quadraticAt(q[0], u), e1 = quadraticAt(q[1], u), e2 = quadraticAt(q[2], u);
        dvec3 edges[3] = dvec3[3](edgeVector(m, 0, u), edgeVector(m, 1, u), edgeVector(m, 2, u));
        double values[3] = double[3](e0, e1, e2);
        bool inside = isInsideByEdges(edges, ndc, values);
        if (inside && checkNearPlane) inside = sampleAt(m, u, ndc).viewDepth >= zNear;
        if (inside != wasInside) bounds[count++] = breaks[i];
        wasInside = inside;
    }
    if (wasInside) bounds[count++] = 1.0;
    return count;
}
