// post-filter-gl velocity pass: the scene at shutter centre, with each vertex's clip position at
// shutter open and close (each with the camera of that time) for the fragment's velocity.
out vec4 v_clipOpen;
out vec4 v_clipClose;
flat out uint v_triangle;

void main() {
    uint tri = uint(gl_VertexID) / 3u;
    uint v = triangles[tri][uint(gl_VertexID) % 3u];
    vec3 position, normal;
    vertexAt(v, 0.5, position, normal);
    vec3 open, close;
    vertexAt(v, 0.0, open, normal);
    vertexAt(v, 1.0, close, normal);
    v_clipOpen = clipFromWorld(open, 0.0);
    v_clipClose = clipFromWorld(close, 1.0);
    v_triangle = tri;
    vec4 clip = clipFromWorld(position, 0.5);
    gl_Position = vec4(clip.x, -clip.y, clip.z, clip.w);  // raster rows top first
}
