#include "exposure/sample_resolve.h"

namespace streak::exposure {

void recordResolveStats(RenderStats& stats, const SampleResolveCounters& r, double intervalSeconds, double numSamples, double numPixels,
                        int budget, const PixelShadingOptions& shading) {
    // Tile work runs on all threads at once: split the tiles' wall time by thread time.
    const double threadTime = intervalSeconds + r.resolveSeconds + r.shadeSeconds;
    const double scale = threadTime > 0.0 ? stats.time("tiles") / threadTime : 0.0;
    stats.addTime("intervals", intervalSeconds * scale);
    stats.addTime("resolve", r.resolveSeconds * scale);
    stats.addTime("shade", r.shadeSeconds * scale);
    stats.setCounter("intervals", double(r.intervals));
    stats.setCounter("intervals_per_sample_mean", double(r.intervals) / numSamples);
    stats.setCounter("intervals_per_sample_max", double(r.maxIntervals));
    stats.setCounter("max_intervals", budget);
    stats.setCounter("compressed_samples", double(r.compressedSamples));
    stats.setCounter("resolved_intervals_max", double(r.maxResolved));
    stats.setCounter("merges", double(r.merges));
    stats.setCounter("hidden_intervals_culled", double(r.hiddenCulled));
    recordPixelShadingStats(stats, r.shading, numPixels, shading);
}

}  // namespace streak::exposure
