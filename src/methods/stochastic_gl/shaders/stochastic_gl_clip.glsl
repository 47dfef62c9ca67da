// stochastic-gl: a vertex's clip position at a sample's time, computed as the CPU's stochastic
// computes it, so that both test the same corners. With a static camera the CPU takes every
// key to clip space once (u_staticClipFromWorld, its own matrix) and weights the clip-space
// keys; with a moving camera it transforms the world position at t.
uniform mat4 u_staticClipFromWorld;

// glm's mat4 * vec4 (w = 1), in its order: (m0 x + m1 y) + (m2 z + m3).
vec4 staticClipOfKey(vec3 p) {
    precise vec4 xy = u_staticClipFromWorld[0] * p.x + u_staticClipFromWorld[1] * p.y;
    precise vec4 zw = u_staticClipFromWorld[2] * p.z + u_staticClipFromWorld[3];
    precise vec4 clip = xy + zw;
    return clip;
}

vec4 clipAt(uint v, float t) {
    if (u_projection.w != 0.0) return clipFromWorld(vertexPositionAt(v, t), t);
    uvec4 info = vertexInfo[v];
    uvec4 mesh = meshes[info.x];
    int first, count;
    float w[MAX_KEYS];
    motionWeights(mesh.x, mesh.y, t, first, count, w);
    precise vec4 clip = staticClipOfKey(keyPositions[info.y + uint(first) * info.z].xyz) * w[0];
    for (int i = 1; i < count; ++i) clip += staticClipOfKey(keyPositions[info.y + uint(first + i) * info.z].xyz) * w[i];
    return clip;
}
