#pragma once

#include "exposure/shading_site.h"
#include "exposure/visible_pieces.h"
#include "raster/sample_pattern.h"
#include "scene/flat_geometry.h"
#include "scene/material.h"
#include "scene/shading.h"
#include "util/options.h"
#include "util/stats.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace streak::exposure {

// How often the exact methods shade what their samples see. Visibility is exact per sample
// either way; only the colour of a visible time span is shared or not.
enum class ShadingRate {
    // Decoupled shading (Ragan-Kelley et al. 2011): the samples of one pixel that see one
    // triangle over overlapping times share one shading, of the pixel's footprint swept along
    // the motion over the union of their times; each sample weighs it by its own exposure.
    Pixel,
    // Every visible span of every sample is shaded alone, at the sample, with a footprint of one
    // sample spacing: N^2 shadings per pixel and triangle, the reference path.
    Sample,
};

// The exact methods' shading options: `shading=pixel|sample` (pixel; against Cycles,
// docs/BENCHMARKS.md) and `shading-cells=G` (4):
// at ShadingRate::Pixel a textured triangle is shaded once per pixel at --aa 2 to 4, and else
// in G x G cells of the pixel (at most --aa N per axis, and as few as hold as many samples a side:
// PixelShadingOptions::cellsFor), each shared by the samples that fall in it; an untextured one
// once per pixel.
//
// `shading-filter=box|lookup` (box): how a shared shading filters its texture over the cluster's
// footprint, as the mean of its texels inside the triangle (TextureFootprint::isBox, clipTo) or
// as one sample's GPU lookup widened to the footprint. The lookup is about three times too wide
// a filter for a pixel's box: against Cycles it loses 11-12 dB on CesiumMan and Fox at 1 cell.
struct PixelShadingOptions {
    ShadingRate rate = ShadingRate::Pixel;
    int cellsPerAxis = 4;
    bool boxFilter = true;
    bool isUnlit = false;  ///< the render's colours are unlit (forMode): a OneColour triangle is one colour
    // The cells a side at --aa samplesPerAxis: at most cellsPerAxis (and --aa), and as few as
    // hold the same samples a side. At --aa 6 that is 3 cells of 2 x 2 samples, not 4 whose
    // cells hold one or two a side: a cell of one sample shades alone, and one of two pays for a
    // box (Texture::sampleBox) shared by only two. Against Cycles at --aa 6 the 14 shared models
    // score as with 4 within 0.2 dB but MorphStressTest (-1.2 dB), textured ones in 1.12-1.71x less
    // time (docs/BENCHMARKS.md, "Cells of equal samples").
    //
    // At --aa 2 to 4 (kOneCellFromAa to kOneCellUpToAa) the pixel is one cell: its samples
    // share one box over the pixel (at least as many taps a side as they span:
    // ShadingSite::boxTaps), where cells of one sample would each take their own lookup, a bell
    // of one sample spacing, whose sum over the pixel is a wider filter than the pixel's box.
    // Against Cycles (analytic, 320x240): CesiumMan +0.8 dB at --aa 3, Fox +1.2, and at --aa 4
    // every model within 0.2 dB or better; 1.2-2.5x faster on textured models (one box's taps,
    // at most Texture::kMaxSweptBoxTaps, for N^2 lookups' of up to 32 along a long path). At
    // --aa 2 the box takes a quarter of that budget (boxBudgetOf), about its four samples'
    // lookups: with the whole one it was 0.8x as fast as they on minified textures. Past --aa 4,
    // one box over 25 or more samples blurs what its cells keep (its level follows its longer
    // axis): CesiumMan at --aa 6 and 8 loses 1.3-1.7 dB with one cell (docs/BENCHMARKS.md, "One
    // cell at --aa 3 and 4" and "One cell at --aa 2").
    static constexpr int kOneCellFromAa = 2, kOneCellUpToAa = 4;
    int cellsFor(int samplesPerAxis) const {
        if (samplesPerAxis >= kOneCellFromAa && samplesPerAxis <= kOneCellUpToAa) return 1;
        const int most = std::max(1, std::min(cellsPerAxis, samplesPerAxis));
        const int perCell = (samplesPerAxis + most - 1) / most;
        return (samplesPerAxis + perCell - 1) / perCell;
    }
    // The options a render in `mode` shades with: a data pass (the normal, the motion vectors) is
    // a value of the point, not a colour to filter, so each sample takes its own and the pixel is
    // their mean (a shared shading would take it at the cluster's centre, over its hull).
    PixelShadingOptions forMode(ShadingMode mode) const {
        PixelShadingOptions o = *this;
        if (mode == ShadingMode::Normal || isVectorPass(mode)) o.rate = ShadingRate::Sample;
        o.isUnlit = mode == ShadingMode::Unlit;
        return o;
    }
};
PixelShadingOptions pixelShadingOptions(OptionMap& options, const std::string& method);

// How the pieces of one triangle in a pixel share their shading (PixelShading::add).
enum class Sharing : std::uint8_t {
    // Its colour varies within a pixel by no more than its lighting and vertex colours do
    // (untextured): one shading per pixel.
    Pixel,
    // Textured and moving: one shading per cell, its texture filtered over the cell's samples
    // swept along the motion (a box).
    Cells,
    // Untextured, unlit and one colour at its corners (FlatTriangle::isOneColour): its base colour
    // times that vertex colour at every point and time, so one shading per pixel serves all its
    // pieces, whatever their times: there is nothing along its path to smear (the time clusters
    // below split the others).
    OneColour,
    // Textured and still all the shutter, under a still camera: one shading per pixel, whose
    // point and texture footprint are found once and whose surface is then shaded (looked up and
    // lit) at each of its samples' own points (ShadingSite::samples), as each would alone but for
    // the footprint. The samples' lookups are the pixel's box filter of a still texture, which a
    // box over a cell only approximates, and the point with its footprint (three perspective
    // evaluations), most of a still sample's cost beside its lookup, is found once.
    StillTextured,
};

// How `triangle` (of `material`) shares in a render whose colours are unlit or not
// (PixelShadingOptions::isUnlit), where isStill says it is still all the shutter under a still
// camera (and its method looks up a still point's texture at its samples).
inline Sharing sharingOf(const Material& material, const FlatTriangle& triangle, bool isUnlit, bool isStill) {
    if (material.baseColorTexture < 0) return isUnlit && triangle.isOneColour ? Sharing::OneColour : Sharing::Pixel;
    return isStill ? Sharing::StillTextured : Sharing::Cells;
}

// What shading the visible pieces did, summed over pixels (for --stats).
struct PixelShadingCounters {
    std::int64_t pixels = 0;            ///< pixels with any visible opaque piece
    std::int64_t pieces = 0;            ///< visible opaque pieces of samples (abutting ones merged)
    std::int64_t shadedSpans = 0;       ///< the shadings they took
    std::int64_t visibleTriangles = 0;  ///< per pixel, the distinct triangles of its pieces, summed
    std::int64_t stillSampleLookups = 0;  ///< the samples shared still shadings listed (Sharing::StillTextured), each looked up and lit, one a piece
    void add(const PixelShadingCounters& o) {
        pixels += o.pixels, pieces += o.pieces, shadedSpans += o.shadedSpans, visibleTriangles += o.visibleTriangles;
        stillSampleLookups += o.stillSampleLookups;
    }
};

// Records them: shaded_spans, visible_pieces, and per pixel of numPixels (the image's) the
// shadings and the distinct visible triangles, whose ratio says how well shading is shared.
void recordPixelShadingStats(RenderStats& stats, const PixelShadingCounters& counters, double numPixels, const PixelShadingOptions& options);

// One pixel's visible opaque pieces, gathered from its samples once their visibility is
// resolved, then shaded together.
//
// At ShadingRate::Pixel the pieces of one triangle are sorted by start time and cut into time
// clusters: a piece joins the cluster before it when they overlap by at least half of the
// shorter of the piece and the cluster's hull (kShareOverlap). A large or slow triangle then
// takes one shading for all its samples; a thin fast sliver, whose samples see it at disjoint
// times, takes one per cluster of times and is never smeared along its path beyond them. A
// cluster is shaded over its hull with a footprint as wide as its samples spread (one sample
// spacing for a lone sample, one pixel for a full pixel): the box of those samples swept along
// the motion, centred on their bounds (a lookup's bell sits at their exposure-weighted
// centroid instead). At the times that point lies off the triangle (a cluster's samples see it
// at different times) it is held to the triangle (ShadingSite::clampToTriangle), and a box's
// texture taps are clipped to it, so a small triangle never shades its neighbours' texels.
class PixelShading {
public:
    static constexpr float kShareOverlap = 0.5f;

    // Starts a pixel with the samples of `pattern`, one pixel being pixelNdc wide and high in
    // NDC, shaded in cellsPerAxis x cellsPerAxis cells (ShadingRate::Pixel): each cell's
    // samples share their shadings.
    void begin(const raster::SamplePattern& pattern, const glm::dvec2& pixelNdc, int cellsPerAxis);
    // Adds the visible pieces of the pixel's sample `sample` at `ndc`; sharingOf(triangle) says
    // how a triangle's pieces share (Sharing).
    template <class SharingOf>
    void add(int sample, const glm::dvec2& ndc, std::span<const VisiblePiece> pieces, SharingOf&& sharingOf) {
        m_ndc[std::size_t(sample)] = ndc;
        for (const VisiblePiece& piece : pieces) {
            const Sharing sharing = sharingOf(piece.triangle);
            m_pending.push_back({piece, std::uint32_t(sample), sharing == Sharing::Cells ? m_cell[std::size_t(sample)] : 0u, sharing});
        }
    }

    // Shades the pixel's pieces with shade(triangle, t0, t1, ShadingSite) -> ShadedColor and adds
    // each piece's colour times its weight to colors[its sample], in each sample's own order of
    // pieces (so a colour that does not depend on the site gives each sample the same sum), and
    // tells added(triangle, that colour) (the deep image keeps each surface's colour).
    template <class Shade, class Added = void (*)(std::uint32_t, const glm::vec3&)>
    void finish(const PixelShadingOptions& options, Shade&& shade, std::span<glm::vec3> colors, PixelShadingCounters& counters,
                Added&& added = [](std::uint32_t, const glm::vec3&) {}) {
        if (m_pending.empty()) return;
        ++counters.pixels;
        counters.pieces += std::int64_t(m_pending.size());
        if (options.rate == ShadingRate::Sample) {
            for (const Pending& p : m_pending) {
                const glm::vec3 color =
                    shade(p.piece.triangle, p.piece.t0, p.piece.t1, sampleSite(m_ndc[p.sample], m_samplesPerAxis)).color * p.piece.weight;
                colors[p.sample] += color;
                added(p.piece.triangle, color);
            }
            counters.shadedSpans += std::int64_t(m_pending.size());
            counters.visibleTriangles += countTriangles();
            return;
        }
        formClusters(options.boxFilter);
        // Where a cell holds one sample (as many cells a side as samples: --aa up to the cell
        // count), a cluster of one piece has nothing to share: it shades as per-sample shading
        // does, with the sample's own lookup rather than a box over one sample (5x slower on
        // cubes at --aa 2). Untextured clusters still share across the pixel.
        const bool isCellOneSample = m_cellsPerAxis >= m_samplesPerAxis;
        std::uint32_t lastTriangle = ~0u;
        for (const Cluster& cluster : m_clusters) {
            const Pending& single = m_pending[m_order[cluster.begin]];
            const bool isSingle = cluster.end - cluster.begin == 1;
            glm::vec3 color;
            if ((isCellOneSample || cluster.isStillTextured) && isSingle) {
                color = shade(single.piece.triangle, single.piece.t0, single.piece.t1, sampleSite(m_ndc[single.sample], m_samplesPerAxis)).color;
            } else if (cluster.isStillTextured) {
                // The point and footprint at the sample nearest the samples' middle (on the
                // triangle, as a centre of their bounds need not be), each sample looked up and lit.
                m_siteSamples.clear();
                glm::dvec2 site = m_ndc[single.sample];
                double nearest = std::numeric_limits<double>::infinity();
                for (std::uint32_t k = cluster.begin; k < cluster.end; ++k) {
                    const Pending& p = m_pending[m_order[k]];
                    const glm::dvec2 ndc = m_ndc[p.sample], off = (ndc - cluster.ndc) / m_pixelNdc;
                    m_siteSamples.push_back({ndc, p.piece.weight});
                    if (const double d = off.x * off.x + off.y * off.y; d < nearest) nearest = d, site = ndc;
                }
                ShadingSite shared = sampleSite(site, m_samplesPerAxis);
                shared.samples = m_siteSamples;
                color = shade(cluster.triangle, cluster.t0, cluster.t1, shared).color;
                counters.stillSampleLookups += std::int64_t(m_siteSamples.size());
            } else {
                color = shade(cluster.triangle, cluster.t0, cluster.t1,
                              ShadingSite{cluster.ndc, cluster.footprintPixels, true, options.boxFilter,
                                          boxTapsOf(cluster.footprintPixels, m_samplesPerAxis), boxBudgetOf(m_samplesPerAxis, m_cellsPerAxis)})
                            .color;
            }
            for (std::uint32_t k = cluster.begin; k < cluster.end; ++k) {
                const Pending& p = m_pending[m_order[k]];
                colors[p.sample] += color * p.piece.weight;
                added(p.piece.triangle, color * p.piece.weight);
            }
            counters.visibleTriangles += cluster.triangle != lastTriangle;
            lastTriangle = cluster.triangle;
        }
        counters.shadedSpans += std::int64_t(m_clusters.size());
    }

private:
    struct Pending {
        VisiblePiece piece;
        std::uint32_t sample = 0, cell = 0;
        Sharing sharing = Sharing::Pixel;
        // Every piece of its triangle joins its cluster whatever its times: a still triangle's
        // colour is the same at every time, and a OneColour one's at every point too.
        bool joinsAll() const { return sharing == Sharing::StillTextured || sharing == Sharing::OneColour; }
    };
    // Pieces m_order[begin..end) of one triangle, shaded as one span.
    struct Cluster {
        std::uint32_t triangle = 0, cell = 0, begin = 0, end = 0;
        float t0 = 0.0f, t1 = 0.0f;
        glm::dvec2 ndc{0.0}, footprintPixels{1.0};
        bool isStillTextured = false;
    };

    void formClusters(bool isBoxCentred);
    std::int64_t countTriangles();

    int m_samplesPerAxis = 1;
    glm::dvec2 m_pixelNdc{1.0};
    int m_cellsPerAxis = 1;
    std::vector<glm::dvec2> m_ndc;      ///< per sample of the pixel
    std::vector<std::uint32_t> m_cell;  ///< per sample of the pixel: its shading cell
    std::vector<Pending> m_pending;
    std::vector<std::uint32_t> m_order;
    std::vector<Cluster> m_clusters;
    std::vector<SiteSample> m_siteSamples;  ///< a still textured cluster's samples, while it is shaded
};

}  // namespace streak::exposure
