// The scene on the GPU (gpu/scene_buffers.h): triangles, key poses, materials, camera, light.
// Every GL method includes this file first; the layouts mirror scene_buffers.cpp.

struct MaterialData {
    vec4 baseColorOpacity;  // rgb base colour, opacity
    vec4 phong;             // specular, shininess, alpha cutoff, unused
    ivec4 info;             // texture (-1: none), alpha mode (0 opaque, 1 mask, 2 blend), double-sided, translucent
};

layout(std430, binding = 0) readonly buffer TriangleBuffer { uvec4 triangles[]; };        // v0, v1, v2, material
layout(std430, binding = 1) readonly buffer KeyPositionBuffer { vec4 keyPositions[]; };   // xyz; key-major per mesh
layout(std430, binding = 2) readonly buffer KeyNormalBuffer { vec4 keyNormals[]; };       // same layout; zero without normals
layout(std430, binding = 3) readonly buffer VertexBuffer { uvec4 vertexInfo[]; };         // mesh, first key index, key stride
layout(std430, binding = 4) readonly buffer VertexAttributeBuffer { vec4 vertexAttributes[]; };  // per vertex: colour, then (uv, 0, 0)
layout(std430, binding = 5) readonly buffer MeshBuffer { uvec4 meshes[]; };               // keys, Bezier pieces' degree (0: linear keys), has normals, unused
layout(std430, binding = 6) readonly buffer MaterialBuffer { MaterialData materials[]; };

layout(std140, binding = 0) uniform SceneBlock {
    vec4 u_eyeOpen;          // xyz camera position at t = 0
    vec4 u_eyeClose;         // at t = 1
    vec4 u_rotationOpen;     // world-from-camera quaternion (x, y, z, w)
    vec4 u_rotationClose;    // negated where that is the shorter way from u_rotationOpen
    vec4 u_slerp;            // angle between the rotations, its sine, 1 where glm::slerp mixes linearly, unused
    vec4 u_projection;       // focal f / aspect, f, zNear, camera moves (0 or 1)
    vec4 u_toLight;
    vec4 u_lightColor;
    vec4 u_ambient;
    vec4 u_background;
    ivec4 u_viewport;        // width, height (in samples), pixels wide, pixels high
    ivec4 u_flags;           // lit (Phong) 1 / unlit 0, sample grid N, grid pattern 1 / n-rooks 0, unused
    vec4 u_shutter;          // rolling duration D, curve points, 1 where exposure is time (box, global), 1 for a box curve
    vec4 u_shutterCurve[32]; // curve point x, normalised weight w, exposure up to x, unused (scene/shutter.h)
};

uniform sampler2D u_textures[MAX_TEXTURES];

// The exposure of one sample row (ShutterWindow, scene/shutter.h): the shutter's stretch
// [start, start + length] under the curve. g_window is the current sample's; a shader that
// shades samples sets it from their row (sampleRow), else it is the whole shutter.
struct ShutterWindow {
    float start;
    float length;
    bool isIdentity;  // exposure is time: box curve, global shutter
};
ShutterWindow g_window = ShutterWindow(0.0, 1.0, true);

ShutterWindow rowWindow(int row) {
    float d = u_shutter.x;
    if (d >= 1.0) return ShutterWindow(0.0, 1.0, u_shutter.z != 0.0);
    int h = u_viewport.w;
    return ShutterWindow(h > 1 ? (1.0 - d) * float(row) / float(h - 1) : 0.0, d, false);
}

// The curve segment [i - 1, i] that holds v in column c of u_shutterCurve (0: x, 2: exposure).
int curveSegment(float v, int c) {
    int n = int(u_shutter.y);
    for (int i = 1; i < n - 1; ++i)
        if (v < u_shutterCurve[i][c]) return i;
    return n - 1;
}

// The curve's exposure up to x in [0, 1] (closed form: quadratic within a segment).
float curveExposure(float x) {
    if (!(x > 0.0)) return 0.0;
    if (x >= 1.0) return 1.0;
    if (u_shutter.w != 0.0) return x;
    int i = curveSegment(x, 0);
    vec4 a = u_shutterCurve[i - 1], b = u_shutterCurve[i];
    float h = x - a.x, slope = (b.y - a.y) / (b.x - a.x);
    return min(1.0, a.z + h * (a.y + 0.5 * slope * h));
}

// The x whose exposure is u.
float curvePosition(float u) {
    u = clamp(u, 0.0, 1.0);
    if (u_shutter.w != 0.0) return u;
    int i = curveSegment(u, 2);
    vec4 a = u_shutterCurve[i - 1], b = u_shutterCurve[i];
    float slope = (b.y - a.y) / (b.x - a.x), rest = u - a.z, qa = 0.5 * slope, qb = a.y;
    float h = !(rest > 0.0) ? 0.0
            : abs(qa) < 1e-12 ? (qb > 0.0 ? rest / qb : 0.0) : 2.0 * rest / (qb + sqrt(max(0.0, qb * qb + 4.0 * qa * rest)));
    return clamp(a.x + h, a.x, b.x);
}

float exposureAt(ShutterWindow w, float t) { return w.isIdentity ? clamp(t, 0.0, 1.0) : curveExposure((t - w.start) / w.length); }
float timeAt(ShutterWindow w, float u) { return w.isIdentity ? u : min(1.0, w.start + w.length * curvePosition(u)); }
// The time a fraction f of the way through [t0, t1] by the window's exposure.
float timeBetween(ShutterWindow w, float t0, float t1, float f) {
    if (w.isIdentity) return t0 + f * (t1 - t0);
    float u0 = exposureAt(w, t0), u1 = exposureAt(w, t1);
    if (!(u1 > u0)) return t0 + f * (t1 - t0);
    return clamp(timeAt(w, u0 + f * (u1 - u0)), t0, t1);
}

// triangles[i].w: the material in the low 30 bits; the top bit double-sided; the next, still:
// the triangle's keys and normals all equal under a still camera (SceneBuffers), so every point
// of it shades the same at every time.
const uint kMaterialMask = 0x3fffffffu;
const uint kDoubleSidedBit = 0x80000000u;
const uint kStillBit = 0x40000000u;

// Motion weights (scene/motion.cpp): position(t) = sum of keys times weights. bezierOrder: the
// degree of each Bezier piece, 0 for piecewise-linear keys.
void motionWeights(uint numKeys, uint bezierOrder, float t, out int first, out int count, out float w[MAX_KEYS]) {
    t = clamp(t, 0.0, 1.0);
    for (int i = 0; i < MAX_KEYS; ++i) w[i] = 0.0;
    if (bezierOrder == 0u || numKeys == 2u) {
        float x = t * float(numKeys - 1u);
        int segment = min(int(x), int(numKeys) - 2);
        float u = x - float(segment);
        first = segment;
        count = 2;
        w[0] = 1.0 - u;
        w[1] = u;
        return;
    }
    int n = int(bezierOrder), pieces = (int(numKeys) - 1) / n;
    precise float x = t * float(pieces);
    int piece = min(int(x), pieces - 1);
    precise float u = x - float(piece);
    first = piece * n;
    count = n + 1;
    w[0] = 1.0;
    for (int degree = 1; degree <= n; ++degree)
        for (int i = degree; i >= 0; --i) {
            // precise: no fused multiply-adds, so the weights round as the CPU's do.
            precise float fromLeft = i > 0 ? w[i - 1] * u : 0.0;
            precise float stay = i < degree ? w[i] * (1.0 - u) : 0.0;
            precise float weight = fromLeft + stay;
            w[i] = weight;
        }
}

// World position and normal of global vertex v at shutter time t.
void vertexAt(uint v, float t, out vec3 position, out vec3 normal) {
    uvec4 info = vertexInfo[v];
    uvec4 mesh = meshes[info.x];
    int first, count;
    float w[MAX_KEYS];
    motionWeights(mesh.x, mesh.y, t, first, count, w);
    precise vec3 p = vec3(0.0), n = vec3(0.0);  // summed as the CPU sums (MotionWeights::apply)
    for (int i = 0; i < count; ++i) {
        uint k = info.y + uint(first + i) * info.z;
        p += keyPositions[k].xyz * w[i];
        n += keyNormals[k].xyz * w[i];
    }
    position = p;
    normal = n;
}

vec3 vertexPositionAt(uint v, float t) {
    vec3 p, n;
    vertexAt(v, t, p, n);
    return p;
}

vec2 vertexUv(uint v) { return vertexAttributes[2u * v + 1u].xy; }
vec4 vertexColor(uint v) { return vertexAttributes[2u * v]; }
bool meshHasNormals(uint v) { return meshes[vertexInfo[v].x].z != 0u; }

vec3 eyeAt(float t) { return mix(u_eyeOpen.xyz, u_eyeClose.xyz, t); }

// glm::slerp of the camera's two orientations. Its angle and sine come from the CPU: GL's acos
// is an approximation, and llvmpipe's moved a turning camera's view enough to flip samples.
vec4 slerpRotation(float t) {
    vec4 x = u_rotationOpen, z = u_rotationClose;
    if (u_slerp.z != 0.0) return mix(x, z, t);
    precise vec4 sum = sin((1.0 - t) * u_slerp.x) * x + sin(t * u_slerp.x) * z;
    return vec4(dvec4(sum) / double(u_slerp.y));  // correctly rounded, as the CPU's float division
}

mat3 mat3FromQuat(vec4 q) {
    float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z, xz = q.x * q.z, xy = q.x * q.y, yz = q.y * q.z;
    float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    return mat3(vec3(1.0 - 2.0 * (yy + zz), 2.0 * (xy + wz), 2.0 * (xz - wy)),
                vec3(2.0 * (xy - wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz + wx)),
                vec3(2.0 * (xz + wy), 2.0 * (yz - wx), 1.0 - 2.0 * (xx + yy)));
}

// Camera::clipFromWorld(t): infinite perspective, clip w = view depth.
vec4 clipFromWorld(vec3 p, float t) {
    vec3 eye = u_eyeOpen.xyz;
    vec4 q = u_rotationOpen;
    if (u_projection.w != 0.0) {
        eye = eyeAt(t);
        q = slerpRotation(t);
    }
    vec3 view = transpose(mat3FromQuat(q)) * (p - eye);
    return vec4(view.x * u_projection.x, view.y * u_projection.y, -view.z - 2.0 * u_projection.z, -view.z);
}

// Fixed-point raster position of sample texel s (raster rows, top first; 1/256 pixel units):
// the CPU's sample position (raster/sample_pattern.cpp): n-rooks, or the grid's cell centre.
// Whole numbers. An n-rooks sample stays inside its texel, less than half a texel from its centre.
dvec2 sampleRaster(ivec2 s) {
    int n = u_flags.y;
    ivec2 pixel = s / n, sub = s - pixel * n;
    // (GLSL leaves % of a negative operand undefined; llvmpipe takes it as unsigned, which is the
    // true residue only where n is a power of two: at --aa 3 the pattern was another one.)
    int a = (sub.y - sub.x + n) % n;
    dvec2 offset = u_flags.z != 0 ? floor((dvec2(sub) + 0.5) / double(n) * 256.0)
                                  : floor((dvec2(sub) * double(n) + double(a) + 0.5) / double(n * n) * 256.0);
    return dvec2(pixel) * 256.0 + offset;
}

// NDC of sample texel s: sampleRaster in normalized device coordinates.
dvec2 sampleNdc(ivec2 s) {
    dvec2 raster = sampleRaster(s) / 256.0;
    return dvec2(2.0 * raster.x / double(u_viewport.z) - 1.0, 1.0 - 2.0 * raster.y / double(u_viewport.w));
}
