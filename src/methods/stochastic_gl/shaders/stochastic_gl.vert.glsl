// stochastic-gl: one corner of a triangle over the stratum [u_stratum.x, u_stratum.y], at the
// times the CPU's spaceTimeBounds looks at (both ends, the middle, and the joints between: every
// key of linear keys, every Bezier piece's end): its raster box, how far its screen path bends
// from the chord (of the stratum, and of each stretch between joints), and whether the triangle
// needs clipping there. The geometry shader joins the three corners.
uniform vec2 u_stratum;

out CornerBounds {
    dvec4 box;              // raster lo.xy, hi.xy
    double chordDeviation;  // the largest |p(mid) - (p(a) + p(b)) / 2| over the stretches [a, b], for curved screen paths, else 0
    int needsClipping;      // 1: near plane or guard band crossed at one of the times
} corner;

void main() {
    uint v = triangles[uint(gl_VertexID) / 3u][uint(gl_VertexID) % 3u];
    uvec4 mesh = meshes[vertexInfo[v].x];
    uint numKeys = mesh.x;
    uint step = max(mesh.y, 1u);  // joints where the path may turn: every key, or every Bezier piece's end
    float t0 = u_stratum.x, t1 = u_stratum.y;
    float times[MAX_KEYS + 1];
    times[0] = t0;
    times[1] = t1;
    times[2] = 0.5 * (t0 + t1);
    int numTimes = 3;
    for (uint k = step; k + 1u < numKeys; k += step) {
        float key = float(double(k) / double(numKeys - 1u));  // keyTime, correctly rounded
        if (key > t0 && key < t1) times[numTimes++] = key;
    }
    dvec2 lo = dvec2(1e300), hi = dvec2(-1e300);
    dvec2 ends[3];  // at t0, t1 and mid-stratum
    corner.needsClipping = 0;
    for (int k = 0; k < numTimes; ++k) {
        vec4 clip = clipAt(v, times[k]);
        if (!isInsideClipVolume(clip)) {
            corner.needsClipping = 1;
            continue;
        }
        dvec2 p = rasterFromClip(clip);
        lo = min(lo, p);
        hi = max(hi, p);
        if (k < 3) ends[k] = p;
    }
    corner.box = dvec4(lo, hi);
    bool isCurved = u_projection.w != 0.0 || mesh.y > 1u;
    corner.chordDeviation = isCurved && corner.needsClipping == 0 ? length(ends[2] - 0.5 * (ends[0] + ends[1])) : 0.0;
    // Joints inside: the stretches between t0, them (ascending, times[3] on) and t1.
    for (int k = 2; isCurved && numTimes > 3 && k < numTimes; ++k) {
        float a = k == 2 ? t0 : times[k], b = k + 1 < numTimes ? times[k + 1] : t1;
        vec4 ca = clipAt(v, a), cb = clipAt(v, b), cm = clipAt(v, 0.5 * (a + b));
        if (!isInsideClipVolume(ca) || !isInsideClipVolume(cb) || !isInsideClipVolume(cm)) {
            corner.needsClipping = 1;
            continue;
        }
        corner.chordDeviation = max(corner.chordDeviation, length(rasterFromClip(cm) - 0.5 * (rasterFromClip(ca) + rasterFromClip(cb))));
    }
}
