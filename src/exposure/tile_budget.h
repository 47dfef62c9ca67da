#pragma once

#include "raster/screen_triangle.h"
#include "raster/tile_grid.h"
#include "util/stats.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace streak::exposure {

// What the memory budget did in one thread's tiles: rectangles halved because their lists would
// have passed the share, single pixels that passed it all the same and were cut, the items
// (intervals, fragments) those cuts dropped, and the most items a rectangle's list held.
struct TileBudgetCounters {
    std::int64_t splits = 0, pixelsCut = 0, dropped = 0, peakItems = 0;
    // Set by a piece that passed its share (refuse): how many times over the share its whole list
    // would have come to, from how far it got. renderWithinShare cuts it into that many pieces.
    double refusedOver = 0.0;
    void add(const TileBudgetCounters& o) {
        splits += o.splits, pixelsCut += o.pixelsCut, dropped += o.dropped, peakItems = std::max(peakItems, o.peakItems);
    }
    // Notes a list of n items where the method checks it against its share.
    void see(std::size_t n) { peakItems = std::max(peakItems, std::int64_t(n)); }
    // A piece gives up with `items` on its list, over a share of maxItems, after `done` of its
    // `total` inputs (triangle segments, paths): assuming the rest add as the first did, its
    // whole list would be items / maxItems * total / done shares.
    void refuse(std::size_t items, std::size_t maxItems, std::size_t done, std::size_t total) {
        refusedOver = double(items) / double(std::max<std::size_t>(maxItems, 1)) * double(total) / double(std::max<std::size_t>(done, 1));
    }
};

// One thread's share of the memory budget for the lists an exact method builds per tile
// (interval records, fragments, intervals): what the budget leaves above the memory resident when
// the tile pass starts, split over the threads. By then the scene, its geometry and the bins are
// all resident, and what grows with depth and samples is the tile lists, so bounding them bounds
// the process. A method halves a tile whose lists would pass its share and renders the halves one
// after the other (renderWithinShare): every sample's list is the same, so the image does not
// change. Only a single pixel over its share is cut, each of its samples keeping its nearest items
// (keepNearestPerSample): lossy, and counted.
class TileBudget {
public:
    // A share this small at least: a budget the scene alone passes still renders, and the
    // overflow is reported (memory_resident_mb above memory_budget_mb).
    static constexpr std::uint64_t kMinShareBytes = std::uint64_t(4) << 20;

    // budgetMB: the process's budget; shareBytes, when not 0, the share itself (tests).
    TileBudget(std::uint64_t budgetMB, std::uint64_t shareBytes) : m_budgetMB(budgetMB), m_fixedShare(shareBytes) {}

    // Measures what is resident and sets the share; call once the pass's fixed data is built.
    void measure();

    std::uint64_t shareBytes() const { return m_share; }
    // How many items of bytesPerItem one thread's lists may hold. A vector may double its
    // capacity as it grows, so an item counts twice.
    std::size_t maxItems(std::size_t bytesPerItem) const {
        return std::max<std::size_t>(1, std::size_t(m_share / (2 * std::uint64_t(bytesPerItem))));
    }

    // Its figures: memory_budget_mb, memory_resident_mb (at measure), tile_share_mb, the items
    // a list may hold (tile_items_max: maxItems(bytesPerItem)) and held (tile_items_peak), and
    // the counters memory_budget_splits, memory_budget_pixels_cut, memory_budget_dropped.
    void record(RenderStats& stats, const TileBudgetCounters& counters, std::size_t bytesPerItem) const;

private:
    std::uint64_t m_budgetMB, m_fixedShare;
    std::uint64_t m_resident = 0, m_share = kMinShareBytes;
};

template <class Attempt>
void renderWithinShare(const raster::PixelBounds& rect, TileBudgetCounters& counters, Attempt&& attempt);

// Halves rect across its longer side (counted in counters.splits), and each half again while it
// still has more than one of `pieces` to hold and more than one pixel, then renders the parts
// (renderWithinShare).
template <class Attempt>
void renderInPieces(const raster::PixelBounds& rect, double pieces, TileBudgetCounters& counters, Attempt&& attempt) {
    ++counters.splits;
    raster::PixelBounds first = rect, second = rect;
    if (rect.x1 - rect.x0 >= rect.y1 - rect.y0) {
        first.x1 = (rect.x0 + rect.x1) / 2;
        second.x0 = first.x1 + 1;
    } else {
        first.y1 = (rect.y0 + rect.y1) / 2;
        second.y0 = first.y1 + 1;
    }
    for (const raster::PixelBounds& half : {first, second}) {
        const bool isPixel = half.x0 == half.x1 && half.y0 == half.y1;
        if (pieces > 2.0 && !isPixel) renderInPieces(half, 0.5 * pieces, counters, attempt);
        else renderWithinShare(half, counters, attempt);
    }
}

// Renders rect by attempt(subRect, isPixel) -> bool. An attempt that would pass its share stops,
// refuses (counters.refuse: how many shares its whole list would take) and returns false,
// leaving the image alone. Its rectangle is then cut into that many pieces, halving across the
// longer side without attempting the halves between, and each piece is attempted in turn (a
// piece that still passes is cut again). Going straight to the pieces spares the work of the
// attempts a halving at a time would make at every size between. A single pixel is attempted
// with isPixel true, and must then keep within its share by cutting its lists, adding what it
// drops to counters.dropped.
template <class Attempt>
void renderWithinShare(const raster::PixelBounds& rect, TileBudgetCounters& counters, Attempt&& attempt) {
    const bool isPixel = rect.x0 == rect.x1 && rect.y0 == rect.y1;
    const std::int64_t dropped = counters.dropped;
    counters.refusedOver = 0.0;
    const bool fits = attempt(rect, isPixel);
    if (isPixel) {
        if (counters.dropped > dropped) ++counters.pixelsCut;
        return;
    }
    if (fits) return;
    renderInPieces(rect, counters.refusedOver, counters, attempt);
}

// A single pixel's cut: keeps, of each sample's items (item.sample in [0, numSamples)), at
// most perSample (at least 1), those of largest nearness(item), in their order; ties go to the
// first. prepare(run) may first shorten a sample's run in place, returning its new length
// (motion-path drops a path's repeated fragments). The items come back grouped by sample.
// Returns how many the cut dropped (not those prepare did).
template <class Item, class Prepare, class Nearness>
std::size_t keepNearestPerSample(std::vector<Item>& items, std::size_t numSamples, std::size_t perSample, std::vector<std::uint32_t>& runs,
                                 std::vector<Item>& grouped, std::vector<float>& keys, Prepare&& prepare, Nearness&& nearness) {
    perSample = std::max<std::size_t>(perSample, 1);
    raster::groupBySample(std::span<const Item>(items), numSamples, runs, grouped);
    items.clear();
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < numSamples; ++i) {
        std::span<Item> run(grouped.data() + runs[i], runs[i + 1] - runs[i]);
        run = run.first(prepare(run));
        if (run.size() <= perSample) {
            items.insert(items.end(), run.begin(), run.end());
            continue;
        }
        keys.clear();
        for (const Item& item : run) keys.push_back(nearness(item));
        std::nth_element(keys.begin(), keys.begin() + std::ptrdiff_t(perSample - 1), keys.end(), std::greater<float>());
        const float threshold = keys[perSample - 1];
        std::size_t ties = perSample - std::size_t(std::count_if(keys.begin(), keys.end(), [&](float k) { return k > threshold; }));
        for (const Item& item : run) {
            const float key = nearness(item);
            bool isKept = key > threshold;
            if (!isKept && key == threshold && ties > 0) isKept = true, --ties;
            if (isKept) items.push_back(item);
        }
        dropped += run.size() - perSample;
    }
    return dropped;
}

}  // namespace streak::exposure
