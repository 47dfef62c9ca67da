// motion-path-gl pass 1: the motion path of one triangle over one segment, the screen region
// it sweeps. With every corner in front of the eye a corner's screen path is a straight
// segment, so the convex hull of the six projected corners holds the triangle at every time:
// a conservative path (beyond the paper's bilinear sides, which lose coverage where they fold).
// A segment reaching behind the eye may cover anything: a full-screen quad. Single-sided
// triangles seen from behind all through the segment emit nothing.
layout(triangles) in;
layout(triangle_strip, max_vertices = 6) out;

uniform int u_segment;
uniform int u_numSegments;

in vec4 v_open[];
in vec4 v_close[];
flat in uint v_triangle[];

flat out uint g_segment;  // triangle * segments + segment

// raster::isBackFacingThroughout: the orientation cubic's Bernstein coefficients all negative.
bool isBackFacingThroughout() {
    for (int k = 0; k <= 3; ++k) {
        double sum = 0.0;
        int count = 0;
        for (int mask = 0; mask < 8; ++mask) {
            if (bitCount(mask) != k) continue;
            dvec3 r0 = dvec3(((mask & 1) != 0 ? v_close[0] : v_open[0]).xyw);
            dvec3 r1 = dvec3(((mask & 2) != 0 ? v_close[1] : v_open[1]).xyw);
            dvec3 r2 = dvec3(((mask & 4) != 0 ? v_close[2] : v_open[2]).xyw);
            sum += dot(r0, cross(r1, r2));
            ++count;
        }
        if (!(sum / double(count) < 0.0)) return false;
    }
    return true;
}

void emitCorner(vec2 ndc) {
    g_segment = v_triangle[0] * uint(u_numSegments) + uint(u_segment);
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);  // raster rows top first
    EmitVertex();
}

void main() {
    float minW = 1e30;
    for (int i = 0; i < 3; ++i) minW = min(minW, min(v_open[i].w, v_close[i].w));
    bool isDoubleSided = (triangles[v_triangle[0]].w & kDoubleSidedBit) != 0u;
    if (minW > 0.0 && !isDoubleSided && isBackFacingThroughout()) return;
    if (!(minW > 0.0)) {
        emitCorner(vec2(-1.0, -1.0));
        emitCorner(vec2(1.0, -1.0));
        emitCorner(vec2(-1.0, 1.0));
        emitCorner(vec2(1.0, 1.0));
        EndPrimitive();
        return;
    }
    // Gift wrapping over the six projected corners, counter-clockwise from the leftmost: fixed
    // trip counts only (llvmpipe miscompiled a monotone chain's data-dependent loops).
    vec2 p[6];
    for (int i = 0; i < 3; ++i) {
        p[i] = v_open[i].xy / v_open[i].w;
        p[i + 3] = v_close[i].xy / v_close[i].w;
    }
    int start = 0;
    for (int i = 1; i < 6; ++i)
        if (p[i].x < p[start].x || (p[i].x == p[start].x && p[i].y < p[start].y)) start = i;
    vec2 hull[6];
    int n = 0, current = start;
    for (int step = 0; step < 6; ++step) {
        hull[n++] = p[current];
        int next = current == 0 ? 1 : 0;
        for (int j = 0; j < 6; ++j) {
            if (j == current) continue;
            vec2 a = p[next] - p[current], b = p[j] - p[current];
            float turn = a.x * b.y - a.y * b.x;
            // j lies clockwise of the candidate edge, or on it and farther: j wraps tighter.
            if (turn < 0.0 || (turn == 0.0 && dot(b, b) > dot(a, a))) next = j;
        }
        current = next;
        if (current == start) break;
    }
    if (n < 3) return;  // degenerate: a point or a line covers no sample centre
    // GL rasterizes at texel centres, but a sample (n-rooks, sampleRaster) lies up to half a
    // texel from its centre: push each edge out by half a texel diagonal, so every texel whose
    // sample the hull covers is rasterized. Each corner moves to where its two pushed edges meet.
    vec2 texel = 2.0 / vec2(u_viewport.xy);
    vec2 grown[6];
    for (int i = 0; i < 6; ++i) {
        if (i >= n) break;
        vec2 a = hull[(i + n - 1) % n], b = hull[i], c = hull[(i + 1) % n];
        // Outward normals of a counter-clockwise polygon, scaled so a unit step is one texel.
        vec2 e0 = (b - a) / texel, e1 = (c - b) / texel;
        vec2 n0 = normalize(vec2(e0.y, -e0.x)), n1 = normalize(vec2(e1.y, -e1.x));
        float d = 0.7072;  // half a texel diagonal, a little over
        vec2 m = n0 + n1;
        float mm = dot(m, m);
        // The miter (n0 + n1) 2d / |n0 + n1|^2, its length capped near 45 d for slivers.
        vec2 push = m * (2.0 * d / max(mm, 1e-3));
        grown[i] = b + push * texel;
    }
    for (int i = 0; i < 6; ++i)
        if (i < n) hull[i] = grown[i];
    // A convex polygon as a strip: 0, 1, n-1, 2, n-2, ...
    emitCorner(hull[0]);
    for (int i = 1; i < n; ++i) emitCorner(hull[(i & 1) != 0 ? (i + 1) / 2 : n - i / 2]);
    EndPrimitive();
}
