// post-filter-gl: TileMax (NEIGHBOR_PASS 0: the longest velocity of each k x k tile, in
// row-major order as the CPU scans) or NeighborMax (1: the longest of each tile's 3 x 3).
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D u_input;
layout(rgba32f, binding = 1) uniform writeonly image2D u_output;
uniform ivec4 u_tiles;  // tiles wide, tiles high, tile side k, unused

vec2 longer(vec2 a, vec2 b) { return dot(b, b) > dot(a, a) ? b : a; }

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_tiles.x || t.y >= u_tiles.y) return;
    vec2 m = vec2(0.0);
#if NEIGHBOR_PASS
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = t + ivec2(dx, dy);
            if (q.x >= 0 && q.y >= 0 && q.x < u_tiles.x && q.y < u_tiles.y) m = longer(m, imageLoad(u_input, q).xy);
        }
#else
    int k = u_tiles.z;
    for (int y = t.y * k; y < min((t.y + 1) * k, u_viewport.w); ++y)
        for (int x = t.x * k; x < min((t.x + 1) * k, u_viewport.z); ++x) m = longer(m, imageLoad(u_input, ivec2(x, y)).xy);
#endif
    imageStore(u_output, t, vec4(m, 0.0, 0.0));
}
