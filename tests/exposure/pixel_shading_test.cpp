#include "exposure/pixel_shading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace streak::exposure {

namespace {

struct Call {
    std::uint32_t triangle;
    float t0, t1;
    ShadingSite site;
};

// Shades every triangle with its own constant colour, recording each call.
struct Recorder {
    std::vector<Call> calls;
    ShadedColor operator()(std::uint32_t triangle, float t0, float t1, const ShadingSite& site) {
        calls.push_back({triangle, t0, t1, site});
        return {glm::vec3(float(triangle + 1), 0.5f, 0.25f), 1.0f};
    }
};

glm::dvec2 sampleNdc(int s) { return {0.01 * s, -0.02 * s}; }

constexpr auto kUntextured = [](std::uint32_t) { return Sharing::Pixel; };
constexpr auto kTextured = [](std::uint32_t) { return Sharing::Cells; };

}  // namespace

TEST(PixelShading, SampleRateShadesEveryPieceAtItsSample) {
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(2);
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 2);
    for (int s = 0; s < 4; ++s) {
        const VisiblePiece piece{7, 0.0f, 1.0f, 1.0f, true};
        shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), kUntextured);
    }
    Recorder recorder;
    std::vector<glm::vec3> colors(4, glm::vec3(0.0f));
    PixelShadingCounters counters;
    shading.finish(PixelShadingOptions{ShadingRate::Sample}, recorder, colors, counters);
    ASSERT_EQ(recorder.calls.size(), 4u);
    for (int s = 0; s < 4; ++s) {
        EXPECT_EQ(recorder.calls[std::size_t(s)].site.ndc, sampleNdc(s));
        EXPECT_EQ(recorder.calls[std::size_t(s)].site.footprintPixels, glm::dvec2(0.5));
        EXPECT_FALSE(recorder.calls[std::size_t(s)].site.clampToTriangle);
        EXPECT_EQ(colors[std::size_t(s)], glm::vec3(8.0f, 0.5f, 0.25f));
    }
    EXPECT_EQ(counters.shadedSpans, 4);
    EXPECT_EQ(counters.visibleTriangles, 1);
}

// With a cell per sample a textured piece has nothing to share: pixel shading is per-sample
// shading, call for call (the sample's own site and span), whatever the filter. Untextured pieces
// still share one shading over the pixel.
TEST(PixelShading, ACellOfOneSampleShadesItAsPerSampleShadingDoes) {
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(2);
    // The 2 x 2 samples in 2 x 2 cells, one cell each, see triangle 3 until different times.
    auto shadeWith = [&](const PixelShadingOptions& options, auto isTextured, Recorder& recorder, std::vector<glm::vec3>& colors) {
        PixelShading shading;
        shading.begin(pattern, glm::dvec2(0.1), 2);
        for (int s = 0; s < 4; ++s) {
            const std::vector<VisiblePiece> pieces{{3, 0.0f, 0.5f + 0.1f * float(s), 0.5f + 0.1f * float(s), true}};
            shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(pieces), isTextured);
        }
        colors.assign(4, glm::vec3(0.0f));
        PixelShadingCounters counters;
        shading.finish(options, recorder, colors, counters);
    };
    for (const bool box : {true, false}) {
        Recorder perSample, perPixel;
        std::vector<glm::vec3> sampleColors, pixelColors;
        shadeWith(PixelShadingOptions{ShadingRate::Sample, 4, box}, kTextured, perSample, sampleColors);
        shadeWith(PixelShadingOptions{ShadingRate::Pixel, 4, box}, kTextured, perPixel, pixelColors);
        ASSERT_EQ(perPixel.calls.size(), 4u);
        ASSERT_EQ(perPixel.calls.size(), perSample.calls.size());
        for (std::size_t k = 0; k < 4; ++k) {
            EXPECT_EQ(perPixel.calls[k].t1, perSample.calls[k].t1);
            EXPECT_EQ(perPixel.calls[k].site.ndc, perSample.calls[k].site.ndc);
            EXPECT_EQ(perPixel.calls[k].site.footprintPixels, perSample.calls[k].site.footprintPixels);
            EXPECT_EQ(perPixel.calls[k].site.boxFootprint, perSample.calls[k].site.boxFootprint);
        }
        EXPECT_EQ(pixelColors, sampleColors);
    }
    Recorder shared;
    std::vector<glm::vec3> colors;
    shadeWith(PixelShadingOptions{ShadingRate::Pixel, 4, true}, kUntextured, shared, colors);
    EXPECT_EQ(shared.calls.size(), 1u);
}

TEST(PixelShading, OverlappingPiecesShareOneShadingWeightedBySample) {
    // An edge sweeping over the pixel: the samples see the triangle from t = 0 to different
    // times, and one sample also sees a second triangle.
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(2);
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 1);
    const float ends[4] = {1.0f, 0.8f, 0.6f, 0.4f};
    for (int s = 0; s < 4; ++s) {
        std::vector<VisiblePiece> pieces{{3, 0.0f, ends[s], ends[s], true}};
        if (s == 3) pieces.push_back({5, 0.4f, 1.0f, 0.6f, true});
        shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(pieces), kUntextured);
    }
    Recorder recorder;
    std::vector<glm::vec3> colors(4, glm::vec3(0.0f));
    PixelShadingCounters counters;
    // With the GPU lookup's filter: one bell at the samples' centroid.
    shading.finish(PixelShadingOptions{ShadingRate::Pixel, 4, false}, recorder, colors, counters);
    ASSERT_EQ(recorder.calls.size(), 2u);
    const Call& shared = recorder.calls[0];
    EXPECT_EQ(shared.triangle, 3u);
    EXPECT_EQ(shared.t0, 0.0f);
    EXPECT_EQ(shared.t1, 1.0f);
    EXPECT_TRUE(shared.site.clampToTriangle);
    EXPECT_FALSE(shared.site.boxFootprint);
    // The exposure-weighted centroid of the four samples.
    glm::dvec2 centroid(0.0);
    double weights = 0.0;
    for (int s = 0; s < 4; ++s) centroid += sampleNdc(s) * double(ends[s]), weights += ends[s];
    EXPECT_NEAR(shared.site.ndc.x, centroid.x / weights, 1e-12);
    EXPECT_NEAR(shared.site.ndc.y, centroid.y / weights, 1e-12);
    // The samples span 0.03 x 0.06 NDC of a 0.1 pixel: 0.3 x 0.6 pixels, plus a sample spacing,
    // at most the pixel.
    EXPECT_NEAR(shared.site.footprintPixels.x, 0.3 + 0.5, 1e-9);
    EXPECT_NEAR(shared.site.footprintPixels.y, 1.0, 1e-9);
    for (int s = 0; s < 3; ++s) EXPECT_EQ(colors[std::size_t(s)], glm::vec3(4.0f, 0.5f, 0.25f) * ends[s]);
    EXPECT_EQ(colors[3], glm::vec3(4.0f, 0.5f, 0.25f) * 0.4f + glm::vec3(6.0f, 0.5f, 0.25f) * 0.6f);
    EXPECT_EQ(counters.pieces, 5);
    EXPECT_EQ(counters.shadedSpans, 2);
    EXPECT_EQ(counters.visibleTriangles, 2);
}

// A box footprint (the default) spans the samples' bounds, so it sits at their middle: at the
// centroid it would reach past the samples on one side and miss them on the other.
TEST(PixelShading, ABoxFootprintIsCentredOnItsSamplesBounds) {
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(2);
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 1);
    const float weights[4] = {1.0f, 0.1f, 0.1f, 0.1f};  // a centroid pulled toward sample 0
    for (int s = 0; s < 4; ++s) {
        const VisiblePiece piece{3, 0.0f, 1.0f, weights[s], true};
        shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), kTextured);
    }
    Recorder recorder;
    std::vector<glm::vec3> colors(4, glm::vec3(0.0f));
    PixelShadingCounters counters;
    shading.finish(PixelShadingOptions{ShadingRate::Pixel, 1}, recorder, colors, counters);
    ASSERT_EQ(recorder.calls.size(), 1u);
    const ShadingSite& site = recorder.calls[0].site;
    EXPECT_TRUE(site.boxFootprint);
    EXPECT_TRUE(site.clampToTriangle);
    EXPECT_NEAR(site.ndc.x, 0.5 * (sampleNdc(0).x + sampleNdc(3).x), 1e-12);
    EXPECT_NEAR(site.ndc.y, 0.5 * (sampleNdc(0).y + sampleNdc(3).y), 1e-12);
    // At most the cell: one pixel.
    EXPECT_EQ(site.footprintPixels, glm::dvec2(0.8, 1.0));
}

TEST(PixelShading, AFastSliverIsShadedOnlyOverTheTimesItsSamplesSeeIt) {
    // A thin triangle crossing the pixel fast: each sample sees it for a short time, the
    // samples one after another. A shading over the hull of all of them would smear it along
    // its path; every shading must cover only times its own samples see it, each joined piece
    // overlapping the cluster by at least half of the shorter.
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(4);
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 1);
    std::vector<VisiblePiece> all;
    for (int s = 0; s < 16; ++s) {
        const float t0 = 0.2f + 0.01f * float((s * 7) % 16);
        const VisiblePiece piece{9, t0, t0 + 0.012f, 0.012f, true};
        all.push_back(piece);
        shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), kUntextured);
    }
    Recorder recorder;
    std::vector<glm::vec3> colors(16, glm::vec3(0.0f));
    PixelShadingCounters counters;
    shading.finish(PixelShadingOptions{ShadingRate::Pixel}, recorder, colors, counters);
    EXPECT_GT(recorder.calls.size(), 4u);  // the hull [0.2, 0.362] is not shaded as one
    for (const Call& call : recorder.calls) {
        EXPECT_LE(call.t1 - call.t0, 0.012f * 2.0f + 1e-6f) << "a shading spans more than its pieces";
        // Every instant of the shading is seen by one of the pieces it serves.
        for (float f = 0.0f; f <= 1.0f; f += 0.125f) {
            const float t = call.t0 + f * (call.t1 - call.t0);
            EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const VisiblePiece& p) { return t >= p.t0 - 1e-6f && t <= p.t1 + 1e-6f; }));
        }
    }
    for (const glm::vec3& c : colors) EXPECT_EQ(c, glm::vec3(10.0f, 0.5f, 0.25f) * 0.012f);
}

TEST(PixelShading, AnUnlitTriangleOfOneColourTakesOneShadingOverAllItsTimes) {
    // The sliver above, of one colour in an unlit render (Sharing::OneColour): nothing along its
    // path can be smeared, so its 16 pieces at their scattered times take one shading.
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(4);
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 1);
    for (int s = 0; s < 16; ++s) {
        const float t0 = 0.2f + 0.01f * float((s * 7) % 16);
        const VisiblePiece piece{9, t0, t0 + 0.012f, 0.012f, true};
        shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), [](std::uint32_t) { return Sharing::OneColour; });
    }
    Recorder recorder;
    std::vector<glm::vec3> colors(16, glm::vec3(0.0f));
    PixelShadingCounters counters;
    shading.finish(PixelShadingOptions{ShadingRate::Pixel}, recorder, colors, counters);
    ASSERT_EQ(recorder.calls.size(), 1u);
    EXPECT_FLOAT_EQ(recorder.calls[0].t0, 0.2f);
    EXPECT_FLOAT_EQ(recorder.calls[0].t1, 0.2f + 0.15f + 0.012f);
    EXPECT_EQ(counters.shadedSpans, 1);
    EXPECT_EQ(counters.visibleTriangles, 1);
    for (const glm::vec3& c : colors) EXPECT_EQ(c, glm::vec3(10.0f, 0.5f, 0.25f) * 0.012f);
}

TEST(PixelShading, OnlyAnUntexturedTriangleOfOneColourInAnUnlitRenderIsOneColour) {
    Material untextured, textured;
    textured.baseColorTexture = 0;
    FlatTriangle oneColour, blended;
    blended.isOneColour = false;
    EXPECT_EQ(sharingOf(untextured, oneColour, true, false), Sharing::OneColour);
    EXPECT_EQ(sharingOf(untextured, oneColour, true, true), Sharing::OneColour);
    EXPECT_EQ(sharingOf(untextured, oneColour, false, false), Sharing::Pixel);  // lit: its normal turns
    EXPECT_EQ(sharingOf(untextured, blended, true, false), Sharing::Pixel);     // its vertex colours blend
    EXPECT_EQ(sharingOf(textured, oneColour, true, false), Sharing::Cells);
    EXPECT_EQ(sharingOf(textured, oneColour, true, true), Sharing::StillTextured);
    // The render's mode says which: unlit is, a lit or data pass is not.
    EXPECT_TRUE(PixelShadingOptions{}.forMode(ShadingMode::Unlit).isUnlit);
    EXPECT_FALSE(PixelShadingOptions{}.forMode(ShadingMode::Phong).isUnlit);
    EXPECT_FALSE(PixelShadingOptions{}.forMode(ShadingMode::Normal).isUnlit);
}

TEST(PixelShading, TexturedTrianglesAreShadedPerCellUntexturedOncePerPixel) {
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(4);
    for (const bool textured : {false, true}) {
        PixelShading shading;
        shading.begin(pattern, glm::dvec2(0.1), 2);
        for (int s = 0; s < 16; ++s) {
            const VisiblePiece piece{1, 0.0f, 1.0f, 1.0f, true};
            if (textured) shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), kTextured);
            else shading.add(s, sampleNdc(s), std::span<const VisiblePiece>(&piece, 1), kUntextured);
        }
        Recorder recorder;
        std::vector<glm::vec3> colors(16, glm::vec3(0.0f));
        PixelShadingCounters counters;
        shading.finish(PixelShadingOptions{ShadingRate::Pixel}, recorder, colors, counters);
        ASSERT_EQ(recorder.calls.size(), textured ? 4u : 1u);
        for (const Call& call : recorder.calls) EXPECT_LE(call.site.footprintPixels.x, textured ? 0.5 : 1.0);
        EXPECT_EQ(counters.visibleTriangles, 1);
    }
}

// The cells a side are at most shading-cells (4) and --aa, and as few as hold the same samples a
// side: at --aa 6, 3 x 3 cells of 2 x 2 samples each shade once, where 4 x 4 cells would hold
// one or two samples a side (16 shadings, most of them boxes shared by two). At --aa 2 to 4 the
// pixel is one cell (kOneCellFromAa, kOneCellUpToAa): its samples share one box rather than each
// take a lookup, at --aa 2 a box of a quarter of the budget (boxBudgetOf).
TEST(PixelShading, EachCellHoldsAsManySamplesASideAsTheCellsAllow) {
    const PixelShadingOptions options;
    static_assert(PixelShadingOptions::kOneCellFromAa == 2 && PixelShadingOptions::kOneCellUpToAa == 4);
    const int expected[] = {0, 1, 1, 1, 1, 3, 3, 4, 4, 3, 4, 4, 4, 4, 4, 4, 4};
    for (int n = 1; n <= 16; ++n) {
        const int cells = options.cellsFor(n);
        EXPECT_EQ(cells, expected[n]) << "--aa " << n;
        const raster::SamplePattern pattern = raster::SamplePattern::rooks(n);
        PixelShading shading;
        shading.begin(pattern, glm::dvec2(0.1), cells);
        for (int s = 0; s < pattern.count(); ++s) {
            const VisiblePiece piece{1, 0.0f, 1.0f, 1.0f, true};
            shading.add(s, glm::dvec2(0.1) * glm::dvec2(pattern.offsets[std::size_t(s)]) / double(raster::kSubpixelScale),
                        std::span<const VisiblePiece>(&piece, 1), kTextured);
        }
        Recorder recorder;
        std::vector<glm::vec3> colors(std::size_t(pattern.count()), glm::vec3(0.0f));
        PixelShadingCounters counters;
        shading.finish(options, recorder, colors, counters);
        // A textured piece every sample sees is shaded once a cell, each cell as wide as the
        // samples it holds.
        EXPECT_EQ(recorder.calls.size(), std::size_t(cells * cells)) << "--aa " << n;
        const int perCell = (n + cells - 1) / cells;
        for (const Call& call : recorder.calls) {
            EXPECT_LE(call.site.footprintPixels.x, double(perCell) / n + 1e-9) << "--aa " << n;
            // The box's budget: a quarter where one box serves a pixel of 2 x 2 samples, else all.
            if (n > 1) { EXPECT_EQ(call.site.boxBudget, n == 2 ? Texture::kMaxSweptBoxTaps / 4 : Texture::kMaxSweptBoxTaps) << "--aa " << n; }
        }
    }
    // An explicit count is a most: 2 at --aa 8 is 2 cells of 4 x 4, 3 is 3 of up to 3 x 3; and
    // at --aa 2 to 4 one cell whatever the count.
    PixelShadingOptions two, three;
    two.cellsPerAxis = 2, three.cellsPerAxis = 3;
    EXPECT_EQ(two.cellsFor(8), 2);
    EXPECT_EQ(three.cellsFor(8), 3);
    EXPECT_EQ(three.cellsFor(5), 3);
    EXPECT_EQ(three.cellsFor(2), 1);
    EXPECT_EQ(three.cellsFor(4), 1);
}

// A still textured triangle (Sharing::StillTextured) shares one shading a pixel across its
// cells and times: one call, its site at one of its samples with that sample's footprint, and
// every piece's sample and exposure listed for the texture's lookups. A lone piece shades as its
// sample does alone.
TEST(PixelShading, AStillTexturedTriangleSharesOneShadingThatListsEverySample) {
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(4);
    constexpr auto kStill = [](std::uint32_t) { return Sharing::StillTextured; };
    auto ndcOf = [&](int s) { return glm::dvec2(0.1) * glm::dvec2(pattern.offsets[std::size_t(s)]) / double(raster::kSubpixelScale); };
    PixelShading shading;
    shading.begin(pattern, glm::dvec2(0.1), 4);
    float weights = 0.0f;
    for (int s = 0; s < 16; ++s) {
        // Seen over different, some disjoint, times (hidden in between by something moving).
        const std::vector<VisiblePiece> pieces = s % 3 == 0 ? std::vector<VisiblePiece>{{2, 0.0f, 0.2f, 0.2f, true}, {2, 0.7f, 1.0f, 0.3f, true}}
                                                            : std::vector<VisiblePiece>{{2, 0.1f * float(s % 4), 1.0f, 1.0f - 0.1f * float(s % 4), true}};
        for (const VisiblePiece& p : pieces) weights += p.weight;
        shading.add(s, ndcOf(s), std::span<const VisiblePiece>(pieces), kStill);
    }
    std::vector<SiteSample> listed;
    ShadingSite site;
    int calls = 0;
    auto shade = [&](std::uint32_t triangle, float, float, const ShadingSite& s) {
        ++calls, site = s;
        listed.assign(s.samples.begin(), s.samples.end());
        return ShadedColor{glm::vec3(float(triangle)), 1.0f};
    };
    std::vector<glm::vec3> colors(16, glm::vec3(0.0f));
    PixelShadingCounters counters;
    shading.finish(PixelShadingOptions{}, shade, colors, counters);
    ASSERT_EQ(calls, 1);
    EXPECT_EQ(counters.shadedSpans, 1);
    EXPECT_EQ(counters.stillSampleLookups, 22);  // 16 samples, 6 of them seeing it twice
    ASSERT_EQ(listed.size(), 22u);
    float listedWeights = 0.0f;
    for (const SiteSample& s : listed) {
        listedWeights += s.weight;
        EXPECT_TRUE(std::any_of(listed.begin(), listed.end(), [&](const SiteSample& o) { return o.ndc == s.ndc; }));
    }
    EXPECT_FLOAT_EQ(listedWeights, weights);
    // One of the samples, with one sample spacing for its footprint, not held (it is on the
    // triangle): as a sample shading alone.
    EXPECT_TRUE(std::any_of(listed.begin(), listed.end(), [&](const SiteSample& o) { return o.ndc == site.ndc; }));
    EXPECT_EQ(site.footprintPixels, glm::dvec2(0.25));
    EXPECT_FALSE(site.clampToTriangle);
    EXPECT_FALSE(site.boxFootprint);
    for (int s = 0; s < 16; ++s) {
        const float w = s % 3 == 0 ? 0.5f : 1.0f - 0.1f * float(s % 4);
        EXPECT_FLOAT_EQ(colors[std::size_t(s)].x, 2.0f * w) << s;
    }

    // A lone piece: its own sample's site, no list.
    shading.begin(pattern, glm::dvec2(0.1), 4);
    const VisiblePiece piece{2, 0.0f, 1.0f, 1.0f, true};
    shading.add(5, ndcOf(5), std::span<const VisiblePiece>(&piece, 1), kStill);
    calls = 0;
    shading.finish(PixelShadingOptions{}, shade, colors, counters);
    ASSERT_EQ(calls, 1);
    EXPECT_EQ(site.ndc, ndcOf(5));
    EXPECT_TRUE(listed.empty());
}

}  // namespace streak::exposure
