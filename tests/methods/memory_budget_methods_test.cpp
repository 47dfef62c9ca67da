// The memory budget in the exact methods: a scene whose tiles' lists pass a thread's share
// renders in halved tiles to the same image, and where even a single pixel passes it, its
// samples keep their nearest intervals, the cut is counted, and the image stays within 1 dB of
// the unbounded one against an independent reference (accumulation).

#include "image/metrics.h"
#include "methods/registry.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace streak {
namespace {

constexpr int kWidth = 32, kHeight = 24, kAa = 2;

// A deep stack: six narrow strips sliding across the whole image in front of forty static
// full-image quads, each its own colour. Every sample holds about fifty intervals; what shows is
// the strips (two intervals each, one per triangle, where a strip slides over the sample) and the
// nearest full quad, so a sample's fourteen nearest intervals hold all it shows. (At nine, as a
// cut share of 14000 bytes leaves analytic, the nearest quad is cut where strips pass: 13.9 dB.)
Scene deepStack() {
    Scene scene = test::emptyScene({0.1f, 0.1f, 0.1f});
    for (int k = 0; k < 6; ++k) {
        const test::PixelCamera cam{kWidth, kHeight, 2.0f + 0.1f * float(k)};
        const std::uint32_t m = test::addMaterial(scene, {0.15f * float(k), 1.0f - 0.15f * float(k), 0.5f});
        const float x0 = -6.0f - 3.0f * float(k);
        test::addPixelQuad(scene, cam, m, x0, -2.0f, x0 + 2.5f, float(kHeight) + 2.0f, float(kWidth) + 12.0f, 0.0f);
    }
    for (int j = 0; j < 40; ++j) {
        const test::PixelCamera cam{kWidth, kHeight, 3.0f + 0.05f * float(j)};
        const std::uint32_t m = test::addMaterial(scene, {0.9f - 0.02f * float(j), 0.2f + 0.015f * float(j), 0.05f * float(j % 5)});
        test::addPixelQuad(scene, cam, m, -4.0f, -4.0f, float(kWidth) + 4.0f, float(kHeight) + 4.0f);
    }
    validateScene(scene);
    return scene;
}

Image renderWithShare(const std::string& method, const Scene& scene, std::uint64_t shareBytes, RenderStats& stats) {
    OptionMap options;
    if (method == "accumulation") options.set("samples", "1024");
    // analytic would not solve the still quads behind the first, nor motion-path build them
    // (their early cull): the lists must be deep for the budget to split and cut them.
    if (method == "analytic" || method == "motion-path") options.set("early-cull", "0");
    std::unique_ptr<Renderer> renderer = createRenderer(method, options);
    RenderSettings settings;
    settings.width = kWidth, settings.height = kHeight, settings.aa = kAa, settings.shading = ShadingMode::Unlit;
    settings.tileShareBytes = shareBytes;
    RenderContext context{stats};
    return renderer->render(scene, settings, context);
}

struct Case {
    const char* method;
    std::uint64_t splitShare;  ///< bytes: a tile's lists pass it, a pixel's fit
    std::uint64_t cutShare;    ///< bytes: a pixel's lists pass it too
};

TEST(MemoryBudget, HalvedTilesGiveTheSameImageAndCutPixelsStayWithinADecibel) {
    const Scene scene = deepStack();
    RenderStats referenceStats;
    const Image reference = renderWithShare("accumulation", scene, 0, referenceStats);
    // Item sizes differ (records of 44 bytes, fragments counted at 156 with what they become),
    // so each method gets its own shares. A cut pixel keeps per sample a share of
    // tile_items_max / 8: 17 records (analytic, higher-order) or 20 paths (motion-path).
    for (const Case& c : {Case{"analytic", 200000, 24000}, Case{"higher-order", 200000, 24000}, Case{"motion-path", 2500000, 50000}}) {
        SCOPED_TRACE(c.method);
        RenderStats unboundedStats, splitStats, cutStats;
        const Image unbounded = renderWithShare(c.method, scene, 0, unboundedStats);
        const Image split = renderWithShare(c.method, scene, c.splitShare, splitStats);
        const Image cut = renderWithShare(c.method, scene, c.cutShare, cutStats);

        EXPECT_EQ(unboundedStats.counter("memory_budget_splits"), 0.0);
        // Halved tiles: every sample's list is the same, so is the image, to the bit.
        EXPECT_GT(splitStats.counter("memory_budget_splits"), 0.0);
        EXPECT_EQ(splitStats.counter("memory_budget_dropped"), 0.0);
        EXPECT_TRUE(std::equal(split.pixels().begin(), split.pixels().end(), unbounded.pixels().begin(), unbounded.pixels().end()));
        // The lists held under a tenth as much, and within the share but for the one segment
        // (path) added after the last check: at most a tile's samples' worth.
        const double tileSamples = (c.method == std::string("motion-path") ? 32.0 * 32.0 : 16.0 * 16.0) * kAa * kAa;
        EXPECT_LT(splitStats.counter("tile_items_peak"), 0.1 * unboundedStats.counter("tile_items_peak"));
        EXPECT_LE(splitStats.counter("tile_items_peak"), splitStats.counter("tile_items_max") + 8.0 * tileSamples);

        // Cut pixels: counted, and the image as close to the reference as the unbounded one.
        EXPECT_GT(cutStats.counter("memory_budget_pixels_cut"), 0.0);
        EXPECT_GT(cutStats.counter("memory_budget_dropped"), 0.0);
        EXPECT_LE(cutStats.counter("tile_items_peak"), cutStats.counter("tile_items_max") + 8.0 * tileSamples);
        const double unboundedPsnr = psnr(unbounded, reference), cutPsnr = psnr(cut, reference);
        EXPECT_GE(unboundedPsnr, 35.0);
        EXPECT_GE(cutPsnr, unboundedPsnr - 1.0);
    }
}

}  // namespace
}  // namespace streak
