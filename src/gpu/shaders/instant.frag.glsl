// The scene at one instant (gpu::InstantPasses): shades a fragment at u_time. Opaque pass
// (TRANSLUCENT_PASS 0, BLEND_PASS 0): writes the colour and 1/w, depth tested. Translucent pass:
// appends (colour, alpha, depth) to the sample's list, behind the opaque depth test (early
// tests, so hidden fragments append nothing). Blend pass (BLEND_PASS 1): writes colour and
// alpha for fixed-function blending in submission order (the blur shell as Jones draws it).
uniform float u_time;

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_color;
flat in uint v_triangle;

#if TRANSLUCENT_PASS || BLEND_PASS
layout(early_fragment_tests) in;
#endif
#if !TRANSLUCENT_PASS
layout(location = 0) out vec4 o_color;
#endif

void main() {
    uvec4 t = triangles[v_triangle];
    uint m = t.w & kMaterialMask;
    bool isDoubleSided = (t.w & kDoubleSidedBit) != 0u;
    if (!gl_FrontFacing && !isDoubleSided) discard;
#if TRANSLUCENT_PASS || BLEND_PASS
    if (!isTranslucentMaterial(m)) discard;
#else
    if (isTranslucentMaterial(m)) discard;
#endif
    SurfacePoint p;
    p.position = v_position;
    p.normal = v_normal;
    if (!meshHasNormals(t.x)) {
        vec3 c0 = vertexPositionAt(t.x, u_time), c1 = vertexPositionAt(t.y, u_time), c2 = vertexPositionAt(t.z, u_time);
        p.normal = cross(c1 - c0, c2 - c0);
    }
    p.uv = v_uv;
    // One pixel of the image is u_flags.y sample texels.
    // One texel of the sample grid is one sample spacing: the footprint the box filter needs.
    p.duvdx = dFdxFine(v_uv);
    p.duvdy = dFdyFine(v_uv);
    p.vertexColor = v_color;
    p.material = m;
    p.isFrontFacing = gl_FrontFacing;
    vec4 shaded = shadeSurface(p, eyeAt(u_time));
#if TRANSLUCENT_PASS
    ivec2 s = ivec2(gl_FragCoord.xy);
    uint index, next;
    if (appendNode(s, index, next)) nodes[index] = TranslucentNode(shaded, gl_FragCoord.w, next);
#elif BLEND_PASS
    o_color = shaded;
#else
    o_color = vec4(shaded.rgb, gl_FragCoord.w);
#endif
}
