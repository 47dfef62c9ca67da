// motion-path-gl pass 2, one invocation per sample: gathers the sample's intervals (the nearest
// MAX_INTERVALS on overflow), shades the translucent ones (their alpha decides what shows
// behind them), sorts in depth-time (split crossings, then Hong & Oh's four tests), resolves
// with u_maskBits-bit masks of the row's exposure (per-slice transmittance when translucent), and shades only
// the visible opaque pieces, wholly visible pieces of one triangle that abut merged first.
layout(local_size_x = 8, local_size_y = 8) in;

uniform int u_maskBits;
uniform int u_sortIntervals;

struct PathNode {
    uint segment;
    uint next;
    float t0, t1;
    float depth0, depth1;
};
layout(std430, binding = 7) readonly buffer NodeBuffer { PathNode nodes[]; };
layout(rgba32f, binding = 2) uniform writeonly image2D u_output;

layout(std430, binding = 9) buffer ResolveCounterBuffer {
    uint intervalOverflowSamples;
    uint splits;
    uint cycles;
    uint shadedSpans;
    uint intervalCount;
    uint maxIntervalCount;
};

Interval intervals[MAX_INTERVALS];
float weights[MAX_INTERVALS];

float resolveOpaque(int n) {
    uint accumulated[kMaskWords], current[kMaskWords];
    for (int w = 0; w < kMaskWords; ++w) accumulated[w] = 0u;
    int covered = 0;
    for (int i = 0; i < n; ++i) {
        weights[i] = 0.0;
        if (covered == u_maskBits) continue;
        exposedMask(intervals[i].t0, intervals[i].t1, u_maskBits, current);
        int visible = 0;
        for (int w = 0; w < kMaskWords; ++w) {
            visible += bitCount(current[w] & ~accumulated[w]);
            accumulated[w] |= current[w];
        }
        covered += visible;
        weights[i] = float(visible) / float(u_maskBits);
    }
    return float(u_maskBits - covered) / float(u_maskBits);
}

float resolveTranslucent(int n) {
    float transmittance[256];
    for (int b = 0; b < u_maskBits; ++b) transmittance[b] = 1.0;
    uint opaque[kMaskWords], open[kMaskWords];
    for (int w = 0; w < kMaskWords; ++w) opaque[w] = 0u;
    for (int i = 0; i < n; ++i) {
        weights[i] = 0.0;
        exposedMask(intervals[i].t0, intervals[i].t1, u_maskBits, open);
        float alpha = intervals[i].color.a, sum = 0.0;
        for (int w = 0; w < kMaskWords; ++w) {
            uint bits = open[w] & ~opaque[w];
            while (bits != 0u) {
                int b = findLSB(bits);
                bits &= bits - 1u;
                int slice = w * 32 + b;
                sum += transmittance[slice];
                transmittance[slice] *= 1.0 - alpha;
                if (transmittance[slice] <= 0.0) opaque[w] |= 1u << uint(b);
            }
        }
        weights[i] = alpha * sum / float(u_maskBits);
    }
    float remaining = 0.0;
    for (int b = 0; b < u_maskBits; ++b) remaining += transmittance[b];
    return remaining / float(u_maskBits);
}

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (s.x >= u_viewport.x || s.y >= u_viewport.y) return;
    dvec2 ndc = sampleNdc(s);
    g_window = rowWindow(s.y / u_flags.y);  // masks and span taps in the row's exposure

    // Gather, keeping the nearest MAX_INTERVALS, sorted by minimum depth.
    int n = 0;
    bool isOverflowing = false;
    uint node = imageLoad(u_heads, s).x;
    for (uint guard = 0u; node != kEndOfList && node < u_listCapacity && guard < u_sampleBudget; ++guard) {
        PathNode f = nodes[node];
        node = f.next;
        Interval interval = Interval(f.t0, f.t1, f.depth0, f.depth1, f.segment, vec4(0.0, 0.0, 0.0, 1.0));
        if (n == MAX_INTERVALS) {
            isOverflowing = true;
            if (minDepth(interval) >= minDepth(intervals[n - 1])) continue;
            --n;
        }
        // Swapped down into place, both neighbours read before either is written: llvmpipe
        // miscompiles the textbook shifting insertion (elements come out duplicated or zero).
        intervals[n] = interval;
        for (int i = n++; i > 0; --i) {
            Interval a = intervals[i - 1], b = intervals[i];
            if (!(minDepth(a) > minDepth(b))) break;
            intervals[i - 1] = b;
            intervals[i] = a;
        }
    }
    if (isOverflowing) atomicAdd(intervalOverflowSamples, 1u);
    if (n == 0) {
        imageStore(u_output, s, vec4(u_background.rgb, 1.0));
        return;
    }
    atomicAdd(intervalCount, uint(n));
    atomicMax(maxIntervalCount, uint(n));

    bool isTranslucent = false;
    for (int i = 0; i < n; ++i) {
        uint tri = intervals[i].segment / uint(u_numSegments);
        if (isTranslucentMaterial(triangles[tri].w & kMaterialMask)) {
            intervals[i].color = shadeTimeSpan(tri, intervals[i].t0, intervals[i].t1, ndc);
            isTranslucent = isTranslucent || intervals[i].color.a < 1.0;
        }
    }

    if (u_sortIntervals != 0 && n > 1) {
        // Split every crossing pair (the list grows by two per split, up to the budget).
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                Interval a = intervals[i], b = intervals[j], aTail, bTail;
                if (!splitAtCrossing(a, b, aTail, bTail)) continue;
                if (n + 2 > MAX_INTERVALS) {
                    isOverflowing = true;
                    continue;
                }
                intervals[i] = a;
                intervals[j] = b;
                intervals[n++] = aTail;
                intervals[n++] = bTail;
                atomicAdd(splits, 1u);
            }
        // Selection sort: place first the interval every other remaining one lets stay in front.
        for (int i = 0; i + 1 < n; ++i) {
            int front = i;
            bool found = false;
            for (int c = i; c < n && !found; ++c) {
                found = true;
                for (int k = i; k < n && found; ++k)
                    if (k != c && !canStayBefore(intervals[c], intervals[k])) found = false;
                if (found) front = c;
            }
            if (!found) atomicAdd(cycles, 1u);
            if (front != i) {
                Interval a = intervals[i], b = intervals[front];
                intervals[i] = b;
                intervals[front] = a;
            }
        }
    }

    float background = isTranslucent ? resolveTranslucent(n) : resolveOpaque(n);
    vec3 sum = u_background.rgb * background;

    // Visible opaque pieces, by triangle then time, so abutting whole pieces merge.
    for (int i = 0; i < n; ++i) {
        if (weights[i] <= 0.0) continue;
        uint tri = intervals[i].segment / uint(u_numSegments);
        if (isTranslucentMaterial(triangles[tri].w & kMaterialMask)) {
            sum += intervals[i].color.rgb * weights[i];
            weights[i] = 0.0;
            continue;
        }
        // Whole: visible all through its span; the weight then records the mask count.
        uint mask[kMaskWords];
        exposedMask(intervals[i].t0, intervals[i].t1, u_maskBits, mask);
        int bits = 0;
        for (int w = 0; w < kMaskWords; ++w) bits += bitCount(mask[w]);
        intervals[i].color.a = weights[i] * float(u_maskBits) >= float(bits) - 0.5 ? 1.0 : 0.0;
        intervals[i].segment = tri;  // from here on: the triangle
    }
    // Pieces left with weight > 0 are opaque; sort them by (triangle, t0).
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (weights[i] > 0.0) {
            intervals[m] = intervals[i];
            weights[m] = weights[i];
            ++m;
        }
    // Insertion sort in the same form as the gather's.
    for (int i = 1; i < m; ++i)
        for (int j = i; j > 0; --j) {
            Interval a = intervals[j - 1], b = intervals[j];
            if (!(b.segment < a.segment || (b.segment == a.segment && b.t0 < a.t0))) break;
            float wa = weights[j - 1], wb = weights[j];
            intervals[j - 1] = b;
            intervals[j] = a;
            weights[j - 1] = wb;
            weights[j] = wa;
        }
    int shaded = 0;
    for (int i = 0; i < m;) {
        float t0 = intervals[i].t0, t1 = intervals[i].t1, weight = weights[i];
        uint tri = intervals[i].segment;
        bool isWhole = intervals[i].color.a > 0.5;
        int j = i + 1;
        for (; j < m && isWhole && intervals[j].color.a > 0.5 && intervals[j].segment == tri && intervals[j].t0 == t1; ++j) {
            t1 = intervals[j].t1;
            weight += weights[j];
        }
        sum += shadeTimeSpan(tri, t0, t1, ndc).rgb * weight;
        ++shaded;
        i = j;
    }
    atomicAdd(shadedSpans, uint(shaded));
    imageStore(u_output, s, vec4(sum, 1.0));
}
