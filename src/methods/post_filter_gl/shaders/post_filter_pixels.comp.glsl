// post-filter-gl: per pixel, the colour and coverage box-filtered over its samples, and the depth and
// velocity of its nearest sample, clamped as clampVelocities does (methods/post_filter).
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D u_sampleColor;
layout(rgba32f, binding = 1) uniform readonly image2D u_sampleMotion;
layout(rgba32f, binding = 2) uniform writeonly image2D u_pixelColor;
layout(rgba32f, binding = 3) uniform writeonly image2D u_pixelMotion;  // velocity, depth (1e30: background)
uniform float u_maxRadius;
uniform float u_velocityScale;  // ReconstructionOptions::velocityScale

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_viewport.z || p.y >= u_viewport.w) return;
    int n = u_flags.y;
    vec4 color = vec4(0.0);  // rgb, coverage
    vec4 nearest = vec4(0.0, 0.0, 1e30, 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            ivec2 s = p * n + ivec2(i, j);
            color += imageLoad(u_sampleColor, s);
            vec4 m = imageLoad(u_sampleMotion, s);
            if (m.w > 0.0 && m.z < nearest.z) nearest = m;
        }
    vec2 v = nearest.xy * u_velocityScale;
    float speed = length(v);
    if (!(speed >= 0.5)) v = vec2(0.0);
    else if (speed > u_maxRadius) v *= u_maxRadius / speed;
    imageStore(u_pixelColor, p, color / float(n * n));
    imageStore(u_pixelMotion, p, vec4(v, nearest.z, 0.0));
}
