// The CPU rasterizer's test of one sample against one triangle, for GL methods that test
// triangles in the fragment shader: the GLSL twin of raster/clip.cpp and
// raster/screen_triangle.cpp. The same near-plane and guard-band clipping, snapping to 1/256
// pixel and top-left fill rule: given the same corners, a sample is covered exactly when the
// CPU finds it covered. Snapped coordinates stay below 2^26 (the guard band), so edge
// functions are whole numbers below 2^53: exact in double, as the CPU's int64 ones.

const float kGuardBand = 16.0;
const double kSubpixelScale = 256.0;

// A covered sample: what depth testing and shading need.
struct RasterHit {
    vec3 bary;       // perspective-correct barycentrics in the source triangle
    vec3 baryRight;  // the same one sample spacing right and down: the texture footprint
    vec3 baryDown;
    float invW;      // 1 / view depth: larger is nearer
    bool isFrontFacing;
};

// ScreenTriangle: E_i(X, Y) = a_i X + b_i Y + c_i, positive inside, X and Y fixed-point.
struct ScreenTriangle {
    dvec3 a, b, c;
    dvec3 bias;  // 0 on top-left edges, -1 elsewhere
    dvec3 invW;  // 1 / clip w of each corner, rounded to float as the CPU stores it
    double invEdgeSum;
    bool isFrontFacing;
};

// rasterFromClip: x right, y down, in pixels. Precondition: w > 0.
dvec2 rasterFromClip(vec4 clip) {
    double invW = 1.0 / double(clip.w);
    return dvec2((double(clip.x) * invW * 0.5 + 0.5) * double(u_viewport.z),
                 (0.5 - double(clip.y) * invW * 0.5) * double(u_viewport.w));
}

// std::llround: the nearest whole number, halves away from zero (exact: the fraction of a
// double is exact).
double roundHalfAway(double x) {
    double magnitude = abs(x), whole = floor(magnitude);
    if (magnitude - whole >= 0.5) whole += 1.0;
    return sign(x) * whole;
}

// Signed distance of p to clip plane i (0: near, 1-4: guard band); inside is >= 0.
float planeDistance(vec4 p, int i) {
    precise float d;
    if (i == 0) d = p.w - u_projection.z;
    else if (i == 1) d = kGuardBand * p.w - p.x;
    else if (i == 2) d = kGuardBand * p.w + p.x;
    else if (i == 3) d = kGuardBand * p.w - p.y;
    else d = kGuardBand * p.w + p.y;
    return d;
}

// Whether p is inside the near plane and the guard band.
bool isInsideClipVolume(vec4 p) {
    for (int i = 0; i < 5; ++i)
        if (planeDistance(p, i) < 0.0) return false;
    return true;
}

bool needsClipping(vec4 clip[3]) {
    return !isInsideClipVolume(clip[0]) || !isInsideClipVolume(clip[1]) || !isInsideClipVolume(clip[2]);
}

// A vertex of a clipped polygon and its barycentrics in the source triangle.
struct ClipVertex {
    vec4 clip;
    vec3 sourceBary;
};

// clipTriangle: Sutherland-Hodgman against the near plane and the guard band; returns the
// polygon's vertex count (0 when nothing remains, at most 3 + 5).
int clipTriangle(vec4 clip[3], out ClipVertex polygon[8]) {
    polygon[0] = ClipVertex(clip[0], vec3(1.0, 0.0, 0.0));
    polygon[1] = ClipVertex(clip[1], vec3(0.0, 1.0, 0.0));
    polygon[2] = ClipVertex(clip[2], vec3(0.0, 0.0, 1.0));
    int count = 3;
    for (int plane = 0; plane < 5 && count > 0; ++plane) {
        ClipVertex next[8];
        int nextCount = 0;
        for (int i = 0; i < count; ++i) {
            ClipVertex a = polygon[i], b = polygon[(i + 1) % count];
            float da = planeDistance(a.clip, plane), db = planeDistance(b.clip, plane);
            if (da >= 0.0) next[nextCount++] = a;
            if ((da >= 0.0) != (db >= 0.0)) {
                // Correctly rounded, as the CPU's float division (GL's float division need not be).
                precise float gap = da - db;
                precise float s = float(double(da) / double(gap));
                precise vec4 crossingClip = a.clip + (b.clip - a.clip) * s;
                precise vec3 crossingBary = a.sourceBary + (b.sourceBary - a.sourceBary) * s;
                next[nextCount++] = ClipVertex(crossingClip, crossingBary);
            }
        }
        polygon = next;
        count = nextCount;
    }
    return count < 3 ? 0 : count;
}

// setupScreenTriangle: false for a triangle of zero area after snapping.
bool setupScreenTriangle(vec4 clip[3], out ScreenTriangle tri) {
    double x[3], y[3];
    for (int i = 0; i < 3; ++i) {
        dvec2 p = rasterFromClip(clip[i]);
        x[i] = roundHalfAway(p.x * kSubpixelScale);
        y[i] = roundHalfAway(p.y * kSubpixelScale);
        tri.invW[i] = double(float(1.0 / double(clip[i].w)));
    }
    double area2 = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area2 == 0.0) return false;
    // y points down in raster space, so counter-clockwise in NDC has negative area here.
    tri.isFrontFacing = area2 < 0.0;
    double orientation = area2 > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        tri.a[i] = -(y[k] - y[j]) * orientation;
        tri.b[i] = (x[k] - x[j]) * orientation;
        tri.c[i] = ((y[k] - y[j]) * x[j] - (x[k] - x[j]) * y[j]) * orientation;
        bool isTopLeft = tri.a[i] > 0.0 || (tri.a[i] == 0.0 && tri.b[i] > 0.0);
        tri.bias[i] = isTopLeft ? 0.0 : -1.0;
    }
    tri.invEdgeSum = 1.0 / (area2 * orientation);
    return true;
}

// ScreenTriangle::interpolate: barycentrics at a point given its edge values; returns 1/w
// (<= 0 beyond the triangle's horizon, where bary is left unset).
float interpolate(ScreenTriangle tri, dvec3 e, out vec3 bary) {
    dvec3 q = e * tri.invEdgeSum * tri.invW;
    double sum = q.x + q.y + q.z;
    bary = vec3(0.0);
    if (sum > 0.0) bary = vec3(q / sum);
    return float(sum);
}

// The sample at fixed-point `samplePosition` against one screen triangle made from (part of) the
// source triangle; sourceFromLocal maps its barycentrics to the source's.
bool hitScreenTriangle(vec4 corners[3], mat3 sourceFromLocal, bool cullBack, dvec2 samplePosition, out RasterHit hit) {
    ScreenTriangle tri;
    if (!setupScreenTriangle(corners, tri)) return false;
    if (cullBack && !tri.isFrontFacing) return false;
    dvec3 e = tri.a * samplePosition.x + tri.b * samplePosition.y + tri.c;
    if (any(lessThan(e + tri.bias, dvec3(0.0)))) return false;
    vec3 bary, right, down;
    hit.invW = interpolate(tri, e, bary);
    hit.bary = sourceFromLocal * bary;
    // SamplePattern::footprintStep: a pixel over --aa N, rounded to fixed point.
    double step = max(1.0, roundHalfAway(kSubpixelScale / double(u_flags.y)));
    hit.baryRight = interpolate(tri, e + tri.a * step, right) > 0.0 ? sourceFromLocal * right : hit.bary;
    hit.baryDown = interpolate(tri, e + tri.b * step, down) > 0.0 ? sourceFromLocal * down : hit.bary;
    hit.isFrontFacing = tri.isFrontFacing;
    return true;
}

// setupTriangle and the CPU's per-sample test: whether the triangle with clip-space corners
// `clip` covers the sample at fixed-point raster position `samplePosition`, clipped by the near plane
// and the guard band as needed; back faces culled when cullBack.
bool hitTriangle(vec4 clip[3], bool cullBack, dvec2 samplePosition, out RasterHit hit) {
    if (!needsClipping(clip)) return hitScreenTriangle(clip, mat3(1.0), cullBack, samplePosition, hit);
    ClipVertex polygon[8];
    int count = clipTriangle(clip, polygon);
    for (int i = 1; i + 1 < count; ++i) {
        vec4 corners[3] = vec4[3](polygon[0].clip, polygon[i].clip, polygon[i + 1].clip);
        mat3 sourceFromLocal = mat3(polygon[0].sourceBary, polygon[i].sourceBary, polygon[i + 1].sourceBary);
        if (hitScreenTriangle(corners, sourceFromLocal, cullBack, samplePosition, hit)) return true;
    }
    return false;
}
