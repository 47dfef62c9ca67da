// motion-path-gl pass 2, one invocation per sample: gathers the sample's intervals (the nearest
// MAX_INTERVALS on overflow), shades the translucent ones (their alpha decides what shows
// behind them), sorts in depth-time (split crossings, then Hong & Oh's four tests), resolves
// opaque lists exactly in time as motion-path does (methods/motion_path/resolve.cpp: each
// interval's visible share and the spans where it shows), or with u_maskBits-bit masks of the
// row's exposure (u_exactWeights 0, the paper's; per-slice transmittance when translucent),
// and shades only the visible opaque pieces, wholly visible pieces of one triangle that abut
// merged first (exposure/visible_pieces.cpp). With u_writeSurfaces it also writes, per sample,
// what shows there for the passes (exposure::PixelPasses on the CPU): each surface's triangle,
// share, depths and the colour it adds. With u_shadingPerPixel it leaves the opaque pieces
// unshaded: it writes them to the piece pool for the pixel pass (motion_path_gl_pixel_shading),
// which shades a pixel's samples together; a sample the pool cannot hold shades its own.
layout(local_size_x = 8, local_size_y = 8) in;

uniform int u_maskBits;
uniform int u_sortIntervals;
uniform int u_exactWeights;
uniform int u_writeSurfaces;
uniform int u_shadingPerPixel;
uniform uint u_pieceCapacity;

// A visible opaque piece of a sample, for the pixel pass; each sample's in one run of the pool.
struct PieceNode {
    uint triangle;
    float t0, t1, weight;
};
layout(std430, binding = 11) writeonly buffer PieceBuffer { PieceNode pieceNodes[]; };
layout(std430, binding = 12) writeonly buffer SamplePieceBuffer { uvec2 samplePieces[]; };  // first, count (cleared to 0)

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
    uint shownOverflowSamples;
    uint piecesWritten;          // asked of the pool, past its capacity too
    uint pieceOverflowSamples;   // samples that shaded their own pieces, the pool being full
};

// What shows in each sample, MAX_SHOWN records a sample (the buffer comes cleared to all ones:
// triangle 0xffffffff is no record): a triangle, its share of the sample, its mean depth over
// the time it shows and the nearest and farthest, and the colour it adds (its colour times its
// share). A sample's pieces of one triangle are one record; past MAX_SHOWN (a sample swept by
// many small triangles) a triangle joins the record of its mesh nearest to it in depth, and a
// triangle of a mesh with no record frees one by joining the two records of one mesh nearest
// each other in depth. So each object's share, depth and colour stay whole; only a sample
// showing more than MAX_SHOWN meshes loses some (counted).
struct ShownRecord {
    uint triangle;
    float share, depth, nearest, farthest;
    float r, g, b;
};
layout(std430, binding = 10) writeonly buffer ShownBuffer { ShownRecord shownRecords[]; };
ShownRecord shown[MAX_SHOWN];
int numShown = 0;
bool isShownOverflowing = false;

// Adds a surface to record k (depths: the mean, the nearest and the farthest).
void joinShown(int k, float share, vec3 depths, vec3 color) {
    float total = shown[k].share + share;
    shown[k].depth = (shown[k].depth * shown[k].share + depths.x * share) / total;
    shown[k].share = total;
    shown[k].nearest = min(shown[k].nearest, depths.y);
    shown[k].farthest = max(shown[k].farthest, depths.z);
    shown[k].r += color.r;
    shown[k].g += color.g;
    shown[k].b += color.b;
}

uint meshOfTriangle(uint tri) { return vertexInfo[triangles[tri].x].x; }

void showSurface(uint tri, float share, vec3 depths, vec3 color) {
    if (u_writeSurfaces == 0 || !(share > 0.0)) return;
    for (int k = 0; k < numShown; ++k) {
        if (shown[k].triangle == tri) {
            joinShown(k, share, depths, color);
            return;
        }
    }
    if (numShown < MAX_SHOWN) {
        shown[numShown++] = ShownRecord(tri, share, depths.x, depths.y, depths.z, color.r, color.g, color.b);
        return;
    }
    uint mesh = meshOfTriangle(tri);
    int nearest = -1;
    float gap = 0.0;
    for (int k = 0; k < numShown; ++k) {
        if (meshOfTriangle(shown[k].triangle) != mesh) continue;
        float g = max(0.0, max(shown[k].nearest - depths.z, depths.y - shown[k].farthest));
        if (nearest < 0 || g < gap) {
            nearest = k;
            gap = g;
        }
    }
    if (nearest >= 0) {
        joinShown(nearest, share, depths, color);
        return;
    }
    // No record of its mesh: free one, joining the two of one mesh nearest each other.
    int a = -1, b = -1;
    for (int i = 0; i < numShown; ++i)
        for (int j = i + 1; j < numShown; ++j) {
            if (meshOfTriangle(shown[i].triangle) != meshOfTriangle(shown[j].triangle)) continue;
            float g = max(0.0, max(shown[i].nearest - shown[j].farthest, shown[j].nearest - shown[i].farthest));
            if (a < 0 || g < gap) {
                a = i;
                b = j;
                gap = g;
            }
        }
    if (a < 0) {
        isShownOverflowing = true;
        return;
    }
    joinShown(a, shown[b].share, vec3(shown[b].depth, shown[b].nearest, shown[b].farthest), vec3(shown[b].r, shown[b].g, shown[b].b));
    shown[b] = ShownRecord(tri, share, depths.x, depths.y, depths.z, color.r, color.g, color.b);
}

// An interval's depths over [t0, t1]: at the middle (linear), the nearer end and the farther.
vec3 depthsOver(Interval interval, float t0, float t1) {
    float d0 = depthAt(interval, t0), d1 = depthAt(interval, t1);
    return vec3(depthAt(interval, 0.5 * (t0 + t1)), min(d0, d1), max(d0, d1));
}

Interval intervals[MAX_INTERVALS];
float weights[MAX_INTERVALS];

// The opaque pieces to shade (exposure::VisiblePiece): a triangle, a time span, its share of
// the sample, and whether it is visible all through the span (then it may merge with an
// abutting whole piece of its triangle). An interval meeting k spans of the union before it
// shows in at most k + 1 gaps and leaves the union k - 1 spans shorter, so n intervals show in
// at most 2n pieces: the array cannot overflow (addPiece's guard keeps it so).
const int kMaxPieces = 2 * MAX_INTERVALS;
uint pieceTriangles[kMaxPieces];
vec4 pieces[kMaxPieces];  // t0, t1, weight, 1 when whole
vec3 pieceDepths[kMaxPieces];  // for the passes: depthsOver the piece
int numPieces = 0;

float measure(float t0, float t1) { return g_window.isIdentity ? t1 - t0 : exposureAt(g_window, t1) - exposureAt(g_window, t0); }

// A piece of interval i.
void addPiece(int i, uint tri, float t0, float t1, float weight, bool isWhole) {
    if (numPieces == kMaxPieces) return;
    pieceTriangles[numPieces] = tri;
    pieceDepths[numPieces] = u_writeSurfaces != 0 ? depthsOver(intervals[i], t0, t1) : vec3(0.0);
    pieces[numPieces++] = vec4(t0, t1, weight, isWhole ? 1.0 : 0.0);
}

// Opaque intervals in depth-time order, measured exactly in the row's exposure: the union of the
// spans so far (disjoint, in time order) hides part of each; the rest is its weight, and each gap
// the union leaves in it is a visible piece (resolveOpaqueExact). Returns the background's share.
// Translucent materials' intervals (of alpha 1 here) take no pieces: they were shaded when gathered.
float resolveOpaqueExact(int n) {
    vec2 covered[MAX_INTERVALS], next[MAX_INTERVALS];
    int numCovered = 0;
    float coveredLength = 0.0;
    for (int i = 0; i < n; ++i) weights[i] = 0.0;
    for (int i = 0; i < n && coveredLength < 1.0; ++i) {
        float t0 = clamp(intervals[i].t0, 0.0, 1.0), t1 = clamp(intervals[i].t1, 0.0, 1.0);
        if (!(t1 > t0)) continue;
        uint tri = intervals[i].segment / uint(u_numSegments);
        bool isShaded = isTranslucentMaterial(triangles[tri].w & kMaterialMask);
        float hidden = 0.0, lo = t0, hi = t1, shownFrom = t0;
        for (int c = 0; c < numCovered; ++c) {
            if (!(covered[c].y > t0) || !(covered[c].x < t1)) continue;
            hidden += measure(max(covered[c].x, t0), min(covered[c].y, t1));
            lo = min(lo, covered[c].x);
            hi = max(hi, covered[c].y);
            float shown = shownFrom < covered[c].x && !isShaded ? measure(shownFrom, covered[c].x) : 0.0;
            if (shown > 0.0) addPiece(i, tri, shownFrom, covered[c].x, shown, true);
            shownFrom = max(shownFrom, covered[c].y);
        }
        float shown = shownFrom < t1 && !isShaded ? measure(shownFrom, t1) : 0.0;
        if (shown > 0.0) addPiece(i, tri, shownFrom, t1, shown, true);
        float visible = max(0.0, measure(t0, t1) - hidden);
        weights[i] = visible;
        coveredLength += visible;
        // The union again: the spans before, the merged one, the spans after.
        int m = 0;
        bool isPlaced = false;
        for (int c = 0; c < numCovered; ++c) {
            if (covered[c].y > t0 && covered[c].x < t1) continue;
            if (!isPlaced && covered[c].x >= t1) {
                next[m++] = vec2(lo, hi);
                isPlaced = true;
            }
            next[m++] = covered[c];
        }
        if (!isPlaced) next[m++] = vec2(lo, hi);
        for (int c = 0; c < m; ++c) covered[c] = next[c];
        numCovered = m;
    }
    return max(0.0, 1.0 - coveredLength);
}

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

// With u_sortIntervals, splits every crossing pair of the sample's n intervals and orders them
// in depth-time order.
void orderIntervals(inout int n) {
    if (u_sortIntervals != 0 && n > 1) {
        // Split every crossing pair (the list grows by two per split, up to the budget).
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                Interval a = intervals[i], b = intervals[j], aTail, bTail;
                if (!splitAtCrossing(a, b, aTail, bTail)) continue;
                if (n + 2 > MAX_INTERVALS) continue;  // past the budget the pair stays unsplit
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
}

// Resolves the sample's n ordered intervals (the translucent ones shaded): the background's
// share, the background and the translucent intervals' colour in sum, and the visible opaque
// spans left in pieces[0, spans), which it returns.
int visibleSpans(int n, bool isTranslucent, out float background, out vec3 sum) {
    // Opaque lists measured exactly give their visible pieces from the resolve.
    bool isExact = !isTranslucent && u_exactWeights != 0;
    background = isExact ? resolveOpaqueExact(n) : isTranslucent ? resolveTranslucent(n) : resolveOpaque(n);
    sum = u_background.rgb * background;
    // Translucent materials' intervals were shaded when gathered; the other intervals are pieces,
    // whole where visible all through their span: with exact weights when their weight is the
    // span's exposure, with masks when it holds every slice of it.
    for (int i = 0; i < n; ++i) {
        if (weights[i] <= 0.0) continue;
        uint tri = intervals[i].segment / uint(u_numSegments);
        if (isTranslucentMaterial(triangles[tri].w & kMaterialMask)) {
            sum += intervals[i].color.rgb * weights[i];
            showSurface(tri, weights[i], depthsOver(intervals[i], intervals[i].t0, intervals[i].t1), intervals[i].color.rgb * weights[i]);
            continue;
        }
        if (isExact) continue;
        bool isWhole;
        if (u_exactWeights != 0) {
            isWhole = weights[i] >= measure(intervals[i].t0, intervals[i].t1) * (1.0 - 1e-5);
        } else {
            uint mask[kMaskWords];
            exposedMask(intervals[i].t0, intervals[i].t1, u_maskBits, mask);
            int bits = 0;
            for (int w = 0; w < kMaskWords; ++w) bits += bitCount(mask[w]);
            isWhole = weights[i] * float(u_maskBits) >= float(bits) - 0.5;
        }
        addPiece(i, tri, intervals[i].t0, intervals[i].t1, weights[i], isWhole);
    }

    // The pieces by (triangle, t0), swapped down into place as in the gather.
    for (int i = 1; i < numPieces; ++i)
        for (int j = i; j > 0; --j) {
            uint ta = pieceTriangles[j - 1], tb = pieceTriangles[j];
            vec4 a = pieces[j - 1], b = pieces[j];
            vec3 da = pieceDepths[j - 1], db = pieceDepths[j];
            if (!(tb < ta || (tb == ta && b.x < a.x))) break;
            pieceTriangles[j - 1] = tb;
            pieceTriangles[j] = ta;
            pieces[j - 1] = b;
            pieces[j] = a;
            pieceDepths[j - 1] = db;
            pieceDepths[j] = da;
        }
    // Abutting whole pieces of one triangle are one span, kept in place (the first `spans`
    // pieces, with their mean depths).
    int spans = 0;
    for (int i = 0; i < numPieces;) {
        uint tri = pieceTriangles[i];
        float t0 = pieces[i].x, t1 = pieces[i].y, weight = pieces[i].z;
        vec3 depths = vec3(pieceDepths[i].x * weight, pieceDepths[i].yz);
        bool isWhole = pieces[i].w > 0.5;
        int j = i + 1;
        for (; j < numPieces && isWhole && pieces[j].w > 0.5 && pieceTriangles[j] == tri && pieces[j].x == t1; ++j) {
            t1 = pieces[j].y;
            weight += pieces[j].z;
            depths = vec3(depths.x + pieceDepths[j].x * pieces[j].z, min(depths.y, pieceDepths[j].y), max(depths.z, pieceDepths[j].z));
        }
        pieceTriangles[spans] = tri;
        pieceDepths[spans] = vec3(depths.x / weight, depths.yz);
        pieces[spans++] = vec4(t0, t1, weight, 1.0);
        i = j;
    }
    return spans;
}

// At shading=pixel, hands the sample's spans to the pixel pass through the piece pool; false
// where it does not (the pool full, or shading=sample): the sample shades its own.
bool poolSpans(ivec2 s, int spans) {
    bool isPooled = false;
    if (u_shadingPerPixel != 0 && spans > 0) {
        uint first = atomicAdd(piecesWritten, uint(spans));
        isPooled = first + uint(spans) <= u_pieceCapacity;
        if (isPooled) {
            for (int k = 0; k < spans; ++k) pieceNodes[first + uint(k)] = PieceNode(pieceTriangles[k], pieces[k].x, pieces[k].y, pieces[k].z);
            samplePieces[uint(s.y) * uint(u_viewport.x) + uint(s.x)] = uvec2(first, uint(spans));
        } else {
            // The pool is full: this sample shades its own, as --option shading=sample does.
            atomicAdd(pieceOverflowSamples, 1u);
        }
    }
    return isPooled;
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
        imageStore(u_output, s, vec4(u_background.rgb, 0.0));  // alpha: coverage
        return;
    }
    atomicAdd(intervalCount, uint(n));
    atomicMax(maxIntervalCount, uint(n));

    // Shading in two rounds from one call of shadeTimeSpan (Mesa inlines every call, and a second
    // one doubled this pass's build on llvmpipe, 11 -> 21 s): the translucent intervals, whose
    // alpha the resolve needs, then the visible opaque spans it leaves, unless the pixel pass
    // shades them (which adds their colour to the passes' records).
    bool isTranslucent = false, isPooled = false;
    float background = 0.0;
    vec3 sum = vec3(0.0);
    int spans = 0, shaded = 0;
    for (int round = 0; round < 2; ++round) {
        for (int k = 0; k < (round == 0 ? n : spans); ++k) {
            // (Each round reads only its own arrays: spans may pass MAX_INTERVALS.)
            uint tri;
            vec2 span;
            bool isShaded;
            if (round == 0) {
                tri = intervals[k].segment / uint(u_numSegments);
                span = vec2(intervals[k].t0, intervals[k].t1);
                isShaded = isTranslucentMaterial(triangles[tri].w & kMaterialMask);
            } else {
                tri = pieceTriangles[k];
                span = pieces[k].xy;
                isShaded = !isPooled;
            }
            vec4 color = vec4(0.0);
            if (isShaded) color = shadeTimeSpan(tri, span.x, span.y, ndc);
            if (round == 0) {
                if (isShaded) {
                    intervals[k].color = color;
                    isTranslucent = isTranslucent || color.a < 1.0;
                }
            } else {
                vec3 added = color.rgb * pieces[k].z;
                sum += added;
                shaded += isShaded ? 1 : 0;
                showSurface(tri, pieces[k].z, pieceDepths[k], added);
            }
        }
        if (round == 0) {
            orderIntervals(n);
            spans = visibleSpans(n, isTranslucent, background, sum);
            isPooled = poolSpans(s, spans);
        }
    }
    atomicAdd(shadedSpans, uint(shaded));
    imageStore(u_output, s, vec4(sum, 1.0 - background));
    if (u_writeSurfaces != 0) {
        uint first = (uint(s.y) * uint(u_viewport.x) + uint(s.x)) * uint(MAX_SHOWN);
        for (int k = 0; k < numShown; ++k) shownRecords[first + uint(k)] = shown[k];
        if (isShownOverflowing) atomicAdd(shownOverflowSamples, 1u);
    }
}
