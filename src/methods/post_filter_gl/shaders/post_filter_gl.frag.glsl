// post-filter-gl velocity pass: the nearest opaque surface's screen velocity (McGuire's V: half
// the displacement over the shutter, in pixels) and view depth; w = 1 marks a surface.
in vec4 v_clipOpen;
in vec4 v_clipClose;
flat in uint v_triangle;

layout(location = 0) out vec4 o_motion;

vec2 rasterOf(vec4 clip) { return vec2((clip.x / clip.w * 0.5 + 0.5) * float(u_viewport.z), (0.5 - 0.5 * clip.y / clip.w) * float(u_viewport.w)); }

void main() {
    uvec4 t = triangles[v_triangle];
    uint m = t.w & kMaterialMask;
    bool isDoubleSided = (t.w & kDoubleSidedBit) != 0u;
    if (!gl_FrontFacing && !isDoubleSided) discard;
    if (isTranslucentMaterial(m)) discard;
    vec2 velocity = 0.5 * (rasterOf(v_clipClose) - rasterOf(v_clipOpen));
    if (!(v_clipOpen.w > 1e-6 && v_clipClose.w > 1e-6) || any(isnan(velocity)) || any(isinf(velocity))) velocity = vec2(0.0);
    o_motion = vec4(velocity, 1.0 / gl_FragCoord.w, 1.0);
}
