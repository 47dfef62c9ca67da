#include "exposure/pixel_shading.h"

#include "util/error.h"

#include <glm/common.hpp>

#include <algorithm>
#include <numeric>

namespace streak::exposure {

PixelShadingOptions pixelShadingOptions(OptionMap& options, const std::string& method) {
    PixelShadingOptions o;
    const std::string value = options.getString("shading", "pixel");
    if (value == "pixel") o.rate = ShadingRate::Pixel;
    else if (value == "sample") o.rate = ShadingRate::Sample;
    else throw Error("method '" + method + "': shading must be pixel or sample, got '" + value + "'");
    o.cellsPerAxis = options.getInt("shading-cells", o.cellsPerAxis, 1, 16);
    const std::string filter = options.getString("shading-filter", "box");
    if (filter == "box") o.boxFilter = true;
    else if (filter == "lookup") o.boxFilter = false;
    else throw Error("method '" + method + "': shading-filter must be box or lookup, got '" + filter + "'");
    return o;
}

void recordPixelShadingStats(RenderStats& stats, const PixelShadingCounters& c, double numPixels, const PixelShadingOptions& options) {
    stats.setCounter("shading_per_pixel", options.rate == ShadingRate::Pixel ? 1 : 0);
    stats.setCounter("shading_cells", options.rate == ShadingRate::Pixel ? options.cellsPerAxis : 0);
    stats.setCounter("shaded_spans", double(c.shadedSpans));
    stats.setCounter("visible_pieces", double(c.pieces));
    stats.setCounter("shaded_spans_per_pixel", numPixels > 0.0 ? double(c.shadedSpans) / numPixels : 0.0);
    stats.setCounter("visible_triangles_per_pixel", numPixels > 0.0 ? double(c.visibleTriangles) / numPixels : 0.0);
    stats.setCounter("still_sample_lookups", double(c.stillSampleLookups));
}

void PixelShading::begin(const raster::SamplePattern& pattern, const glm::dvec2& pixelNdc, int cellsPerAxis) {
    m_samplesPerAxis = pattern.samplesPerAxis();
    m_pixelNdc = pixelNdc;
    m_pending.clear();
    if (m_ndc.size() == std::size_t(pattern.count()) && m_cellsPerAxis == cellsPerAxis) return;
    m_cellsPerAxis = cellsPerAxis;
    m_ndc.assign(std::size_t(pattern.count()), glm::dvec2(0.0));
    m_cell.resize(std::size_t(pattern.count()));
    for (int s = 0; s < pattern.count(); ++s) {
        const glm::i64vec2 cell = pattern.offsets[std::size_t(s)] * std::int64_t(cellsPerAxis) / raster::kSubpixelScale;
        m_cell[std::size_t(s)] = std::uint32_t(cell.y * cellsPerAxis + cell.x);
    }
}

void PixelShading::formClusters(bool isBoxCentred) {
    m_order.resize(m_pending.size());
    std::iota(m_order.begin(), m_order.end(), 0u);
    // Each sample's pieces come sorted by (triangle, start) already, and a sample has one cell:
    // the stable sort keeps each sample's order.
    auto isBefore = [&](std::uint32_t a, std::uint32_t b) {
        const Pending &pa = m_pending[a], &pb = m_pending[b];
        if (pa.piece.triangle != pb.piece.triangle) return pa.piece.triangle < pb.piece.triangle;
        if (pa.cell != pb.cell) return pa.cell < pb.cell;
        return pa.piece.t0 < pb.piece.t0;
    };
    // A pixel's few pieces, mostly of one or two triangles, sort in place by insertion (stable,
    // and about linear when they are); std::stable_sort takes a buffer from the heap each call.
    constexpr std::size_t kInsertionSortMost = 64;
    if (m_order.size() <= kInsertionSortMost) {
        for (std::size_t i = 1; i < m_order.size(); ++i) {
            const std::uint32_t value = m_order[i];
            std::size_t j = i;
            for (; j > 0 && isBefore(value, m_order[j - 1]); --j) m_order[j] = m_order[j - 1];
            m_order[j] = value;
        }
    } else {
        std::stable_sort(m_order.begin(), m_order.end(), isBefore);
    }
    m_clusters.clear();
    glm::dvec2 ndcSum(0.0), lo(0.0), hi(0.0);
    double weightSum = 0.0;
    auto close = [&] {
        Cluster& c = m_clusters.back();
        // A box is centred on its samples' bounds, which it spans; a lookup sits at their centroid.
        if (isBoxCentred) c.ndc = 0.5 * (lo + hi);
        else c.ndc = weightSum > 0.0 ? ndcSum / weightSum : m_ndc[m_pending[m_order[c.begin]].sample];
        // The samples' spread plus one sample spacing, at most the cell.
        c.footprintPixels = glm::min(glm::dvec2(1.0 / m_cellsPerAxis), glm::abs(hi - lo) / m_pixelNdc + glm::dvec2(1.0 / m_samplesPerAxis));
    };
    for (std::uint32_t k = 0; k < std::uint32_t(m_order.size()); ++k) {
        const Pending& p = m_pending[m_order[k]];
        bool joins = false;
        if (!m_clusters.empty() && m_clusters.back().triangle == p.piece.triangle && m_clusters.back().cell == p.cell) {
            const Cluster& c = m_clusters.back();
            const float overlap = std::min(c.t1, p.piece.t1) - p.piece.t0;
            joins = p.joinsAll() || overlap >= kShareOverlap * std::min(p.piece.t1 - p.piece.t0, c.t1 - c.t0);
        }
        if (joins) {
            Cluster& c = m_clusters.back();
            c.t1 = std::max(c.t1, p.piece.t1), c.end = k + 1;
        } else {
            if (!m_clusters.empty()) close();
            m_clusters.push_back({p.piece.triangle, p.cell, k, k + 1, p.piece.t0, p.piece.t1, glm::dvec2(0.0), glm::dvec2(1.0),
                                  p.sharing == Sharing::StillTextured});
            ndcSum = glm::dvec2(0.0), weightSum = 0.0;
            lo = hi = m_ndc[p.sample];
        }
        const glm::dvec2& ndc = m_ndc[p.sample];
        ndcSum += ndc * double(p.piece.weight), weightSum += double(p.piece.weight);
        lo = glm::min(lo, ndc), hi = glm::max(hi, ndc);
    }
    if (!m_clusters.empty()) close();
}

std::int64_t PixelShading::countTriangles() {
    m_order.clear();
    for (const Pending& p : m_pending) m_order.push_back(p.piece.triangle);
    std::sort(m_order.begin(), m_order.end());
    return std::int64_t(std::unique(m_order.begin(), m_order.end()) - m_order.begin());
}

}  // namespace streak::exposure
