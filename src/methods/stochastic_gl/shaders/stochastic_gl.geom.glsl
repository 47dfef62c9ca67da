// stochastic-gl: the space-time bounding geometry of one triangle over the stratum: a quad
// over the pixels it may cover at some time in it (the CPU's spaceTimeBounds: the corners'
// boxes at the stratum's times, padded by a pixel for snapping and by twice the chord
// deviation for curved paths; the whole image when it needs clipping). Triangles of the other
// pass (opaque or translucent) emit nothing.
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

in CornerBounds {
    dvec4 box;
    double chordDeviation;
    int needsClipping;
} corners[];

flat out uint g_triangle;

void main() {
    uint tri = uint(gl_PrimitiveIDIn);
    if (isTranslucentMaterial(triangles[tri].w & kMaterialMask) != (TRANSLUCENT_PASS != 0)) return;
    dvec2 image = dvec2(u_viewport.zw);
    dvec4 pixels = dvec4(0.0, 0.0, image - 1.0);  // inclusive bounds
    if (corners[0].needsClipping + corners[1].needsClipping + corners[2].needsClipping == 0) {
        dvec2 lo = min(min(corners[0].box.xy, corners[1].box.xy), corners[2].box.xy);
        dvec2 hi = max(max(corners[0].box.zw, corners[1].box.zw), corners[2].box.zw);
        double pad = 1.0 + 2.0 * (corners[0].chordDeviation + corners[1].chordDeviation + corners[2].chordDeviation);
        pixels = dvec4(max(floor(lo - pad), dvec2(0.0)), min(floor(hi + pad), image - 1.0));
    }
    if (pixels.x > pixels.z || pixels.y > pixels.w) return;
    // Pixel edges in NDC: GL's row r is raster row r (sample texels are in raster rows).
    vec4 ndc = vec4(2.0 * pixels.xy / image - 1.0, 2.0 * (pixels.zw + 1.0) / image - 1.0);
    for (int corner = 0; corner < 4; ++corner) {  // a strip: (x0, y0), (x1, y0), (x0, y1), (x1, y1)
        g_triangle = tri;
        gl_Position = vec4(corner % 2 == 0 ? ndc.x : ndc.z, corner < 2 ? ndc.y : ndc.w, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
