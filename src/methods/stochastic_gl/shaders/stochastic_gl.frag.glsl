// stochastic-gl: the test of triangle g_triangle at this sample texel's own shutter time, as
// the CPU's stochastic tests it (raster.glsl), and the shading of a hit. Opaque pass
// (TRANSLUCENT_PASS 0): writes the colour and 1/w, and a depth that orders as 1/w so the
// nearest hit wins. Translucent pass: appends (colour, alpha, 1/w) to the sample's list when
// in front of the opaque hit.
layout(r32f, binding = 4) uniform readonly image2D u_sampleTimes;  // this stratum's time per sample

flat in uint g_triangle;

#if TRANSLUCENT_PASS
layout(rgba32f, binding = 2) uniform readonly image2D u_opaque;  // rgb, 1/w of the opaque hit (0: none)
#else
layout(location = 0) out vec4 o_color;
#endif

// An order-reversing map of positive 1/w to depth in [0, 0.5] that keeps every float apart
// (a shift of the bit pattern), so the depth test picks the CPU's nearest hit and keeps the
// first drawn, lowest-index triangle on ties as the CPU does. 1/w is clamped to
// [2^-63, 2^63], far beyond any view depth a scene has.
float depthFromInvW(float invW) {
    uint bits = clamp(floatBitsToUint(invW), 0x20000000u, 0x5f000000u);
    return uintBitsToFloat(0x5f000000u - bits);
}

void main() {
    ivec2 s = ivec2(gl_FragCoord.xy);
    float t = imageLoad(u_sampleTimes, s).x;
    uvec4 tri = triangles[g_triangle];
    vec3 corners[3], cornerNormals[3];
    vec4 clip[3];
    for (int i = 0; i < 3; ++i) {
        vertexAt(tri[i], t, corners[i], cornerNormals[i]);
        clip[i] = clipAt(tri[i], t);
    }
    bool isDoubleSided = (tri.w & kDoubleSidedBit) != 0u;
    RasterHit hit;
    if (!hitTriangle(clip, !isDoubleSided, sampleRaster(s), hit)) discard;
#if TRANSLUCENT_PASS
    // Behind the opaque hit it would be hidden: spare the list.
    if (hit.invW <= imageLoad(u_opaque, s).w) discard;
#endif
    SurfacePoint p = surfacePoint(g_triangle, corners, cornerNormals, hit.bary, hit.baryRight, hit.baryDown, hit.isFrontFacing);
    vec4 shaded = shadeSurface(p, eyeAt(t));
#if TRANSLUCENT_PASS
    uint index, next;
    if (appendNode(s, index, next)) nodes[index] = TranslucentNode(shaded, hit.invW, next);
#else
    o_color = vec4(shaded.rgb, hit.invW);
    gl_FragDepth = depthFromInvW(hit.invW);
#endif
}
