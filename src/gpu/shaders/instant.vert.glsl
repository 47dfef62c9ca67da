// The scene at shutter time u_time (gpu::InstantPasses), pulled from the scene buffers by vertex
// index (three per triangle), transformed as the CPU's exposure::InstantFrame does.
uniform float u_time;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
out vec4 v_color;
flat out uint v_triangle;

void main() {
    uint tri = uint(gl_VertexID) / 3u;
    uint v = triangles[tri][uint(gl_VertexID) % 3u];
    vec3 position, normal;
    vertexAt(v, u_time, position, normal);
    v_position = position;
    v_normal = normal;
    v_uv = vertexUv(v);
    v_color = vertexColor(v);
    v_triangle = tri;
    vec4 clip = clipFromWorld(position, u_time);
    gl_Position = vec4(clip.x, -clip.y, clip.z, clip.w);  // raster rows top first
}
