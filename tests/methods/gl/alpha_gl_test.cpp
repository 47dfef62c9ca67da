// The GL methods' alpha (the coverage behind --transparent), held to what the CPU methods' is
// (support/alpha_scene.h), and their normal pass (ShadingMode::Normal) against their CPU twins'.

#include "scene/builtin_scenes.h"
#include "support/alpha_scene.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace streak {

TEST(AlphaGl, EveryGlMethodGivesTheCoverageOfItsOwnColour) {
    test::expectAlphaIsCoverage("motion-path-gl", OptionMap(), 1e-5f);
    test::expectAlphaIsCoverage("accumulation-gl", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f);
    test::expectAlphaIsCoverage("stochastic-gl", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f);
    test::expectAlphaIsCoverage("blur-shell-gl", OptionMap(), -1.0f);
    test::expectAlphaIsCoverage("post-filter-gl", OptionMap(), -1.0f);
}

TEST(NormalGl, EveryGlMethodShadesTheNormalAsItsCpuTwin) {
    // A turning cube: unit normals that change over the shutter and across faces. The twins
    // share samples (the grid for accumulation-gl) and times, so they agree but for rounding and
    // the rasterizers' tie-breaks on edges: few pixels off, none by much on average.
    const Scene scene = test::validBuiltin("rotating-cube");
    const std::pair<const char*, const char*> twins[] = {{"motion-path-gl", "motion-path"}, {"accumulation-gl", "accumulation"},
                                                         {"stochastic-gl", "stochastic"}, {"post-filter-gl", "post-filter"}};
    for (const auto& [gl, cpu] : twins) {
        SCOPED_TRACE(gl);
        const OptionMap options = std::string(cpu) == "accumulation" || std::string(cpu) == "stochastic" ? test::withOption("samples", "8") : OptionMap();
        const bool grid = std::string(gl) == "accumulation-gl" || std::string(gl) == "post-filter-gl";
        const Image a = test::render(gl, scene, 48, 36, options, nullptr, ShadingMode::Normal, 2, grid);
        const Image b = test::render(cpu, scene, 48, 36, options, nullptr, ShadingMode::Normal, 2, grid);
        double sum = 0.0, largestLength = 0.0;
        for (std::size_t i = 0; i < a.pixels().size(); ++i) {
            for (int c = 0; c < 3; ++c) sum += std::abs(double(a.pixels()[i][c]) - double(b.pixels()[i][c]));
            largestLength = std::max(largestLength, double(std::sqrt(glm::dot(a.pixels()[i], a.pixels()[i]))));
        }
        EXPECT_LT(sum / double(3 * a.pixels().size()), 2e-3);
        EXPECT_LE(largestLength, 1.0 + 1e-4);  // unit normals, averaged: never longer than 1
        EXPECT_GT(largestLength, 0.9);         // and not the albedo or Phong by mistake: some face head-on
    }
}

}  // namespace streak
