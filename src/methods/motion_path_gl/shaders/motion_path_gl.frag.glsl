// motion-path-gl pass 1: for the sample under this fragment of a motion path, the exact time
// spans in which it lies inside the moving triangle (its three edge quadratics), each appended
// to the sample's list as an interval with its depth at both ends. Back faces of single-sided
// triangles are dropped here, as on the CPU.
layout(early_fragment_tests) in;

uniform int u_numSegments;

flat in uint g_segment;

struct PathNode {
    uint segment;
    uint next;
    float t0, t1;          // shutter times
    float depth0, depth1;  // view depth at t0 and t1
};
layout(std430, binding = 7) buffer NodeBuffer { PathNode nodes[]; };

void main() {
    ivec2 s = ivec2(gl_FragCoord.xy);
    dvec2 ndc = sampleNdc(s);
    uint tri = g_segment / uint(u_numSegments);
    int k = int(g_segment % uint(u_numSegments));
    // The corners again, from the scene buffers: cheaper than 24 flat varyings per vertex.
    float segmentStart = float(k) / float(u_numSegments), segmentEnd = float(k + 1) / float(u_numSegments);
    vec4 open[3], close[3];
    float minW = 1e30;
    for (int i = 0; i < 3; ++i) {
        open[i] = clipFromWorld(vertexPositionAt(triangles[tri][i], segmentStart), segmentStart);
        close[i] = clipFromWorld(vertexPositionAt(triangles[tri][i], segmentEnd), segmentEnd);
        minW = min(minW, min(open[i].w, close[i].w));
    }
    MovingTriangle m = movingTriangle(open, close);
    double segmentT0 = double(segmentStart), segmentT1 = double(segmentEnd);
    bool checkNearPlane = !(minW >= u_projection.z);
    bool isDoubleSided = (triangles[tri].w & kDoubleSidedBit) != 0u;
    double bounds[8];
    int n = insideSpans(m, ndc, double(u_projection.z), checkNearPlane, bounds);
    for (int i = 0; i + 1 < n; i += 2) {
        // Exact in double: u = 0 and 1 give the segment's ends to the bit, so pieces abut.
        float t0 = float(segmentT0 + bounds[i] * (segmentT1 - segmentT0));
        float t1 = float(segmentT0 + bounds[i + 1] * (segmentT1 - segmentT0));
        double u0 = (double(t0) - segmentT0) / (segmentT1 - segmentT0), u1 = (double(t1) - segmentT0) / (segmentT1 - segmentT0);
        HomogeneousSample s0 = sampleAt(m, u0, ndc), s1 = sampleAt(m, u1, ndc);
        if (!s0.isValid || !s1.isValid || (!isDoubleSided && !isFrontFacingAt(m, 0.5 * (u0 + u1)))) {
            atomicAdd(listMethodCounter, 1u);  // culled intervals
            continue;
        }
        uint index, next;
        if (appendNode(s, index, next)) nodes[index] = PathNode(g_segment, next, t0, t1, float(s0.viewDepth), float(s1.viewDepth));
    }
}
