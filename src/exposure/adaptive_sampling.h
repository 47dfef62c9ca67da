#pragma once

#include "image/image.h"
#include "raster/sample_pattern.h"
#include "raster/screen_triangle.h"
#include "util/stats.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace streak::exposure {

// What the first pass saw besides colour, for the geometry one centre sample can miss whole: a
// stroke of text, a wire, a thin edge-on part narrower than a pixel between the centres. Per
// pixel, the surfaces its sample showed (a set of (mesh, material) keys, 64 bits of a hash) and
// how deep it saw (the farthest depth of what showed, where opaque surfaces cover it all the
// shutter); and the triangle segments that covered no sample of the pass, with their pixel
// bounds and nearest depth. Such a segment refines the pixels of its bounds whose 3 x 3
// neighbourhood shows nothing of its surface and does not hide it: the small triangles inside a
// finely tessellated surface are unseen too, but their surface shows around them, and what they
// would add is its colour again; and small parts wholly behind what the pass saw stay hidden.
class FirstPassGeometry {
public:
    FirstPassGeometry(int width, int height)
        : m_width(width), m_shown(std::size_t(width) * std::size_t(height), 0),
          m_reach(std::size_t(width) * std::size_t(height), std::numeric_limits<float>::infinity()) {}

    static std::uint64_t keyBit(std::uint32_t mesh, std::uint32_t material) {
        const std::uint64_t h = (std::uint64_t(mesh) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(material) * 0xC2B2AE3D27D4EB4Full);
        return std::uint64_t(1) << ((h ^ (h >> 29)) & 63u);
    }
    // The pass's sample of pixel (x, y) showed this surface (from the thread whose tile owns it).
    void show(int x, int y, std::uint32_t mesh, std::uint32_t material) {
        m_shown[std::size_t(y) * std::size_t(m_width) + std::size_t(x)] |= keyBit(mesh, material);
    }
    std::uint64_t shownAt(int x, int y) const { return m_shown[std::size_t(y) * std::size_t(m_width) + std::size_t(x)]; }
    // Nothing beyond view depth `depth` can show at pixel (x, y): its sample saw opaque surfaces
    // all the shutter, none farther. (Infinite, the default, where it saw the background or
    // through a translucent surface.)
    void setReach(int x, int y, float depth) { m_reach[std::size_t(y) * std::size_t(m_width) + std::size_t(x)] = depth; }
    float reachAt(int x, int y) const { return m_reach[std::size_t(y) * std::size_t(m_width) + std::size_t(x)]; }

    // A segment of this surface covered no sample of `pixels` (a tile's rectangle, within its
    // bounds), coming no nearer than view depth `nearest` (0: unknown); any thread.
    struct Unseen {
        std::uint64_t key = 0;
        raster::PixelBounds pixels;
        float nearest = 0.0f;
    };
    void addUnseen(const Unseen& unseen) { m_unseen.local().push_back(unseen); }
    template <class F>
    void forEachUnseen(F&& f) const {
        for (const std::vector<Unseen>& list : m_unseen)
            for (const Unseen& u : list) f(u);
    }

private:
    int m_width;
    std::vector<std::uint64_t> m_shown;
    std::vector<float> m_reach;
    tbb::enumerable_thread_specific<std::vector<Unseen>> m_unseen;
};

// Adaptive antialiasing for the exact methods (RenderSettings::adaptiveThreshold): where a pixel
// needs its N x N samples, where fewer do, and where one does.
//
// Exact time spans make a pixel's colour smooth along the motion, so what point samples alias is
// space: silhouettes, creases and material edges. Most of an image has none, so the methods take
// a first pass and refine. The first gives every pixel one sample, at its centre (the --aa 1 pattern), exact
// over the shutter as always. A pixel is then refined, its colour and passes made again from a
// fuller pattern alone, where it or one of its 8 neighbours differs from it by more than the
// threshold in display terms: sRGB-encoded colour (clamped to [0, 1], what PSNR and the eye
// judge) or coverage. This is Mitchell's contrast refinement (1987), on exact spans. A motion-
// blurred edge ramps over many pixels, each close to the next, so it mostly stays at one sample;
// a still or slow edge, and any edge across the motion, is refined. What one centre sample and
// its neighbours all miss (a sliver thinner than a pixel that no centre sees) is not; a lower
// threshold refines more, 0 every pixel whose neighbourhood is not flat.
//
// How many samples a refined pixel takes follows its contrast, as Mitchell's second stage does:
// a box-filtered edge's error is about its contrast over the samples a side, so a pixel whose
// largest difference is at most `fullContrast` takes coarsePatternOf(N): half the samples a
// side, at least 2 (a quarter of them); one above it, or refined for a surface its sample
// missed, the whole N x N. Mild steps are a textured surface's detail and the edges between
// similar colours; strong ones are silhouettes against what lies behind (docs/BENCHMARKS.md,
// "Refinement by contrast").
class AdaptiveSampling {
public:
    // How a pixel is rendered again: not, with the coarse pattern, or with the full one.
    enum class Level : std::uint8_t { None = 0, Coarse = 1, Full = 2 };

    // The region a first pass renders: the asked one grown by a pixel on each side, within the
    // image, so each pixel it holds has its neighbours and is marked as the whole frame marks it
    // (a region render stays the whole frame's to the bit).
    static std::optional<raster::PixelBounds> firstPassRegion(const std::optional<raster::PixelBounds>& region, int width, int height);

    // The pattern of a pixel refined at Level::Coarse under `full`: half its samples a side, at
    // least 2, on the same kind of pattern (n-rooks or grid). When that is no fewer samples than
    // full has (N <= 2), there is no coarse level: every refined pixel takes the full pattern.
    static raster::SamplePattern coarsePatternOf(const raster::SamplePattern& full);
    static bool hasCoarseLevel(const raster::SamplePattern& full) { return coarsePatternOf(full).count() < full.count(); }

    // The contrast above which a refined pixel takes the full pattern, for `threshold` and the
    // asked `fullContrast` (RenderSettings::adaptiveFullContrast): 0 means the default, three
    // times the threshold; at most the threshold means every refined pixel takes it.
    static float fullContrastFor(float threshold, float fullContrast) {
        return fullContrast > 0.0f ? std::max(fullContrast, threshold) : 3.0f * threshold;
    }

    // Marks the pixels of `within` (the whole image without one) to refine, from the first pass:
    // by contrast, and where `geometry` (when given) has a surface its samples missed. With
    // hasCoarse, a pixel whose contrast is at most fullContrast (fullContrastFor's) takes
    // Level::Coarse; without, every marked pixel takes Level::Full.
    AdaptiveSampling(const Image& firstPass, float threshold, const std::optional<raster::PixelBounds>& within,
                     const FirstPassGeometry* geometry = nullptr, bool hasCoarse = false, float fullContrast = 0.0f);

    Level levelAt(int x, int y) const { return Level(m_marks[std::size_t(y) * std::size_t(m_width) + std::size_t(x)]); }
    bool isMarked(int x, int y) const { return levelAt(x, y) != Level::None; }
    // Whether rect holds a pixel of `level`.
    bool anyIn(const raster::PixelBounds& rect, Level level) const;
    std::int64_t numMarked() const { return m_numMarked; }
    std::int64_t numCoarse() const { return m_numCoarse; }

    // Calls f(run) for each run of pixels of `level` in rect, one row at a time, left to right.
    template <class F>
    void forEachRun(const raster::PixelBounds& rect, Level level, F&& f) const {
        for (int y = rect.y0; y <= rect.y1; ++y)
            for (int x = rect.x0; x <= rect.x1;) {
                if (levelAt(x, y) != level) {
                    ++x;
                    continue;
                }
                int end = x;
                while (end < rect.x1 && levelAt(end + 1, y) == level) ++end;
                f(raster::PixelBounds{x, y, end, y});
                x = end + 1;
            }
    }

    // How many samples the passes took over numPixels (a pixel and its refinement each): what
    // per-sample counters divide by.
    double numSamples(double numPixels, const raster::SamplePattern& full) const {
        return numPixels + double(m_numMarked - m_numCoarse) * double(full.count()) + double(m_numCoarse) * double(coarsePatternOf(full).count());
    }
    // How many pixels the passes resolved and shaded: per-pixel counters divide by it.
    double numPixelRenders(double numPixels) const { return numPixels + double(m_numMarked); }

    // adaptive_threshold, adaptive_full_contrast, adaptive_pixels_refined,
    // adaptive_pixels_refined_coarse (of them, those at Level::Coarse), adaptive_refined_fraction
    // (of the pixels asked for) and adaptive_pixels_unseen_geometry (refined for an unseen
    // surface alone).
    void record(RenderStats& stats, float threshold) const;

private:
    int m_width = 0;
    float m_fullContrast = 0.0f;  ///< 0 without a coarse level
    std::vector<std::uint8_t> m_marks;  ///< Level per pixel
    std::int64_t m_numMarked = 0, m_numCoarse = 0, m_numAsked = 0, m_numMissed = 0;  ///< missed: marked for an unseen surface alone
};

}  // namespace streak::exposure
