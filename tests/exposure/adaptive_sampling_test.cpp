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
    marks.forEachRun(rect, [&](const raster::PixelBounds& run) { runs.push_back(run); });
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

}  // namespace streak::exposure
