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
    dvec2 at[MAX_KEYS + 1];  // at each time
    corner.needsClipping = 0;
    for (int k = 0; k < numTimes; ++k) {
        vec4 clip = clipAt(v, times[k]);
        if (!isInsideClipVolume(clip)) {
            corner.needsClipping = 1;
            continue;
        }
        at[k] = rasterFromClip(clip);
        lo = min(lo, at[k]);
        hi = max(hi, at[k]);
    }
    corner.box = dvec4(lo, hi);
    bool isCurved = u_projection.w != 0.0 || mesh.y > 1u;
    corner.chordDeviation = isCurved && corner.needsClipping == 0 ? length(at[2] - 0.5 * (at[0] + at[1])) : 0.0;
    // Joints inside: the stretches between t0, them (ascending, times[3] on) and t1.
    for (int k = 2; isCurved && corner.needsClipping == 0 && numTimes > 3 && k < numTimes; ++k) {
        int a = k == 2 ? 0 : k, b = k + 1 < numTimes ? k + 1 : 1;
        vec4 middle = clipAt(v, 0.5 * (times[a] + times[b]));
        if (!isInsideClipVolume(middle)) {
            corner.needsClipping = 1;
            continue;
        }
        corner.chordDeviation = max(corner.chordDeviation, length(rasterFromClip(middle) - 0.5 * (at[a] + at[b])));
    }
}
