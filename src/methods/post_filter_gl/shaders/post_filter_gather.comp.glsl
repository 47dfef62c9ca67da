// post-filter-gl: the gather of methods/post_filter/reconstruction_filter.cpp, per pixel, of
// colour and coverage (alpha) alike.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D u_pixelColor;
layout(rgba32f, binding = 1) uniform readonly image2D u_pixelMotion;
layout(rgba32f, binding = 2) uniform readonly image2D u_neighborMax;
layout(rgba32f, binding = 3) uniform writeonly image2D u_output;
layout(std430, binding = 8) readonly buffer JitterBuffer { float jitters[]; };  // per pixel, from the CPU's hash
uniform ivec4 u_gather;  // tile side k, taps, unused, unused
uniform float u_softDepth;

float cone(float distance, float speed) { return clamp(1.0 - distance / max(speed, 1e-6), 0.0, 1.0); }

float cylinder(float distance, float speed) {
    float lo = 0.95 * speed, hi = 1.05 * speed;
    if (distance <= lo) return 1.0;
    if (distance >= hi) return 0.0;
    float x = (distance - lo) / (hi - lo);
    return 1.0 - x * x * (3.0 - 2.0 * x);
}

float softDepthCompare(float a, float b, float extent) { return clamp(1.0 - (a - b) / extent, 0.0, 1.0); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(u_viewport.z, u_viewport.w);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 centre = imageLoad(u_pixelColor, p);
    vec2 vn = imageLoad(u_neighborMax, p / u_gather.x).xy;
    if (length(vn) <= 0.5) {
        imageStore(u_output, p, centre);
        return;
    }
    vec4 mx = imageLoad(u_pixelMotion, p);
    float speedX = length(mx.xy), zx = mx.z;
    float weight = 1.0 / max(speedX, 0.5);
    vec4 sum = centre * weight;
    float jitter = jitters[p.y * size.x + p.x];
    int taps = u_gather.y;
    for (int i = 0; i < taps; ++i) {
        if (i == (taps - 1) / 2) continue;
        float t = -1.0 + 2.0 * (float(i) + jitter + 1.0) / float(taps + 1);
        ivec2 q = clamp(ivec2(floor(vec2(p) + 0.5 + vn * t)), ivec2(0), size - 1);
        vec4 my = imageLoad(u_pixelMotion, q);
        float distance = length(vec2(q - p));
        float zy = my.z, extent = u_softDepth * min(zx, zy);
        float speedY = length(my.xy);
        float alpha = softDepthCompare(zy, zx, extent) * cone(distance, speedY) + softDepthCompare(zx, zy, extent) * cone(distance, speedX) +
                      2.0 * cylinder(distance, speedY) * cylinder(distance, speedX);
        weight += alpha;
        sum += alpha * imageLoad(u_pixelColor, q);
    }
    imageStore(u_output, p, sum / weight);
}
