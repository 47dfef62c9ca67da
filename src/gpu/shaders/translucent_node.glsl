// A shaded translucent fragment in a per-sample list (fragment_list.glsl), the node type of
// gpu/translucent_resolve.h: written by the passes that shade translucent surfaces, read by
// translucent_resolve.comp.glsl.
struct TranslucentNode {
    vec4 color;  // rgb (not premultiplied), alpha
    float invW;  // 1 / view depth: larger is nearer
    uint next;
};
layout(std430, binding = 7) buffer NodeBuffer { TranslucentNode nodes[]; };
