// Per sample, blends the translucent fragments in front of the opaque surface front to back
// over it (raster/translucency.cpp) and adds the result, with its coverage in alpha (1 over an
// opaque surface, else what the layers take from the background), to the running sum, weighted by the
// row's exposure of u_rowCell when it is a stretch of the shutter (else 1).
layout(local_size_x = 8, local_size_y = 8) in;

uniform vec2 u_rowCell;

layout(rgba32f, binding = 2) uniform readonly image2D u_opaque;  // rgb, 1/w of the opaque surface (0: none)
layout(rgba32f, binding = 3) uniform image2D u_sum;

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (s.x >= u_viewport.x || s.y >= u_viewport.y) return;
    vec4 opaque = imageLoad(u_opaque, s);
    vec3 color = opaque.w > 0.0 ? opaque.rgb : u_background.rgb;
    // The nearest MAX_LAYERS fragments, sorted nearest first (largest 1/w).
    TranslucentNode layers[MAX_LAYERS];
    int count = 0;
    bool isOverflowing = false;
    uint node = imageLoad(u_heads, s).x;
    for (uint guard = 0u; node != kEndOfList && node < u_listCapacity && guard < u_sampleBudget; ++guard) {
        TranslucentNode f = nodes[node];
        node = f.next;
        if (f.invW <= opaque.w) continue;
        if (count == MAX_LAYERS) {
            isOverflowing = true;
            if (f.invW <= layers[count - 1].invW) continue;
            --count;
        }
        // Swapped down into place, both neighbours read before either is written: llvmpipe
        // miscompiles the textbook shifting insertion (elements come out duplicated or zero).
        layers[count] = f;
        for (int i = count++; i > 0; --i) {
            TranslucentNode nearer = layers[i - 1], inserted = layers[i];
            if (!(nearer.invW < inserted.invW)) break;
            layers[i - 1] = inserted;
            layers[i] = nearer;
        }
    }
    if (isOverflowing) atomicAdd(listMethodCounter, 1u);  // samples with more than MAX_LAYERS
    vec3 sum = vec3(0.0);
    float transmittance = 1.0;
    for (int i = 0; i < count; ++i) {
        sum += transmittance * layers[i].color.a * layers[i].color.rgb;
        transmittance *= 1.0 - layers[i].color.a;
    }
    float weight = 1.0;
    if (u_rowCell.y > u_rowCell.x) {
        ShutterWindow w = rowWindow(s.y / u_flags.y);
        weight = exposureAt(w, u_rowCell.y) - exposureAt(w, u_rowCell.x);
    }
    float coverage = 1.0 - transmittance * (opaque.w > 0.0 ? 0.0 : 1.0);
    imageStore(u_sum, s, imageLoad(u_sum, s) + weight * vec4(sum + transmittance * color, coverage));
}
