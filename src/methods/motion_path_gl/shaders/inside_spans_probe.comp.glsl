// insideSpans (moving_triangle.glsl) on a batch of given triangles and points, for the tests
// that hold the GLSL twin to raster::MovingTriangle.
layout(local_size_x = 64) in;

struct SpanProbe {
    vec4 open[3], close[3];
    dvec2 ndc;
    double zNear;
    int checkNearPlane;
};
layout(std430, binding = 0) readonly buffer ProbeBuffer { SpanProbe probes[]; };
struct SpanProbeResult {
    double bounds[8];
    int count;
};
layout(std430, binding = 1) writeonly buffer ResultBuffer { SpanProbeResult results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(probes.length())) return;
    SpanProbe p = probes[i];
    double bounds[8];
    results[i].count = insideSpans(movingTriangle(p.open, p.close), p.ndc, p.zNear, p.checkNearPlane != 0, bounds);
    results[i].bounds = bounds;
}
