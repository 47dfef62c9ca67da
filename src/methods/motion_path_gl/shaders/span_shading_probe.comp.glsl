// shadeTimeSpanAt (span_shading.glsl) on a batch of given (triangle, span, site), for the tests
// that hold the GLSL twin to exposure::shadeTriangleSpan.
layout(local_size_x = 64) in;

struct ShadingProbe {
    dvec2 ndc;
    float t0, t1;
    uint triangle;
    uint flags;  // 1: held to the triangle, 2: a box footprint
    vec2 footprintPixels;
};
layout(std430, binding = 10) readonly buffer ShadingProbeBuffer { ShadingProbe probes[]; };
layout(std430, binding = 11) writeonly buffer ShadingResultBuffer { vec4 shaded[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(probes.length())) return;
    ShadingProbe p = probes[i];
    shaded[i] = shadeTimeSpanAt(p.triangle, p.t0, p.t1,
                                ShadingSite(p.ndc, dvec2(p.footprintPixels), (p.flags & 1u) != 0u, (p.flags & 2u) != 0u, ivec2(1), kMaxSweptBoxTaps));
}
