// The --aa sample positions against the exact area of a half-plane inside a pixel.
#include "raster/sample_pattern.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

namespace streak::raster {

namespace {

// The area of the unit square where dot(normal, p) < c: the square clipped by the line
// (Sutherland-Hodgman), then the shoelace formula.
double halfPlaneArea(glm::dvec2 normal, double c) {
    const glm::dvec2 square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<glm::dvec2> inside;
    for (int k = 0; k < 4; ++k) {
        const glm::dvec2 a = square[k], b = square[(k + 1) % 4];
        const double fa = glm::dot(normal, a) - c, fb = glm::dot(normal, b) - c;
        if (fa < 0) inside.push_back(a);
        if ((fa < 0) != (fb < 0)) inside.push_back(a + (b - a) * (fa / (fa - fb)));
    }
    double twice = 0;
    for (std::size_t k = 0; k < inside.size(); ++k) {
        const glm::dvec2 a = inside[k], b = inside[(k + 1) % inside.size()];
        twice += a.x * b.y - b.x * a.y;
    }
    return std::abs(twice) / 2;
}

glm::dvec2 pixelFraction(glm::i64vec2 offset) { return glm::dvec2(offset) / double(kSubpixelScale); }

// RMS over seeded random lines through the pixel (uniform angle and point) of the covered
// sample fraction minus the covered area.
double edgeCoverageError(const SamplePattern& pattern) {
    Rng rng(5);
    const int lines = 20000;
    double squares = 0;
    for (int l = 0; l < lines; ++l) {
        const double angle = 2 * std::numbers::pi * rng.uniform();
        const glm::dvec2 normal(std::cos(angle), std::sin(angle));
        const double c = glm::dot(normal, glm::dvec2(rng.uniform(), rng.uniform()));
        int covered = 0;
        for (const glm::i64vec2& offset : pattern.offsets) covered += glm::dot(normal, pixelFraction(offset)) < c;
        const double error = double(covered) / pattern.count() - halfPlaneArea(normal, c);
        squares += error * error;
    }
    return std::sqrt(squares / lines);
}

}  // namespace

TEST(SamplePattern, RooksHasOneSamplePerStratumColumnAndRow) {
    for (int n : {1, 2, 3, 4, 5, 8, 16}) {
        const SamplePattern pattern = SamplePattern::rooks(n);
        ASSERT_EQ(pattern.count(), n * n);
        std::set<std::pair<int, int>> strata;
        std::set<int> columns, rows;
        for (const glm::i64vec2& offset : pattern.offsets) {
            const glm::dvec2 p = pixelFraction(offset);
            strata.insert({int(p.x * n), int(p.y * n)});
            columns.insert(int(p.x * n * n));
            rows.insert(int(p.y * n * n));
        }
        EXPECT_EQ(int(strata.size()), n * n) << "n = " << n;
        EXPECT_EQ(int(columns.size()), n * n) << "n = " << n;
        EXPECT_EQ(int(rows.size()), n * n) << "n = " << n;
    }
}

TEST(SamplePattern, RowsAreEvenlySpacedAndRowsOfNSquaredAreRooksRows) {
    // rows(r): row k at (k + 1/2) / r down the pixel's middle. rows(n^2) has rooks(n)'s rows to
    // the fixed-point unit, so a line tile at --aa n with n^2 rows sees what its points' rows do.
    for (int r : {1, 2, 3, 5, 7, 16, 256}) {
        const SamplePattern pattern = SamplePattern::rows(r);
        ASSERT_EQ(pattern.count(), r);
        for (int k = 0; k < r; ++k) {
            EXPECT_EQ(pattern.offsets[std::size_t(k)].x, kSubpixelScale / 2);
            EXPECT_NEAR(pixelFraction(pattern.offsets[std::size_t(k)]).y, (k + 0.5) / r, 1.0 / kSubpixelScale) << "r = " << r << ", row " << k;
        }
    }
    for (int n : {1, 2, 3, 4, 8}) {
        std::multiset<std::int64_t> rooksRows, rows;
        for (const glm::i64vec2& offset : SamplePattern::rooks(n).offsets) rooksRows.insert(offset.y);
        for (const glm::i64vec2& offset : SamplePattern::rows(n * n).offsets) rows.insert(offset.y);
        EXPECT_EQ(rooksRows, rows) << "n = " << n;
        EXPECT_EQ(SamplePattern::rows(n * n).samplesPerAxis(), n);
    }
}

TEST(SamplePattern, RooksResolvesEdgesAtAnyAngleAboutAsWellAsTheGrid) {
    // The sheared grid x = (i n + j + 1/2) / n^2, y = (j n + i + 1/2) / n^2 is n-rooks too, but
    // its points pair up nearly on top of each other: 1.7x the grid's error at n = 8, 2.3x at
    // n = 16 (the control below). The lattice keeps n-rooks' 1/n^2 on axis-aligned edges
    // (fidelity_test's 3% edge) and stays near the grid at every other angle.
    for (int n : {8, 16}) {
        std::vector<glm::i64vec2> sheared;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sheared.emplace_back(std::int64_t((i * n + j + 0.5) / (n * n) * kSubpixelScale), std::int64_t((j * n + i + 0.5) / (n * n) * kSubpixelScale));
        SamplePattern shearedPattern;
        shearedPattern.offsets = sheared;
        const double grid = edgeCoverageError(SamplePattern::grid(n));
        EXPECT_LT(edgeCoverageError(SamplePattern::rooks(n)), 1.4 * grid) << "n = " << n;
        EXPECT_GT(edgeCoverageError(shearedPattern), 1.6 * grid) << "n = " << n;
    }
}

}  // namespace streak::raster
