// motion-path-gl pass 1: each vertex at both ends of linear segment u_segment, transformed to
// clip space (the key poses are evaluated at the segment's end times, as on the CPU).
uniform int u_segment;
uniform int u_numSegments;

out vec4 v_open;
out vec4 v_close;
flat out uint v_triangle;

void main() {
    uint tri = uint(gl_VertexID) / 3u;
    uint v = triangles[tri][uint(gl_VertexID) % 3u];
    float t0 = float(u_segment) / float(u_numSegments), t1 = float(u_segment + 1) / float(u_numSegments);
    v_open = clipFromWorld(vertexPositionAt(v, t0), t0);
    v_close = clipFromWorld(vertexPositionAt(v, t1), t1);
    v_triangle = tri;
    gl_Position = vec4(0.0);
}
