#include "exposure/tile_budget.h"

#include "util/memory.h"

#include <tbb/task_arena.h>

namespace streak::exposure {

void TileBudget::measure() {
    m_resident = residentBytes();
    if (m_fixedShare > 0) {
        m_share = m_fixedShare;
        return;
    }
    const std::uint64_t budget = m_budgetMB << 20;
    const std::uint64_t threads = std::uint64_t(std::max(1, tbb::this_task_arena::max_concurrency()));
    const std::uint64_t left = budget > m_resident ? budget - m_resident : 0;
    m_share = std::max(kMinShareBytes, left / threads);
}

void TileBudget::record(RenderStats& stats, const TileBudgetCounters& counters, std::size_t bytesPerItem) const {
    constexpr double kMB = 1024.0 * 1024.0;
    stats.setCounter("memory_budget_mb", double(m_budgetMB));
    stats.setCounter("memory_resident_mb", double(m_resident) / kMB);
    stats.setCounter("tile_share_mb", double(m_share) / kMB);
    stats.setCounter("tile_items_max", double(maxItems(bytesPerItem)));
    stats.setCounter("tile_items_peak", double(counters.peakItems));
    stats.setCounter("memory_budget_splits", double(counters.splits));
    stats.setCounter("memory_budget_pixels_cut", double(counters.pixelsCut));
    stats.setCounter("memory_budget_dropped", double(counters.dropped));
}

}  // namespace streak::exposure
