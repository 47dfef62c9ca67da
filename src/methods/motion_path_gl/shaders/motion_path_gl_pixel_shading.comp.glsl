// motion-path-gl pass 3 at --option shading=pixel, one invocation per pixel: the GLSL twin of
// exposure::PixelShading. The resolve left each sample's visible opaque pieces (abutting ones of
// a triangle merged) in the piece pool; here the pieces of a pixel's samples are sorted by
// (triangle, shading cell, start) and cut into time clusters: a piece joins the cluster before it
// when they overlap by at least half the shorter of the two (kShareOverlap). Each cluster is
// shaded once, over its hull, held to its triangle, with a box footprint as wide as its samples
// spread, and each of its pieces adds that colour times its own weight to its sample. Untextured
// triangles take one cell a pixel, textured ones u_shadingCells a side. A cluster of one piece,
// where a cell holds one sample, shades as that sample alone would. A textured triangle still
// all the shutter under a still camera (kStillBit) takes one cluster a pixel, all its pieces
// whatever their times, whose colour is the mean of its pieces' samples' own shadings weighted
// by their exposures (the CPU's Sharing::StillTextured, which lights each at its sample with one
// sample's footprint). An untextured triangle of one colour in an unlit render also takes one
// cluster a pixel (Sharing::OneColour). Past u_maxPixelPieces a
// pixel's further pieces are shaded each at its sample (counted), each as a cluster of its own
// numbered after the pixel's clusters.
//
// One dispatch shades clusters [u_firstCluster, u_firstCluster + u_clusterCount) of each pixel,
// and the host dispatches again while a pixel has more (maxClusters): llvmpipe ends every loop
// of an invocation once all its loops together have run 65,535 iterations (gallivm's
// LP_MAX_TGSI_LOOP_ITERATIONS), and a box shading alone can take a few thousand, so a pixel's
// clusters are shaded a few per dispatch. (The pieces past u_maxPixelPieces were all shaded in
// the first dispatch: on builtin:pan at --aa 6 that ended the loops of whole workgroups, whose
// invocations run in the same SIMD lanes and share the count, and left 121 pixels unshaded.)
layout(local_size_x = 8, local_size_y = 8) in;

uniform int u_firstCluster;
uniform int u_clusterCount;
uniform int u_shadingCells;  // cells a side, at most --aa
uniform int u_boxFilter;     // shading-filter=box: the box at the samples' bounds; lookup: at their centroid
uniform int u_writeSurfaces;
// The pieces a pixel sorts and clusters, at most MAX_PIXEL_PIECES (the arrays' size, the same for
// a range of --aa, so that one build of this pass serves them).
uniform int u_maxPixelPieces;

struct PieceNode {
    uint triangle;
    float t0, t1, weight;
};
layout(std430, binding = 11) readonly buffer PieceBuffer { PieceNode pieceNodes[]; };
layout(std430, binding = 12) readonly buffer SamplePieceBuffer { uvec2 samplePieces[]; };  // first, count
layout(rgba32f, binding = 2) uniform image2D u_output;

layout(std430, binding = 13) buffer PixelShadingCounterBuffer {
    uint pixelsShaded;       // pixels with any piece
    uint piecesGathered;     // their pieces
    uint clustersShaded;     // the shadings they took
    uint visibleTriangles;   // per pixel, the distinct triangles of its pieces, summed
    uint pieceOverflowPixels;
    uint maxClusters;        // the most clusters in a pixel
    uint stillSampleLookups; // the samples' shadings of still textured clusters
};

struct ShownRecord {
    uint triangle;
    float share, depth, nearest, farthest;
    float r, g, b;
};
layout(std430, binding = 10) buffer ShownBuffer { ShownRecord shownRecords[]; };

const float kShareOverlap = 0.5;


uint meshOfTriangle(uint tri) { return vertexInfo[triangles[tri].x].x; }

// Adds a colour to a sample's record that holds a triangle: its own, or its mesh's where they
// joined (the resolve's showSurface).
void addShownColor(uint sampleIndex, uint tri, vec3 color) {
    if (u_writeSurfaces == 0) return;
    uint first = sampleIndex * uint(MAX_SHOWN);
    int k = -1;
    for (int r = 0; r < MAX_SHOWN && k < 0; ++r)
        if (shownRecords[first + uint(r)].triangle == tri) k = r;
    for (int r = 0; r < MAX_SHOWN && k < 0; ++r) {
        uint other = shownRecords[first + uint(r)].triangle;
        if (other != 0xffffffffu && meshOfTriangle(other) == meshOfTriangle(tri)) k = r;
    }
    if (k < 0) return;
    shownRecords[first + uint(k)].r += color.r;
    shownRecords[first + uint(k)].g += color.g;
    shownRecords[first + uint(k)].b += color.b;
}

uint pendingTriangle[MAX_PIXEL_PIECES];
vec3 pendingSpan[MAX_PIXEL_PIECES];    // t0, t1, weight
uint pendingSample[MAX_PIXEL_PIECES];  // sample << 16 | cell
uint order[MAX_PIXEL_PIECES];
uint sortScratch[MAX_PIXEL_PIECES];
vec3 colors[MAX_PIXEL_SAMPLES];
ivec2 sampleTexel[MAX_PIXEL_SAMPLES];
dvec2 sampleNdcs[MAX_PIXEL_SAMPLES];
int clusterBegin[MAX_PIXEL_PIECES];
vec2 clusterSpan[MAX_PIXEL_PIECES];  // the hull of its pieces' times
dvec2 clusterLo[MAX_PIXEL_PIECES], clusterHi[MAX_PIXEL_PIECES];
dvec3 clusterNdcSum[MAX_PIXEL_PIECES];  // the weighted sum of its samples' NDC, and of the weights

bool isTexturedTriangle(uint tri) { return materials[triangles[tri].w & kMaterialMask].info.x >= 0; }
bool isStillTexturedTriangle(uint tri) { return (triangles[tri].w & kStillBit) != 0u && isTexturedTriangle(tri); }
// The CPU's Sharing::OneColour: untextured, unlit, one vertex colour at its three corners.
bool isOneColourTriangle(uint tri) {
    uvec4 t = triangles[tri];
    return !isTexturedTriangle(tri) && u_flags.x == 0 && vertexColor(t.x) == vertexColor(t.y) && vertexColor(t.x) == vertexColor(t.z);
}

// Whether pending piece a sorts before b: by triangle, cell, start.
bool sortsBefore(uint a, uint b) {
    if (pendingTriangle[a] != pendingTriangle[b]) return pendingTriangle[a] < pendingTriangle[b];
    uint ca = pendingSample[a] & 0xffffu, cb = pendingSample[b] & 0xffffu;
    if (ca != cb) return ca < cb;
    return pendingSpan[a].x < pendingSpan[b].x;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= u_viewport.z || pixel.y >= u_viewport.w) return;
    int n = u_flags.y, spp = n * n;
    g_window = rowWindow(pixel.y);
    bool isCellOneSample = u_shadingCells >= n;

    // Gather, in sample order; each sample's pieces come sorted by (triangle, start).
    int numPending = 0, numOverflowing = 0;
    for (int s = 0; s < spp; ++s) {
        ivec2 texel = pixel * n + ivec2(s % n, s / n);
        sampleTexel[s] = texel;
        sampleNdcs[s] = sampleNdc(texel);
        colors[s] = imageLoad(u_output, texel).rgb;
        ivec2 offset = ivec2(sampleRaster(texel) - dvec2(pixel) * 256.0);
        ivec2 cellXY = offset * u_shadingCells / 256;
        uint cell = uint(cellXY.y * u_shadingCells + cellXY.x);
        uint sampleIndex = uint(texel.y) * uint(u_viewport.x) + uint(texel.x);
        uvec2 run = samplePieces[sampleIndex];
        for (uint k = 0u; k < run.y; ++k) {
            PieceNode piece = pieceNodes[run.x + k];
            if (numPending == u_maxPixelPieces) {
                ++numOverflowing;
                continue;
            }
            pendingTriangle[numPending] = piece.triangle;
            pendingSpan[numPending] = vec3(piece.t0, piece.t1, piece.weight);
            pendingSample[numPending] = uint(s) << 16 | (isTexturedTriangle(piece.triangle) && !isStillTexturedTriangle(piece.triangle) ? cell : 0u);
            order[numPending] = uint(numPending);
            ++numPending;
        }
    }
    if (numOverflowing > 0 && u_firstCluster == 0) atomicAdd(pieceOverflowPixels, 1u);
    if (numPending == 0) return;

    // A stable sort by (triangle, cell, start): bottom-up merges, n log n steps. (Swapping each
    // piece down into place took up to n^2 / 2, past llvmpipe's 65,535 loop iterations an
    // invocation at --aa 8's 512 pieces, before any shading.)
    for (int width = 1; width < numPending; width *= 2) {
        for (int lo = 0; lo < numPending; lo += 2 * width) {
            int mid = min(lo + width, numPending), hi = min(lo + 2 * width, numPending);
            int i = lo, j = mid;
            for (int k = lo; k < hi; ++k) {
                if (i < mid && (j >= hi || !sortsBefore(order[j], order[i]))) sortScratch[k] = order[i++];
                else sortScratch[k] = order[j++];
            }
        }
        for (int k = 0; k < numPending; ++k) order[k] = sortScratch[k];
    }

    // Clusters (exposure::PixelShading::formClusters): pieces order[begin, end) of one triangle
    // and cell, their hull in time, and the bounds and the weighted centroid of their samples.
    int numClusters = 0;
    for (int k = 0; k < numPending; ++k) {
        uint p = order[k];
        bool joins = false;
        if (numClusters > 0) {
            uint q = order[clusterBegin[numClusters - 1]];
            if (pendingTriangle[p] == pendingTriangle[q] && (pendingSample[p] & 0xffffu) == (pendingSample[q] & 0xffffu)) {
                vec2 hull = clusterSpan[numClusters - 1];
                float overlap = min(hull.y, pendingSpan[p].y) - pendingSpan[p].x;
                joins = isStillTexturedTriangle(pendingTriangle[p]) || isOneColourTriangle(pendingTriangle[p]) ||
                        overlap >= kShareOverlap * min(pendingSpan[p].y - pendingSpan[p].x, hull.y - hull.x);
            }
        }
        dvec2 ndc = sampleNdcs[pendingSample[p] >> 16];
        double weight = double(pendingSpan[p].z);
        if (joins) {
            int c = numClusters - 1;
            clusterSpan[c].y = max(clusterSpan[c].y, pendingSpan[p].y);
            clusterLo[c] = min(clusterLo[c], ndc);
            clusterHi[c] = max(clusterHi[c], ndc);
            clusterNdcSum[c] += dvec3(ndc * weight, weight);
        } else {
            clusterBegin[numClusters] = k;
            clusterSpan[numClusters] = pendingSpan[p].xy;
            clusterLo[numClusters] = ndc;
            clusterHi[numClusters] = ndc;
            clusterNdcSum[numClusters] = dvec3(ndc * weight, weight);
            ++numClusters;
        }
    }

    // Each cluster shaded once, its colour times each piece's weight added to the piece's sample.
    dvec2 pixelNdc = dvec2(2.0 / double(u_viewport.z), 2.0 / double(u_viewport.w));
    int triangleCount = 1;
    uint lastTriangle = 0xffffffffu;
    for (int c = 0; c < numClusters; ++c) {
        if (c > 0 && pendingTriangle[order[clusterBegin[c]]] != lastTriangle) ++triangleCount;
        lastTriangle = pendingTriangle[order[clusterBegin[c]]];
    }
    int lastCluster = min(numClusters + numOverflowing, u_firstCluster + u_clusterCount);
    // This dispatch's clusters, the pixel's own [u_firstCluster, numClusters) after those past
    // them (the pieces past u_maxPixelPieces), each shaded by the one call below: the compiler
    // inlines every call of shadeTimeSpanAt, and llvmpipe took 47 s to build this pass with three.
    int firstOwn = min(u_firstCluster, numClusters), lastOwn = min(numClusters, lastCluster);
    int firstPast = max(u_firstCluster, numClusters);
    int numPast = max(0, lastCluster - firstPast);
    for (int j = 0; j < numPast + max(0, lastOwn - firstOwn); ++j) {
        bool isPast = j < numPast;
        int c = isPast ? firstPast + j : firstOwn + j - numPast;
        uint tri;
        vec2 span;
        ShadingSite site;
        int begin = 0, end = 0, pastSample = 0;
        float pastWeight = 0.0;
        bool isStillShared = false;
        if (isPast) {
            // The piece numbered (c - numClusters) past u_maxPixelPieces in the gather's walk,
            // shaded at its sample.
            int target = c - numClusters + u_maxPixelPieces, walked = 0;
            for (int s = 0; s < spp; ++s) {
                uint sampleIndex = uint(sampleTexel[s].y) * uint(u_viewport.x) + uint(sampleTexel[s].x);
                uvec2 run = samplePieces[sampleIndex];
                if (target >= walked && target < walked + int(run.y)) {
                    PieceNode piece = pieceNodes[run.x + uint(target - walked)];
                    tri = piece.triangle;
                    span = vec2(piece.t0, piece.t1);
                    pastWeight = piece.weight;
                    pastSample = s;
                }
                walked += int(run.y);
            }
            site = sampleSite(sampleNdcs[pastSample]);
        } else {
            begin = clusterBegin[c];
            end = c + 1 < numClusters ? clusterBegin[c + 1] : numPending;
            uint first = order[begin];
            tri = pendingTriangle[first];
            span = clusterSpan[c];
            isStillShared = end - begin > 1 && isStillTexturedTriangle(tri);
            if ((isCellOneSample || isStillTexturedTriangle(tri)) && end - begin == 1) {
                site = sampleSite(sampleNdcs[pendingSample[first] >> 16]);
            } else {
                dvec2 lo = clusterLo[c], hi = clusterHi[c];
                dvec3 sum = clusterNdcSum[c];
                dvec2 ndc = u_boxFilter != 0 ? 0.5 * (lo + hi) : sum.z > 0.0 ? sum.xy / sum.z : sampleNdcs[pendingSample[first] >> 16];
                dvec2 footprint = min(dvec2(1.0 / double(u_shadingCells)), abs(hi - lo) / pixelNdc + dvec2(1.0 / double(n)));
                site = ShadingSite(ndc, footprint, true, u_boxFilter != 0, boxTapsOf(footprint, n), boxBudgetOf(n, u_shadingCells));
            }
        }
        // (One call of shadeTimeSpanAt, for a still cluster once a piece, at the piece's sample.)
        int members = isStillShared ? end - begin : 1;
        vec3 sum = vec3(0.0);
        float weights = 0.0;
        for (int m = 0; m < members; ++m) {
            uint piece = order[begin + m];
            ShadingSite at = isStillShared ? sampleSite(sampleNdcs[pendingSample[piece] >> 16]) : site;
            float weight = isStillShared ? pendingSpan[piece].z : 1.0;
            sum += weight * shadeTimeSpanAt(tri, span.x, span.y, at).rgb;
            weights += weight;
        }
        vec3 color = weights > 0.0 ? sum / weights : vec3(0.0);
        if (isStillShared) atomicAdd(stillSampleLookups, uint(members));
        if (isPast) {
            vec3 added = color * pastWeight;
            colors[pastSample] += added;
            addShownColor(uint(sampleTexel[pastSample].y) * uint(u_viewport.x) + uint(sampleTexel[pastSample].x), tri, added);
        }
        for (int m = begin; m < end; ++m) {
            uint piece = order[m];
            int s = int(pendingSample[piece] >> 16);
            vec3 added = color * pendingSpan[piece].z;
            colors[s] += added;
            addShownColor(uint(sampleTexel[s].y) * uint(u_viewport.x) + uint(sampleTexel[s].x), pendingTriangle[piece], added);
        }
    }
    if (lastCluster > u_firstCluster)
        for (int s = 0; s < spp; ++s) {
            vec4 stored = imageLoad(u_output, sampleTexel[s]);
            imageStore(u_output, sampleTexel[s], vec4(colors[s], stored.a));
        }
    atomicAdd(clustersShaded, uint(max(0, lastCluster - u_firstCluster)));
    if (u_firstCluster > 0) return;
    atomicMax(maxClusters, uint(numClusters + numOverflowing));
    atomicAdd(pixelsShaded, 1u);
    atomicAdd(piecesGathered, uint(numPending));
    atomicAdd(visibleTriangles, uint(triangleCount));
}
