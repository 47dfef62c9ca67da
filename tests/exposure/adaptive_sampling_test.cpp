// Which pixels adaptive antialiasing refines (exposure::AdaptiveSampling), from a first pass's
// image and what its samples saw.
#include "exposure/adaptive_sampling.h"

#include <gtest/gtest.h>

#include <vector>

namespace streak::exposure {

namespace {

// A 12 x 8 first pass: dark grey, with a white block over x >= 6 (a vertical edge between
// columns 5 and 6), and full coverage.
Image stepImage() {
    Image image(12, 8, glm::vec3(0.05f));
    for (int y = 0; y < 8; ++y)
        for (int x = 6; x < 12; ++x) image.at(x, y) = glm::vec3(1.0f);
    image.setAlpha(std::vector<float>(12 * 8, 1.0f));
    return image;
}

std::vector<raster::PixelBounds> runsOf(const AdaptiveSampling& marks, const raster::PixelBounds& rect) {
    std::vector<raster::PixelBounds> runs;
    marks.forEachRun(rect, AdaptiveSampling::Level::Full, [&](const raster::PixelBounds& run) { runs.push_back(run); });
    return runs;
}

}  // namespace

TEST(AdaptiveSampling, MarksBothSidesOfAnEdgeAndNothingFlat) {
    const AdaptiveSampling marks(stepImage(), 0.02f, std::nullopt);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 12; ++x) EXPECT_EQ(marks.isMarked(x, y), x == 5 || x == 6) << x << "," << y;
    EXPECT_EQ(marks.numMarked(), 16);
    // One run of two pixels per row, in order.
    const std::vector<raster::PixelBounds> runs = runsOf(marks, {0, 0, 11, 7});
    ASSERT_EQ(runs.size(), 8u);
    for (int y = 0; y < 8; ++y) {
        EXPECT_EQ(runs[std::size_t(y)].x0, 5);
        EXPECT_EQ(runs[std::size_t(y)].x1, 6);
        EXPECT_EQ(runs[std::size_t(y)].y0, y);
        EXPECT_EQ(runs[std::size_t(y)].y1, y);
    }
    // A run is cut where the rectangle (a tile) ends.
    EXPECT_EQ(runsOf(marks, {0, 0, 5, 0}).size(), 1u);
    EXPECT_EQ(runsOf(marks, {0, 0, 5, 0})[0].x1, 5);
    EXPECT_EQ(marks.numSamples(96.0, raster::samplePatternFor(4, false)), 96.0 + 16.0 * 16.0);
}

TEST(AdaptiveSampling, JudgesContrastInSrgbAndCoverage) {
    // 0.004 against 0.0 in linear light is 0.05 apart in sRGB (the eye's and PSNR's scale), and
    // 0.904 against 0.9 only 0.002: the dark step is refined, the bright one not.
    for (const auto& [dark, marked] : {std::pair{0.0f, true}, std::pair{0.9f, false}}) {
        Image image(4, 1, glm::vec3(dark));
        image.at(2, 0) = image.at(3, 0) = glm::vec3(dark + 0.004f);
        const AdaptiveSampling marks(image, 0.02f, std::nullopt);
        EXPECT_EQ(marks.isMarked(1, 0), marked) << dark;
        EXPECT_EQ(marks.isMarked(2, 0), marked) << dark;
        EXPECT_FALSE(marks.isMarked(0, 0));
    }
    // Equal colour, different coverage (a silhouette over a background of the same colour).
    Image image(4, 1, glm::vec3(0.3f));
    image.setAlpha({1.0f, 1.0f, 0.0f, 0.0f});
    const AdaptiveSampling marks(image, 0.02f, std::nullopt);
    EXPECT_TRUE(marks.isMarked(1, 0));
    EXPECT_TRUE(marks.isMarked(2, 0));
    EXPECT_FALSE(marks.isMarked(0, 0));
    EXPECT_FALSE(marks.isMarked(3, 0));
}

TEST(AdaptiveSampling, MarksOnlyInsideTheRegionAndReadsItsBorder) {
    // The region [5, 5] x [0, 7] sees its right neighbour (column 6) across the edge.
    const AdaptiveSampling marks(stepImage(), 0.02f, raster::PixelBounds{5, 0, 5, 7});
    for (int y = 0; y < 8; ++y) {
        EXPECT_TRUE(marks.isMarked(5, y));
        EXPECT_FALSE(marks.isMarked(6, y));
    }
    EXPECT_EQ(marks.numMarked(), 8);
    const std::optional<raster::PixelBounds> grown = AdaptiveSampling::firstPassRegion(raster::PixelBounds{0, 2, 5, 7}, 12, 8);
    ASSERT_TRUE(grown);
    EXPECT_EQ(grown->x0, 0);
    EXPECT_EQ(grown->y0, 1);
    EXPECT_EQ(grown->x1, 6);
    EXPECT_EQ(grown->y1, 7);
    EXPECT_FALSE(AdaptiveSampling::firstPassRegion(std::nullopt, 12, 8));
}

TEST(AdaptiveSampling, RefinesWhereASurfaceNoSampleSawIsMissingAround) {
    // A flat image: no contrast anywhere. Surface A shows in every pixel of the left half;
    // surface B nowhere.
    Image image(12, 8, glm::vec3(0.2f));
    FirstPassGeometry geometry(12, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 6; ++x) geometry.show(x, y, 1, 0);
    // An unseen triangle of A over [2, 4] x [3, 4]: A shows around it, nothing to refine.
    geometry.addUnseen({FirstPassGeometry::keyBit(1, 0), {2, 3, 4, 4}});
    // An unseen one of B (a stroke thinner than a pixel) over [8, 10] x [5, 5], and one of A
    // reaching past where A shows, over [6, 8] x [1, 1].
    geometry.addUnseen({FirstPassGeometry::keyBit(2, 0), {8, 5, 10, 5}});
    geometry.addUnseen({FirstPassGeometry::keyBit(1, 0), {6, 1, 8, 1}});
    const AdaptiveSampling marks(image, 0.02f, std::nullopt, &geometry);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 12; ++x) {
            const bool stroke = y == 5 && x >= 8 && x <= 10;
            const bool pastA = y == 1 && (x == 7 || x == 8);  // column 6 has A at its left
            EXPECT_EQ(marks.isMarked(x, y), stroke || pastA) << x << "," << y;
        }
    RenderStats stats;
    marks.record(stats, 0.02f);
    EXPECT_EQ(stats.counter("adaptive_pixels_unseen_geometry"), 5.0);
    EXPECT_EQ(stats.counter("adaptive_pixels_refined"), 5.0);
    // The same material on another mesh is another surface.
    EXPECT_NE(FirstPassGeometry::keyBit(1, 0), FirstPassGeometry::keyBit(2, 0));
}

TEST(AdaptiveSampling, AMildStepTakesTheCoarsePatternAStrongOneTheFull) {
    // Left to right, full coverage: 0.2 | 0.2 | 0.24 | 0.24 | 0.9 | 0.9 in linear light. In sRGB
    // the first step is 0.485 -> 0.527 (0.043: above 0.02, within 3 x 0.02) and the second
    // 0.527 -> 0.955.
    Image image(6, 3, glm::vec3(0.2f));
    for (int y = 0; y < 3; ++y) {
        image.at(2, y) = image.at(3, y) = glm::vec3(0.24f);
        image.at(4, y) = image.at(5, y) = glm::vec3(0.9f);
    }
    image.setAlpha(std::vector<float>(6 * 3, 1.0f));
    using Level = AdaptiveSampling::Level;
    const AdaptiveSampling graded(image, 0.02f, std::nullopt, nullptr, /*hasCoarse=*/true);
    const Level expected[6] = {Level::None, Level::Coarse, Level::Coarse, Level::Full, Level::Full, Level::None};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 6; ++x) EXPECT_EQ(graded.levelAt(x, y), expected[x]) << x << "," << y;
    EXPECT_EQ(graded.numMarked(), 12);
    EXPECT_EQ(graded.numCoarse(), 6);
    // Each level's runs hold its pixels alone.
    std::vector<raster::PixelBounds> coarse, full;
    graded.forEachRun({0, 0, 5, 2}, Level::Coarse, [&](const raster::PixelBounds& run) { coarse.push_back(run); });
    graded.forEachRun({0, 0, 5, 2}, Level::Full, [&](const raster::PixelBounds& run) { full.push_back(run); });
    ASSERT_EQ(coarse.size(), 3u);
    ASSERT_EQ(full.size(), 3u);
    EXPECT_EQ(coarse[0].x0, 1);
    EXPECT_EQ(coarse[0].x1, 2);
    EXPECT_EQ(full[0].x0, 3);
    EXPECT_EQ(full[0].x1, 4);
    EXPECT_TRUE(graded.anyIn({1, 0, 1, 2}, Level::Coarse));
    EXPECT_FALSE(graded.anyIn({1, 0, 1, 2}, Level::Full));
    // Samples: 18 first, 6 pixels of 2 x 2 and 6 of 4 x 4 at --aa 4.
    EXPECT_EQ(graded.numSamples(18.0, raster::samplePatternFor(4, false)), 18.0 + 6.0 * 4.0 + 6.0 * 16.0);
    RenderStats stats;
    graded.record(stats, 0.02f);
    EXPECT_FLOAT_EQ(stats.counter("adaptive_full_contrast"), 0.06f);
    EXPECT_EQ(stats.counter("adaptive_pixels_refined_coarse"), 6.0);
    // A full contrast of 0.5 holds the second step too; without a coarse level, all are full.
    const AdaptiveSampling loose(image, 0.02f, std::nullopt, nullptr, true, 0.5f);
    EXPECT_EQ(loose.levelAt(3, 1), Level::Coarse);
    EXPECT_EQ(loose.numCoarse(), 12);
    // A full contrast below the threshold is the threshold: every marked pixel full, none lost.
    const AdaptiveSampling below(image, 0.02f, std::nullopt, nullptr, true, 0.01f);
    EXPECT_EQ(below.numMarked(), 12);
    EXPECT_EQ(below.numCoarse(), 0);
    const AdaptiveSampling flat(image, 0.02f, std::nullopt);
    EXPECT_EQ(flat.levelAt(1, 1), Level::Full);
    EXPECT_EQ(flat.numCoarse(), 0);
    EXPECT_EQ(flat.numMarked(), 12);
}

TEST(AdaptiveSampling, ASurfaceTheFirstPassMissedTakesTheFullPatternEvenWhereTheContrastIsMild) {
    Image image(6, 1, glm::vec3(0.2f));
    image.at(3, 0) = image.at(4, 0) = image.at(5, 0) = glm::vec3(0.24f);  // a mild step between 2 and 3
    FirstPassGeometry geometry(6, 1);
    geometry.addUnseen({FirstPassGeometry::keyBit(7, 0), {2, 0, 2, 0}});  // under pixel 2 alone
    const AdaptiveSampling marks(image, 0.02f, std::nullopt, &geometry, true);
    EXPECT_EQ(marks.levelAt(2, 0), AdaptiveSampling::Level::Full);
    EXPECT_EQ(marks.levelAt(3, 0), AdaptiveSampling::Level::Coarse);
    EXPECT_EQ(marks.numMarked(), 2);
    EXPECT_EQ(marks.numCoarse(), 1);
    RenderStats stats;
    marks.record(stats, 0.02f);
    EXPECT_EQ(stats.counter("adaptive_pixels_unseen_geometry"), 0.0);  // it was refined for its contrast too
}

TEST(AdaptiveSampling, TheCoarsePatternHasHalfTheSamplesASideAndTheFullOnesKind) {
    EXPECT_EQ(AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(8, false)).samplesPerAxis(), 4);
    EXPECT_EQ(AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(4, false)).samplesPerAxis(), 2);
    EXPECT_EQ(AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(3, false)).samplesPerAxis(), 2);
    EXPECT_EQ(AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(5, false)).samplesPerAxis(), 2);
    const raster::SamplePattern grid = AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(6, true));
    EXPECT_TRUE(grid.isGrid());
    EXPECT_EQ(grid.offsets, raster::samplePatternFor(3, true).offsets);
    EXPECT_EQ(AdaptiveSampling::coarsePatternOf(raster::samplePatternFor(4, false)).offsets, raster::samplePatternFor(2, false).offsets);
    EXPECT_TRUE(AdaptiveSampling::hasCoarseLevel(raster::samplePatternFor(3, false)));
    EXPECT_FALSE(AdaptiveSampling::hasCoarseLevel(raster::samplePatternFor(2, false)));
    EXPECT_FLOAT_EQ(AdaptiveSampling::fullContrastFor(0.02f, 0.0f), 0.06f);
    EXPECT_FLOAT_EQ(AdaptiveSampling::fullContrastFor(0.02f, 0.3f), 0.3f);
    EXPECT_FLOAT_EQ(AdaptiveSampling::fullContrastFor(0.02f, 0.01f), 0.02f);
}

}  // namespace streak::exposure
