// Span shading, the GLSL twin of exposure/span_shading.cpp with exposure/triangle_surface_point:
// the mean colour and alpha of a triangle under one sample, or under a pixel's samples that share
// the shading (ShadingSite), over [t0, t1]. Texture taps sit at exact times along the uv path (a
// ratio of quadratics), as many as the footprint's mip level needs, at most u_textureSamples
// (past which the level rises to length / k); lighting is Simpson's rule, or more taps where the
// normal or view turns.

uniform int u_numSegments;  // linear segments per triangle
uniform int u_textureSamples;
uniform float u_tapsPerTexel;
uniform int u_sweptTexture;  // SpanTextureFilter::Swept: one lookup per straight piece of the uv path
const int kMaxSweptPieces = 8;
const float kMaxTurnPerTap = 0.4;
const int kMaxLightingTaps = 16;

// Where a span is shaded (exposure::ShadingSite): a point, its texture footprint in pixels, and
// for a shading that a pixel's samples share, the point held to its triangle and a box footprint.
struct ShadingSite {
    dvec2 ndc;
    dvec2 footprintPixels;
    bool clampToTriangle;
    bool boxFootprint;
    ivec2 boxTaps;  // a box's fewest taps a side (exposure::boxTapsOf)
    int boxBudget;  // a box's most taps in all (exposure::boxBudgetOf)
};

// exposure::boxTapsOf: the samples a box over footprintPixels spans a side, 1 to 8.
ivec2 boxTapsOf(dvec2 footprintPixels, int samplesPerAxis) {
    return clamp(ivec2(floor(footprintPixels * double(samplesPerAxis) + 0.5)), ivec2(1), ivec2(8));
}

// exposure::boxBudgetOf: a pixel of 2 x 2 samples sharing one box takes a quarter of the budget.
int boxBudgetOf(int samplesPerAxis, int cellsPerAxis) { return cellsPerAxis == 1 && samplesPerAxis == 2 ? kMaxSweptBoxTaps / 4 : kMaxSweptBoxTaps; }

// One sample alone (exposure::sampleSite): one sample spacing.
ShadingSite sampleSite(dvec2 ndc) { return ShadingSite(ndc, dvec2(1.0 / double(u_flags.y)), false, false, ivec2(1), kMaxSweptBoxTaps); }

// A triangle under a site, with the segment last used (taps come in time order).
struct SpanPoint {
    uint triangle;
    dvec2 ndc;
    dvec2 step;  // the footprint in NDC
    bool clampToTriangle, boxFootprint;
    int segment;  // -1: none yet
    MovingTriangle moving;
    vec3 world0[3], world1[3], normal0[3], normal1[3];
    double segmentT0, segmentT1;
    dvec3 cornerWeights[3];  // corner i's edge function: u^2, u, 1 coefficients
    dvec2 uvNumerator[3];    // u^2, u, 1 coefficients
    dvec3 uvDenominator;
};

SpanPoint spanPoint(uint tri, ShadingSite site) {
    SpanPoint p;
    p.triangle = tri;
    p.ndc = site.ndc;
    p.step = dvec2(2.0 * site.footprintPixels.x / double(u_viewport.z), 2.0 * site.footprintPixels.y / double(u_viewport.w));
    p.clampToTriangle = site.clampToTriangle;
    p.boxFootprint = site.boxFootprint;
    p.segment = -1;
    return p;
}

// clampedBarycentrics (scene/barycentric.h): negative weights dropped, the rest renormalised.
dvec3 clampedBarycentrics(dvec3 b) {
    if (b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0) return b;
    dvec3 c = max(b, dvec3(0.0));
    double sum = c.x + c.y + c.z;
    return sum > 0.0 ? c / sum : dvec3(1.0 / 3.0);
}

void selectSegmentAt(inout SpanPoint p, int k);

// The segment that holds t (taps come in time order: mostly the one last used). One exit (see
// shadeTimeSpanAt).
void selectSegment(inout SpanPoint p, float t) {
    int k = clamp(int(t * float(u_numSegments)), 0, u_numSegments - 1);
    if (k != p.segment) selectSegmentAt(p, k);
}

void selectSegmentAt(inout SpanPoint p, int k) {
    p.segment = k;
    float t0 = float(k) / float(u_numSegments), t1 = float(k + 1) / float(u_numSegments);
    p.segmentT0 = double(t0);
    p.segmentT1 = double(t1);
    vec4 open[3], close[3];
    uvec4 tri = triangles[p.triangle];
    for (int i = 0; i < 3; ++i) {
        vertexAt(tri[i], t0, p.world0[i], p.normal0[i]);
        vertexAt(tri[i], t1, p.world1[i], p.normal1[i]);
        open[i] = clipFromWorld(p.world0[i], t0);
        close[i] = clipFromWorld(p.world1[i], t1);
    }
    p.moving = movingTriangle(open, close);
    // Corner i's weight is the edge function of the edge opposite it, edge (i + 1) % 3.
    p.uvDenominator = dvec3(0.0);
    for (int i = 0; i < 3; ++i) {
        dvec3 e = edgeFunction(p.moving, (i + 1) % 3, p.ndc);
        p.cornerWeights[i] = e;
        dvec2 uv = dvec2(vertexUv(tri[i]));
        p.uvNumerator[0] = (i == 0 ? dvec2(0.0) : p.uvNumerator[0]) + e.x * uv;
        p.uvNumerator[1] = (i == 0 ? dvec2(0.0) : p.uvNumerator[1]) + e.y * uv;
        p.uvNumerator[2] = (i == 0 ? dvec2(0.0) : p.uvNumerator[2]) + e.z * uv;
        p.uvDenominator += e;
    }
}

double localTime(SpanPoint p, float t) { return (double(t) - p.segmentT0) / (p.segmentT1 - p.segmentT0); }

bool surfaceAt(inout SpanPoint p, float t, bool withFootprint, out SurfacePoint out_) {
    selectSegment(p, t);
    double u = localTime(p, t);
    HomogeneousSample s, right, down;
    sampleWithNeighbours(p.moving, u, p.ndc, dvec2(p.step.x, 0.0), dvec2(0.0, -p.step.y), s, right, down);
    if (!s.isValid) return false;
    dvec3 baryRight = s.bary, baryDown = s.bary;
    if (withFootprint && right.isValid && down.isValid && right.viewDepth > 0.0 && down.viewDepth > 0.0) {
        baryRight = right.bary;
        baryDown = down.bary;
    }
    if (p.clampToTriangle) {
        // The footprint keeps its shape; it moves with the point.
        dvec3 held = clampedBarycentrics(s.bary);
        baryRight += held - s.bary;
        baryDown += held - s.bary;
        s.bary = held;
    }
    vec3 world[3], normal[3];
    float uf = float(u);
    for (int i = 0; i < 3; ++i) {
        world[i] = mix(p.world0[i], p.world1[i], uf);
        normal[i] = mix(p.normal0[i], p.normal1[i], uf);
    }
    out_ = surfacePoint(p.triangle, world, normal, vec3(s.bary), vec3(baryRight), vec3(baryDown), s.isFrontFacing);
    return true;
}

bool uvAt(inout SpanPoint p, float t, out vec2 uv) {
    // One exit (see shadeTimeSpanAt).
    selectSegment(p, t);
    double u = localTime(p, t);
    double denominator = quadraticAt(p.uvDenominator, u);
    uv = vec2(0.0);
    bool isDefined = !(denominator == 0.0 || isinf(denominator) || isnan(denominator));
    if (isDefined) {
        uv = vec2(((p.uvNumerator[0] * u + p.uvNumerator[1]) * u + p.uvNumerator[2]) / denominator);
        // Held to the triangle (a box's taps are clipped to it instead).
        if (p.clampToTriangle && !p.boxFootprint) {
            dvec3 b = dvec3(quadraticAt(p.cornerWeights[0], u), quadraticAt(p.cornerWeights[1], u), quadraticAt(p.cornerWeights[2], u)) / denominator;
            if (!(b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0)) {
                dvec3 held = clampedBarycentrics(b);
                uvec4 tri = triangles[p.triangle];
                uv = vec2(held.x * dvec2(vertexUv(tri.x)) + held.y * dvec2(vertexUv(tri.y)) + held.z * dvec2(vertexUv(tri.z)));
            }
        }
    }
    return isDefined;
}

float turnBetween(vec3 a, vec3 b) {
    float la = length(a), lb = length(b);
    if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
    return length(a / la - b / lb);
}

// The quadratic through (0, a), (1/2, m), (1, b) at f.
vec3 quadraticThrough(vec3 a, vec3 m, vec3 b, float f) {
    return a + f * ((-3.0 * a + 4.0 * m - b) + f * (2.0 * a - 4.0 * m + 2.0 * b));
}

vec4 shadeTimeSpanAt(uint tri, float t0, float t1, ShadingSite site) {
    SpanPoint point = spanPoint(tri, site);
    float times[3] = g_window.isIdentity ? float[3](t0, 0.5 * (t0 + t1), t1)
                                         : float[3](timeBetween(g_window, t0, t1, 0.0), timeBetween(g_window, t0, t1, 0.5),
                                                    timeBetween(g_window, t0, t1, 1.0));
    SurfacePoint ends[3];
    for (int i = 0; i < 3; ++i)
        if (!surfaceAt(point, times[i], true, ends[i])) return vec4(0.0);
    uint m = ends[1].material;
    bool lit = isLit();
    // The normal pass: the span's mean normal (Simpson's weights), with the unlit path's alpha.
    vec3 meanNormal = (shadingNormal(ends[0].normal, ends[0].isFrontFacing) + 4.0 * shadingNormal(ends[1].normal, ends[1].isFrontFacing) +
                       shadingNormal(ends[2].normal, ends[2].isFrontFacing)) / 6.0;

    // Lighting: Simpson's three points, or n midpoint taps where the surface turns.
    int lightingTaps = 0;
    PhongTerms simpson[3];
    PhongTerms taps[kMaxLightingTaps];
    vec3 meanDiffuse = vec3(0.0), meanSpecular = vec3(0.0);
    if (lit) {
        float normalTurn = max(turnBetween(ends[0].normal, ends[1].normal), turnBetween(ends[1].normal, ends[2].normal));
        vec3 e0 = eyeAt(times[0]) - ends[0].position, e1 = eyeAt(times[1]) - ends[1].position, e2 = eyeAt(times[2]) - ends[2].position;
        float viewTurn = max(turnBetween(e0, e1), turnBetween(e1, e2));
        lightingTaps = clamp(int(ceil(2.0 * (2.0 * normalTurn + viewTurn) / kMaxTurnPerTap)), 1, kMaxLightingTaps);
        if (lightingTaps <= 3) {
            for (int i = 0; i < 3; ++i) simpson[i] = phongTerms(m, ends[i].position, ends[i].normal, ends[i].isFrontFacing, eyeAt(times[i]));
            meanDiffuse = (simpson[0].diffuse + 4.0 * simpson[1].diffuse + simpson[2].diffuse) / 6.0;
            meanSpecular = (simpson[0].specular + 4.0 * simpson[1].specular + simpson[2].specular) / 6.0;
        } else {
            int used = 0;
            for (int i = 0; i < lightingTaps; ++i) {
                float t = timeBetween(g_window, t0, t1, (float(i) + 0.5) / float(lightingTaps));
                SurfacePoint sp;
                if (surfaceAt(point, t, false, sp)) taps[used++] = phongTerms(m, sp.position, sp.normal, sp.isFrontFacing, eyeAt(t));
                else if (used > 0) taps[used] = taps[used - 1], ++used;
            }
            if (used == 0) taps[used++] = phongTerms(m, ends[1].position, ends[1].normal, ends[1].isFrontFacing, eyeAt(times[1]));
            lightingTaps = used;
            for (int i = 0; i < used; ++i) meanDiffuse += taps[i].diffuse, meanSpecular += taps[i].specular;
            meanDiffuse /= float(used);
            meanSpecular /= float(used);
        }
    }

    vec4 vertexColor = ends[1].vertexColor;
    MaterialData mat = materials[m];
    if (mat.info.x < 0) {
        vec4 albedo = materialAlbedo(m, ends[1].uv, vec2(0.0), vec2(0.0), vertexColor);
        if (isNormalPass()) return vec4(meanNormal, albedo.a);
        if (!lit) return albedo;
        return vec4(albedo.rgb * meanDiffuse + meanSpecular, albedo.a);
    }

    int tex = mat.info.x;
    vec2 size = textureSizeOf(tex);
    float footprintLod[3];
    for (int i = 0; i < 3; ++i) footprintLod[i] = finestLodOfFootprint(tex, ends[i].duvdx, ends[i].duvdy);
    vec2 a = abs(ends[1].uv - ends[0].uv) * size, b = abs(ends[2].uv - ends[1].uv) * size;
    float pathTexels = max(a.x + b.x, a.y + b.y);
    float spacing = exp2(max(0.0, min(footprintLod[0], min(footprintLod[1], footprintLod[2]))));
    int numTaps = clamp(int(ceil(u_tapsPerTexel * pathTexels / spacing)), 1, u_textureSamples);
    float pathLod = log2(max(pathTexels / float(u_textureSamples), 1e-8));

    // Swept: the path cut where it bends (its middle off the chord by more than a quarter tap
    // width, a quarter of that per halving), one lookup of the footprint swept along each piece.
    int pieces = 1;
    bool isBox = site.boxFootprint;
    bool swept = u_sweptTexture != 0 && mat.info.y != 1 && !isBox;  // a mask keeps the taps
    if (swept) {
        float bend = length((ends[1].uv - 0.5 * (ends[0].uv + ends[2].uv)) * size);
        while (pieces < kMaxSweptPieces && bend > 0.25 * spacing * float(pieces * pieces)) pieces *= 2;
        numTaps = pieces;
    }
    // A box takes one grid for the whole span (Texture::boxGrid): the box's level and taps at the
    // widest it is at the span's ends and middle, and the times along the path.
    ivec4 grid = ivec4(0, 1, 1, 1);
    if (isBox) {
        float lengthX = 0.0, lengthY = 0.0;
        for (int i = 0; i < 3; ++i) {
            lengthX = max(lengthX, length(ends[i].duvdx * size));
            lengthY = max(lengthY, length(ends[i].duvdy * size));
        }
        grid = boxGrid(tex, lengthX, lengthY, pathTexels, u_tapsPerTexel, u_textureSamples, site.boxTaps, site.boxBudget);
        numTaps = grid.w;
    }
    vec2 from = ends[0].uv;
    bool hasFrom = true;

    vec3 sum = vec3(0.0), specularSum = vec3(0.0);
    float alphaSum = 0.0, weightSum = 0.0;
    // A shared shading's box counts only the texels of its triangle, and each time as much as the
    // triangle then covers of the box (at least kLeastCoverage, so a span keeps some weight).
    bool isClipped = isBox && site.clampToTriangle;
    uvec4 corners = triangles[tri];
    vec2 clip[3] = vec2[3](vertexUv(corners.x), vertexUv(corners.y), vertexUv(corners.z));
    const float kLeastCoverage = 1e-3;
    for (int i = 0; i < numTaps; ++i) {
        float f = (float(i) + 0.5) / float(numTaps);
        vec2 uv = ends[1].uv;
        vec2 sweep = vec2(0.0);
        bool hasTap = true;
        if (swept) {
            vec2 to = ends[2].uv;
            bool hasTo = true;
            if (2 * (i + 1) == pieces) to = ends[1].uv;
            else if (i + 1 < pieces) hasTo = uvAt(point, timeBetween(g_window, t0, t1, float(i + 1) / float(pieces)), to);
            hasTap = hasFrom && hasTo;
            uv = 0.5 * (from + to);
            sweep = to - from;
            from = to;
            hasFrom = hasTo;
        } else if (isBox || 2 * i + 1 != numTaps) {
            hasTap = uvAt(point, timeBetween(g_window, t0, t1, f), uv);
        }
        if (!hasTap) continue;
        vec2 duvdx = quadraticThrough(vec3(ends[0].duvdx, 0.0), vec3(ends[1].duvdx, 0.0), vec3(ends[2].duvdx, 0.0), f).xy;
        vec2 duvdy = quadraticThrough(vec3(ends[0].duvdy, 0.0), vec3(ends[1].duvdy, 0.0), vec3(ends[2].duvdy, 0.0), f).xy;
        float weight = 1.0;
        vec4 texel = swept   ? sampleSweptFootprint(tex, uv, duvdx, duvdy, sweep, 0.0, max(16, u_textureSamples), u_tapsPerTexel)
                     : isBox ? sampleBox(tex, uv, duvdx, duvdy, grid, isClipped, clip, weight)
                             : sampleFootprint(tex, uv, duvdx, duvdy, pathLod);
        weight = max(weight, kLeastCoverage);
        if (lit) {
            vec3 diffuse, specular;
            if (lightingTaps <= 3) {
                diffuse = quadraticThrough(simpson[0].diffuse, simpson[1].diffuse, simpson[2].diffuse, f);
                specular = quadraticThrough(simpson[0].specular, simpson[1].specular, simpson[2].specular, f);
            } else {
                float x = clamp(f * float(lightingTaps) - 0.5, 0.0, float(lightingTaps - 1));
                int j = min(int(x), lightingTaps - 1), k = min(j + 1, lightingTaps - 1);
                float w = x - float(j);
                diffuse = mix(taps[j].diffuse, taps[k].diffuse, w);
                specular = mix(taps[j].specular, taps[k].specular, w);
            }
            sum += texel.rgb * diffuse * weight;
            specularSum += specular * weight;
        } else {
            sum += texel.rgb * weight;
        }
        alphaSum += alphaOf(m, texel.a * vertexColor.a) * weight;
        weightSum += weight;
    }
    if (weightSum == 0.0) return vec4(0.0);
    float scale = 1.0 / weightSum;
    if (isNormalPass()) return vec4(meanNormal, alphaSum * scale);
    return vec4(mat.baseColorOpacity.rgb * vertexColor.rgb * sum * scale + specularSum * scale, alphaSum * scale);
}

// One sample's span, at the sample with a footprint of one sample spacing.
vec4 shadeTimeSpan(uint tri, float t0, float t1, dvec2 ndc) { return shadeTimeSpanAt(tri, t0, t1, sampleSite(ndc)); }
